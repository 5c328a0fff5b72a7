#pragma once
// The `estimator.slam:` section of a robot config (every key optional; docs/configuration.md).

#include "mrslam/common/config.hpp"
#include "mrslam/robot/slam/slam_estimator.hpp"

namespace mrslam::robot::slam {

/// Reads the section over the defaults of SlamSettings (its `ekf` is left as given); throws
/// ConfigError (`file:line: key: what is wrong`).
SlamSettings loadSlamSettings(const Config& section, SlamSettings settings = {});

}  // namespace mrslam::robot::slam
