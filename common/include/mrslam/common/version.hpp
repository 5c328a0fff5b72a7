#pragma once
// The project's version (CMake's project VERSION), for every program's --version.

#include <string>

namespace mrslam {

/// "mrslam <program> <version>".
std::string versionLine(const std::string& program);

}  // namespace mrslam
