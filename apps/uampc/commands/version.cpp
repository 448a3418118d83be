// A file of its own so that a new version (each commit changes it) recompiles only this file.
#include "commands/version.hpp"

#include <fastrtps/config.h>

#include "uampc_version.hpp"  // generated in the build tree by cmake/UampcVersion.cmake

namespace uampc::app {

std::string uampcVersion() { return UAMPC_VERSION; }

std::string fastDdsVersion() { return FASTRTPS_VERSION_STR; }

std::string versionText() { return "uampc " + uampcVersion() + "\nFast DDS " + fastDdsVersion(); }

}  // namespace uampc::app
