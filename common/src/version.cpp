#include "mrslam/common/version.hpp"

namespace mrslam {

std::string versionLine(const std::string& program) {
  return "mrslam " + program + " " + MRSLAM_VERSION;
}

}  // namespace mrslam
