#include "mrslam/robot/robot_config.hpp"

#include "mrslam/common/shutdown.hpp"
#include "mrslam/drivers/breezyslam_reader.hpp"
#include "mrslam/drivers/carmen_reader.hpp"
#include "mrslam/drivers/log_format.hpp"

namespace mrslam::robot {

namespace {

DeviceFallback loadFallback(const Config& device) {
  return device.getChoice("fallback", "replay", {"replay", "none"}) == "none"
             ? DeviceFallback::kNone
             : DeviceFallback::kReplay;
}

// source.devices: laser (Hokuyo), imu (3DM-GX1), encoders (Phidget), each optional, each with
// its fallback; replay_log feeds the fallbacks.
DeviceSourceSettings loadDevices(const Config& section) {
  DeviceSourceSettings devices;
  devices.replay_log = section.getPath("replay_log", "");
  devices.reopen_period_s =
      section.getDouble("reopen_period_s", devices.reopen_period_s, {0.01, 3600.0});
  devices.reorder_window_s =
      section.getDouble("reorder_window_s", devices.reorder_window_s, {0.0, 5.0});
  if (section.has("laser")) {
    devices.laser = drivers::loadHokuyoSettings(section.section("laser"));
    devices.laser_fallback = loadFallback(section.section("laser"));
  }
  if (section.has("imu")) {
    devices.imu = drivers::Gx1Settings::fromConfig(section.section("imu"));
    devices.imu_fallback = loadFallback(section.section("imu"));
  }
  if (section.has("encoders")) {
    devices.encoders = drivers::PhidgetEncoderSettings::fromConfig(section.section("encoders"));
    devices.encoders_fallback = loadFallback(section.section("encoders"));
  }
  if (!devices.laser && !devices.imu && !devices.encoders) {
    section.fail("laser", "a devices source needs at least one of laser, imu, encoders");
  }
  return devices;
}

SourceSettings loadSource(const Config& section) {
  SourceSettings source;
  const std::string type = section.getChoice(
      "type", "simulator", {"simulator", "log", "breezyslam", "carmen", "devices"});
  source.type = type == "simulator"    ? SourceType::kSimulator
                : type == "log"        ? SourceType::kLog
                : type == "breezyslam" ? SourceType::kBreezySlam
                : type == "devices"    ? SourceType::kDevices
                                       : SourceType::kCarmen;
  if (source.type == SourceType::kDevices) {
    source.devices = loadDevices(section.section("devices"));
  }
  source.path = section.getPath("path", "");  // may be left to the command line (--log)
  source.malformed = section.getChoice("malformed", "skip", {"skip", "stop"}) == "stop"
                         ? drivers::MalformedPolicy::kStop
                         : drivers::MalformedPolicy::kSkip;
  const std::vector<double> noise =
      section.getDoubles("odometry_noise", {0.0, 0.0}, 2, {0.0, 100.0});
  source.odometry_noise.distance_fraction = noise[0];
  source.odometry_noise.deg_per_m = noise[1];
  source.odometry_noise.seed = static_cast<std::uint64_t>(section.getInt("seed", 1, {0, 9.0e15}));
  return source;
}

DiffDriveParams loadPlatform(const Config& section) {
  DiffDriveParams platform;
  platform.wheel_radius_m =
      section.getDouble("wheel_radius_m", platform.wheel_radius_m, {1e-3, 2.0});
  platform.track_width_m = section.getDouble("track_width_m", platform.track_width_m, {1e-2, 5.0});
  platform.ticks_per_revolution =
      section.getDouble("ticks_per_revolution", platform.ticks_per_revolution, {1.0, 1e7});
  return platform;
}

SensorMounting loadMounting(const Config& laser, const Config& imu) {
  SensorMounting mounting;
  mounting.T_robot_laser =
      SE2(laser.getDouble("x_m", 0.0, {-5.0, 5.0}), laser.getDouble("y_m", 0.0, {-5.0, 5.0}),
          laser.getDouble("yaw_rad", 0.0, {-M_PI, M_PI}));
  mounting.imu_yaw_offset_rad = imu.getDouble("yaw_offset_rad", 0.0, {-M_PI, M_PI});
  return mounting;
}

OdometryNoise loadOdometryNoise(const Config& section) {
  OdometryNoise noise;
  noise.translation_per_m =
      section.getDouble("translation_per_m", noise.translation_per_m, {0.0, 10.0});
  noise.rotation_per_rad =
      section.getDouble("rotation_per_rad", noise.rotation_per_rad, {0.0, 10.0});
  noise.rotation_per_m = section.getDouble("rotation_per_m", noise.rotation_per_m, {0.0, 10.0});
  return noise;
}

MappingSettings loadMapping(const Config& section) {
  MappingSettings mapping;
  mapping.resolution_m = section.getDouble("resolution_m", mapping.resolution_m, {0.005, 5.0});
  mapping.max_range_m = section.getDouble("max_range_m", mapping.max_range_m, {0.0, 200.0});
  mapping.clearing_range_m =
      section.getDouble("clearing_range_m", mapping.clearing_range_m, {0.0, 200.0});
  const Config log_odds = section.section("log_odds");
  LogOddsParams& params = mapping.log_odds;
  params.hit = static_cast<float>(log_odds.getDouble("hit", params.hit, {0.01, 10.0}));
  params.miss = static_cast<float>(log_odds.getDouble("miss", params.miss, {-10.0, -0.01}));
  params.clamp_min =
      static_cast<float>(log_odds.getDouble("clamp_min", params.clamp_min, {-50.0, -0.1}));
  params.clamp_max =
      static_cast<float>(log_odds.getDouble("clamp_max", params.clamp_max, {0.1, 50.0}));
  return mapping;
}

void loadPublish(const Config& section, RobotConfig& config) {
  RunnerSettings& runner = config.runner;
  runner.speed = section.getDouble("speed", runner.speed, {0.0, 1000.0});
  runner.max_replay_gap_s =
      section.getDouble("max_replay_gap_s", runner.max_replay_gap_s, {0.0, 86400.0});
  runner.map_period_s = section.getDouble("map_period_s", runner.map_period_s, {0.0, 3600.0});
  runner.status_period_s =
      section.getDouble("status_period_s", runner.status_period_s, {0.0, 3600.0});
  runner.trajectory_points = static_cast<std::size_t>(section.getInt(
      "trajectory_points", static_cast<long long>(runner.trajectory_points), {0, 1e6}));
  config.delivery_readers =
      static_cast<int>(section.getInt("delivery_readers", config.delivery_readers, {0, 64}));
  config.delivery_timeout_s =
      section.getDouble("delivery_timeout_s", config.delivery_timeout_s, {0.0, 3600.0});
}

}  // namespace

RobotConfig loadRobotConfig(const std::string& path) {
  const Config config = Config::loadFile(path);
  RobotConfig robot;
  robot.robot_id = config.requireString("robot_id");
  if (!isValidRobotId(robot.robot_id)) {
    config.fail("robot_id", "'" + robot.robot_id + "' is not a robot id (1-64 of A-Z a-z 0-9 _ -)");
  }
  robot.source = loadSource(config.section("source"));
  robot.simulator = drivers::loadSimulatorSettings(config.section("simulator"));
  robot.sightings = drivers::loadSightingSettings(config.section("simulator").section("sightings"));
  robot.platform = loadPlatform(config.section("platform"));
  robot.mounting = loadMounting(config.section("laser"), config.section("imu"));
  robot.laser_mounting_unset = !config.has("laser");
  robot.odometry_noise = loadOdometryNoise(config.section("odometry_noise"));
  robot.estimator = loadEstimatorSettings(config.section("estimator"));
  robot.estimator.ekf.odometry = robot.odometry_noise;
  robot.mapping = loadMapping(config.section("mapping"));
  loadPublish(config.section("publish"), robot);
  robot.dds = loadDdsSettings(config.section("dds"));
  config.checkNoUnknownKeys();
  return robot;
}

namespace {

drivers::CarmenSettings carmenSettings(const SourceSettings& source) {
  drivers::CarmenSettings settings;
  settings.path = source.path;
  settings.malformed_policy = source.malformed;
  return settings;
}

std::unique_ptr<drivers::SampleSource> openUnwrappedSource(const RobotConfig& config) {
  const SourceSettings& source = config.source;
  const bool needs_log =
      source.type != SourceType::kSimulator && source.type != SourceType::kDevices;
  if (needs_log && source.path.empty()) {
    throw std::runtime_error("source.path: a log source needs the path of its log (--log)");
  }
  switch (source.type) {
    case SourceType::kSimulator:
      if (!config.sightings.robots.empty()) {
        return std::make_unique<drivers::SightingSimulator>(config.simulator, config.sightings,
                                                            config.platform, config.mounting);
      }
      return std::make_unique<drivers::Simulator>(config.simulator, config.platform,
                                                  config.mounting);
    case SourceType::kDevices:
      return std::make_unique<DeviceSource>(source.devices, shutdownRequested());
    case SourceType::kLog:
      return drivers::openLogReader(source.path, source.malformed);
    case SourceType::kBreezySlam: {
      drivers::BreezySlamSettings settings;
      settings.path = source.path;
      settings.malformed_policy = source.malformed;
      return std::make_unique<drivers::BreezySlamReader>(settings);
    }
    case SourceType::kCarmen:
      return std::make_unique<drivers::CarmenReader>(carmenSettings(source));
  }
  throw std::logic_error("unknown source type");
}

}  // namespace

std::unique_ptr<drivers::SampleSource> openSource(const RobotConfig& config) {
  auto source = openUnwrappedSource(config);
  if (config.source.odometry_noise.enabled()) {
    return std::make_unique<drivers::OdometryNoiseSource>(std::move(source),
                                                          config.source.odometry_noise);
  }
  return source;
}

std::optional<SE2> applyLogLaserMounting(RobotConfig& config) {
  if (!config.laser_mounting_unset || config.source.type != SourceType::kCarmen ||
      config.source.path.empty()) {
    return std::nullopt;
  }
  const std::optional<SE2> mounting =
      drivers::CarmenReader(carmenSettings(config.source)).laserMounting();
  if (mounting) {
    config.mounting.T_robot_laser = *mounting;
  }
  return mounting;
}

std::unique_ptr<PoseEstimator> makeEstimator(const RobotConfig& config, EstimatorType type) {
  if (type == EstimatorType::kOdometry) {
    return std::make_unique<OdometryEstimator>(config.platform, config.odometry_noise);
  }
  EkfSettings ekf = config.estimator.ekf;
  ekf.odometry = config.odometry_noise;
  if (type == EstimatorType::kSlam) {
    slam::SlamSettings settings = config.estimator.slam;
    settings.ekf = ekf;
    settings.ekf.odometry = settings.odometry;
    return std::make_unique<slam::SlamEstimator>(config.platform, config.mounting, settings);
  }
  return std::make_unique<EkfEstimator>(config.platform, config.mounting, ekf);
}

std::unique_ptr<RobotPipeline> makePipeline(const RobotConfig& config) {
  return makePipeline(config, config.estimator.type);
}

std::unique_ptr<RobotPipeline> makePipeline(const RobotConfig& config, EstimatorType type) {
  return std::make_unique<RobotPipeline>(config.mapping, config.mounting,
                                         makeEstimator(config, type));
}

}  // namespace mrslam::robot
