// `uampc --version`: which uampc this is and which Fast DDS it speaks.
#pragma once

#include <string>

namespace uampc::app {

// Two lines, "uampc <git describe at build time>" and "Fast DDS <version>", no final newline.
std::string versionText();

}  // namespace uampc::app
