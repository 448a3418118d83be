// A file of its own so that a new version (each commit changes it) recompiles only this file.
#include "version.hpp"

#include <fastrtps/config.h>

#include "uampc_version.hpp"  // generated in the build tree by cmake/UampcVersion.cmake

namespace uampc::app {

std::string versionText() { return std::string("uampc ") + UAMPC_VERSION + "\nFast DDS " + FASTRTPS_VERSION_STR; }

}  // namespace uampc::app
