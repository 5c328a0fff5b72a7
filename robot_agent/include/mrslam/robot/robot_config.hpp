#pragma once
// The robot agent's configuration (config/<robot>.yaml), validated on load, and the sample
// source it names.

#include <memory>
#include <optional>
#include <string>

#include "mrslam/common/dds_settings.hpp"
#include "mrslam/common/platform.hpp"
#include "mrslam/drivers/odometry_noise.hpp"
#include "mrslam/drivers/sample_source.hpp"
#include "mrslam/drivers/sighting_simulator.hpp"
#include "mrslam/drivers/simulator.hpp"
#include "mrslam/robot/device_source.hpp"
#include "mrslam/robot/estimator_config.hpp"
#include "mrslam/robot/grid_mapper.hpp"
#include "mrslam/robot/odometry_estimator.hpp"
#include "mrslam/robot/robot_runner.hpp"

namespace mrslam::robot {

enum class SourceType { kSimulator, kLog, kBreezySlam, kCarmen, kDevices };

struct SourceSettings {
  SourceType type = SourceType::kSimulator;  ///< where the samples come from
  std::string path;  ///< the log (log, breezyslam, carmen), relative to the config file; may be
                     ///< empty in the file and given on the command line
  drivers::MalformedPolicy malformed = drivers::MalformedPolicy::kSkip;  ///< malformed lines
  /// Seeded noise added to the log's odometry poses (`odometry_noise: [f, deg_per_m]`, `seed`);
  /// off by default. For logs whose odometry is perfect (the corrected CARMEN logs).
  drivers::OdometryNoiseSettings odometry_noise;
  DeviceSourceSettings devices;  ///< type devices: the robot's own devices and their fallbacks
};

struct RobotConfig {
  std::string robot_id;  ///< the robot's name on DDS and in files
  SourceSettings source;
  drivers::SimulatorSettings simulator;
  drivers::SightingSettings sightings;  ///< simulator.sightings: teammates it can see
  DiffDriveParams platform;
  SensorMounting mounting;
  bool laser_mounting_unset = false;  ///< no `laser:` section: the log's mounting is taken
  OdometryNoise odometry_noise;       ///< odometry increments' noise (both estimators use it)
  EstimatorSettings estimator;
  MappingSettings mapping;
  RunnerSettings runner;
  DdsSettings dds;
  int delivery_readers = 1;          ///< map readers (fusion agents) to wait for at the end
  double delivery_timeout_s = 30.0;  ///< how long to wait for them to take the final map
};

/// Loads and validates a robot config; throws ConfigError (`file:line: key: what is wrong`).
RobotConfig loadRobotConfig(const std::string& path);

/// Opens the configured source, wrapped in an OdometryNoiseSource when source.odometry_noise is
/// on. Throws std::runtime_error when it cannot be opened.
std::unique_ptr<drivers::SampleSource> openSource(const RobotConfig& config);

/// When the config left the laser mounting unset and its source is a CARMEN log, sets
/// mounting.T_robot_laser to the one the log records (CarmenReader::laserMounting) and returns
/// it; nothing otherwise. Opens the log (std::runtime_error when it cannot).
std::optional<SE2> applyLogLaserMounting(RobotConfig& config);

/// The estimator of `type` with the config's platform, mounting and settings.
std::unique_ptr<PoseEstimator> makeEstimator(const RobotConfig& config, EstimatorType type);

/// The pipeline the config describes, with config.estimator.type as its estimator.
std::unique_ptr<RobotPipeline> makePipeline(const RobotConfig& config);
/// The pipeline the config describes, with an estimator of `type`.
std::unique_ptr<RobotPipeline> makePipeline(const RobotConfig& config, EstimatorType type);

}  // namespace mrslam::robot
