// A parameter's value from its text, as a scene file or `--set NAME=VALUE` writes it (a YAML
// scalar or flow list), checked against its declaration as the scene validator checks it: type,
// finite numbers, bounds (0 too where it switches off), choices, existing files.
#pragma once

#include <string>

#include "uampc/runtime/parameter.hpp"

namespace uampc {

// Throws std::invalid_argument("parameter 'NAME': what is wrong") when the text is not a value the
// declaration allows. A relative path is made absolute from the working directory.
ParameterValue parseParameterValue(const ParameterSpec& spec, const std::string& text);

}  // namespace uampc
