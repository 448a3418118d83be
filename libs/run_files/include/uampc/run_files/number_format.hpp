// How the run files print numbers: the shortest text that reads back as the same double.
#pragma once

#include <string>

namespace uampc::run_files {

// "nan", "inf" and "-inf" for those (what numpy and pandas read).
std::string formatDouble(double value);

}  // namespace uampc::run_files
