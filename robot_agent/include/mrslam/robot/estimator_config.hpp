#pragma once
// The `estimator:` section of a robot config: which pose estimator, and the EKF's settings.

#include <memory>
#include <string>

#include "mrslam/common/config.hpp"
#include "mrslam/robot/ekf_estimator.hpp"
#include "mrslam/robot/slam/slam_estimator.hpp"

namespace mrslam::robot {

enum class EstimatorType {
  kOdometry,  ///< dead reckoning (OdometryEstimator)
  kEkf,       ///< the cascaded EKF with scan matching and IMU (EkfEstimator)
  kSlam,      ///< submaps, pose graph and loop closure with the EKF in front (SlamEstimator)
};

struct EstimatorSettings {
  EstimatorType type = EstimatorType::kEkf;  ///< which estimator the pipeline runs
  EkfSettings ekf;                           ///< the EKF's settings (odometry noise: top level)
  slam::SlamSettings slam;                   ///< the SLAM's settings (its ekf: the above)
};

/// "odometry", "ekf" or "slam".
const char* estimatorTypeName(EstimatorType type);
/// Parses "odometry", "ekf" or "slam"; throws std::invalid_argument otherwise.
EstimatorType parseEstimatorType(const std::string& name);

/// Reads the `estimator:` section (every key optional); throws ConfigError.
EstimatorSettings loadEstimatorSettings(const Config& section);

}  // namespace mrslam::robot
