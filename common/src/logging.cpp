#include "mrslam/common/logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace mrslam {

void logToStandardError(const std::string& program) {
  const spdlog::level::level_enum level = spdlog::get_level();
  spdlog::set_default_logger(spdlog::stderr_color_mt(program));
  spdlog::set_level(level);
}

}  // namespace mrslam
