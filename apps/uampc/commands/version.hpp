// `uampc --version`: which uampc this is and which Fast DDS it speaks.
#pragma once

#include <string>

namespace uampc::app {

// git describe of the source tree when uampc was built ("unknown" outside git).
std::string uampcVersion();
// The Fast DDS uampc was built with ("2.9.1").
std::string fastDdsVersion();
// Two lines, "uampc <uampcVersion()>" and "Fast DDS <fastDdsVersion()>", no final newline.
std::string versionText();

}  // namespace uampc::app
