// robot_agent: reads one robot's sensors (devices, a log or the simulator), estimates its pose,
// builds its occupancy grid and publishes pose, map and status on DDS.
//
// Replay of a log without a config: `robot_agent LOG --config-dir config [--no-dds] ...` takes
// config/carmen.yaml or config/breezyslam.yaml by the log's format (what `./mrslam replay` runs).

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <optional>

#include "mrslam/common/logging.hpp"
#include "mrslam/common/map_io.hpp"
#include "mrslam/common/shutdown.hpp"
#include "mrslam/common/version.hpp"
#include "mrslam/drivers/log_format.hpp"
#include "mrslam/drivers/mrslam_log.hpp"
#include "mrslam/robot/robot_config.hpp"
#include "mrslam/robot/trajectory_io.hpp"
#include "robot_node.hpp"

namespace {

using mrslam::robot::RobotConfig;

// Sends nothing anywhere: --no-dds.
class NoOutput : public mrslam::robot::RobotOutput {
 public:
  void publishPose(mrslam::Stamp, const mrslam::SE2&, const Eigen::Matrix3d&) override {}
  void publishMap(const mrslam::robot::MapSnapshot&) override {}
  void publishStatus(const mrslam::robot::StatusReport&) override {}
  bool wantsMaps() const override { return false; }
};

struct Options {
  std::string config_path;
  std::string config_dir = "config";
  std::string robot_id;
  int domain = -1;
  int delivery_readers = -1;
  std::string discovery_server;
  std::string security_dir;
  std::string security_identity;
  double speed = -1.0;
  std::string log;
  std::string positional_log;
  std::string estimator;
  std::string odom_noise;
  long long seed = -1;
  std::string out;
  std::string trajectory_out;
  std::string record;
  bool no_dds = false;
};

// The EKF's counters, once at the end of a run.
void logEkfSummary(const std::string& robot_id, const mrslam::robot::EkfEstimator& ekf) {
  const mrslam::robot::EkfCounters& c = ekf.counters();
  spdlog::info(
      "{}: EKF: {} scans, {} matches accepted, {} gated out, {} failed; {} keyframes; IMU "
      "heading {}/{} and yaw rate {}/{} accepted/gated, {} heading recoveries, {} late IMU "
      "samples dropped, {} IMU gaps; gyro bias {:.5f} rad/s",
      robot_id, c.scans, c.scan_updates, c.scan_rejections, c.scan_match_failures, c.keyframes,
      c.heading_updates, c.heading_rejections, c.yaw_rate_updates, c.yaw_rate_rejections,
      c.heading_recoveries, c.late_imu, c.imu_gaps, ekf.gyroBias());
}

void logSlamSummary(const std::string& robot_id, const mrslam::robot::slam::SlamEstimator& slam) {
  const auto& c = slam.counters();
  spdlog::info(
      "{}: SLAM: {} scans, {} submap matches ({} gated out, {} failed, {} with a correlative "
      "search); {} nodes, {} submaps; loop closure: {} searches, {} found, {} refused by their "
      "residual; {} pose-graph solves",
      robot_id, c.scans, c.matches, c.match_rejections, c.match_failures, c.correlative_searches,
      c.nodes, c.submaps, slam.loopCloser().counters().searches, c.closures,
      slam.poseGraph().counters().closures_refused, slam.poseGraph().counters().solves);
}

void writeOutputs(const Options& options, const mrslam::robot::RobotPipeline& pipeline,
                  const RobotConfig& config) {
  if (!options.out.empty()) {
    std::filesystem::create_directories(options.out);
    const mrslam::GridMap map = pipeline.grid().toGridMap();
    const std::string stem = (std::filesystem::path(options.out) / config.robot_id).string();
    mrslam::saveMapYaml(map, stem + ".yaml");
    mrslam::MapOverlay overlay;
    for (const auto& point : pipeline.trajectory()) {
      overlay.trajectory_m.push_back(point.T_map_robot.translation());
    }
    mrslam::saveMapPng(map, stem + ".png", {overlay});
    spdlog::info("{}: map written to {}.yaml/.pgm/.png", config.robot_id, stem);
  }
  if (!options.trajectory_out.empty()) {
    mrslam::robot::writeTumTrajectory(pipeline.trajectory(), options.trajectory_out);
  }
}

int runRobot(const Options& options, const RobotConfig& config) {
  std::unique_ptr<mrslam::drivers::SampleSource> source = mrslam::robot::openSource(config);
  if (!options.record.empty()) {
    source = std::make_unique<mrslam::drivers::RecordingSource>(std::move(source), options.record,
                                                                config.robot_id);
    spdlog::info("{}: recording every sample to {}", config.robot_id, options.record);
  }
  auto estimator = mrslam::robot::makeEstimator(config, config.estimator.type);
  const auto* ekf = dynamic_cast<const mrslam::robot::EkfEstimator*>(estimator.get());
  const auto* slam = dynamic_cast<const mrslam::robot::slam::SlamEstimator*>(estimator.get());
  auto pipeline = std::make_unique<mrslam::robot::RobotPipeline>(config.mapping, config.mounting,
                                                                 std::move(estimator));
  NoOutput no_output;
  std::unique_ptr<mrslam::robot::RobotNode> node;
  if (!options.no_dds) {
    node = std::make_unique<mrslam::robot::RobotNode>(config.dds, config.robot_id);
  }
  mrslam::robot::RobotOutput& output =
      node ? static_cast<mrslam::robot::RobotOutput&>(*node) : no_output;
  spdlog::info("{}: running on {} with the {} estimator", config.robot_id, source->describe(),
               mrslam::robot::estimatorTypeName(config.estimator.type));
  mrslam::robot::RobotRunner runner(config.runner, *source, *pipeline, output);
  // A log or the simulator: how far the replay is, on standard error.
  mrslam::robot::ReplayProgress progress(config.robot_id, stderr, ::isatty(STDERR_FILENO) == 1);
  runner.setProgress(&progress);
  const auto summary = runner.run(mrslam::shutdownRequested());
  const auto counters = source->counters();
  spdlog::info(
      "{}: {} samples, {} scans, {} maps published, {} malformed records skipped, {} jumps of the "
      "log's clock shortened",
      config.robot_id, summary.samples, pipeline->counters().scans, summary.maps_published,
      counters.malformed_records, summary.replay_gaps_shortened);
  if (ekf != nullptr) {
    logEkfSummary(config.robot_id, *ekf);
  }
  if (slam != nullptr) {
    logSlamSummary(config.robot_id, *slam);
  }
  writeOutputs(options, *pipeline, config);
  if (node && config.delivery_readers > 0) {
    spdlog::info(
        "{}: waiting up to {} s for {} fusion agent(s) to hold the final map and the {} "
        "sightings written",
        config.robot_id, config.delivery_timeout_s, config.delivery_readers,
        summary.sightings_published);
    if (!node->waitForDelivery(config.delivery_readers, config.delivery_timeout_s,
                               summary.sightings_published > 0)) {
      spdlog::warn("{}: fewer than {} fusion agent(s) took the final map and sightings within {} s",
                   config.robot_id, config.delivery_readers, config.delivery_timeout_s);
      return 3;
    }
  }
  return 0;
}

// The config of --config, or by the log's format from --config-dir; then the command line's
// overrides.
RobotConfig loadConfig(Options& options) {
  if (!options.positional_log.empty()) {
    if (!options.log.empty() && options.log != options.positional_log) {
      throw std::invalid_argument("two logs given: " + options.log + " and " +
                                  options.positional_log);
    }
    options.log = options.positional_log;
  }
  std::string config_path = options.config_path;
  // A log given on the command line is read by the reader its content asks for.
  std::optional<mrslam::robot::SourceType> detected;
  if (!options.log.empty()) {
    const mrslam::drivers::LogFormat format = mrslam::drivers::detectLogFormat(options.log);
    if (format == mrslam::drivers::LogFormat::kUnknown) {
      throw std::invalid_argument(options.log +
                                  ": neither a CARMEN, a BreezySLAM nor an mrslam log");
    }
    detected = format == mrslam::drivers::LogFormat::kCarmen ? mrslam::robot::SourceType::kCarmen
               : format == mrslam::drivers::LogFormat::kMrslam
                   ? mrslam::robot::SourceType::kLog
                   : mrslam::robot::SourceType::kBreezySlam;
    if (config_path.empty()) {
      if (format == mrslam::drivers::LogFormat::kMrslam) {
        throw std::invalid_argument(
            options.log + ": an mrslam log needs the --robot-config it was recorded with");
      }
      const bool carmen = format == mrslam::drivers::LogFormat::kCarmen;
      config_path =
          (std::filesystem::path(options.config_dir) / (carmen ? "carmen.yaml" : "breezyslam.yaml"))
              .string();
      spdlog::info("robot_agent: {} log, config {}", mrslam::drivers::logFormatName(format),
                   config_path);
    }
  } else if (config_path.empty()) {
    throw std::invalid_argument("give --config, or a log to replay");
  }
  RobotConfig config = mrslam::robot::loadRobotConfig(config_path);
  if (options.domain >= 0) {
    config.dds.domain_id = options.domain;
  }
  if (options.delivery_readers >= 0) {
    config.delivery_readers = options.delivery_readers;
  }
  if (!options.discovery_server.empty()) {
    config.dds.discovery_server = options.discovery_server;
  }
  if (!options.robot_id.empty()) {
    if (!mrslam::isValidRobotId(options.robot_id)) {
      throw std::invalid_argument("--robot-id: '" + options.robot_id +
                                  "' is not a robot id (1-64 of A-Z a-z 0-9 _ -)");
    }
    config.robot_id = options.robot_id;
  }
  if (!options.security_dir.empty()) {
    config.dds.security_dir = options.security_dir;
  }
  if (!options.security_identity.empty()) {
    config.dds.security_identity = options.security_identity;
  } else if (config.dds.security_identity.empty()) {
    config.dds.security_identity = config.robot_id;
  }
  if (!options.log.empty()) {
    config.source.path = options.log;
    if (detected) {
      config.source.type = *detected;
    } else if (config.source.type == mrslam::robot::SourceType::kSimulator) {
      config.source.type = mrslam::robot::SourceType::kLog;
    }
  }
  if (options.speed >= 0.0) {
    config.runner.speed = options.speed;
  }
  if (!options.estimator.empty()) {
    config.estimator.type = mrslam::robot::parseEstimatorType(options.estimator);
  }
  if (!options.odom_noise.empty()) {
    const std::uint64_t seed = config.source.odometry_noise.seed;
    config.source.odometry_noise = mrslam::drivers::parseOdometryNoise(options.odom_noise);
    config.source.odometry_noise.seed = seed;
  }
  if (options.seed >= 0) {
    config.source.odometry_noise.seed = static_cast<std::uint64_t>(options.seed);
  }
  if (const auto mounting = mrslam::robot::applyLogLaserMounting(config)) {
    spdlog::info("robot_agent: the log mounts the laser at x {:.3f} m, y {:.3f} m, {:.2f} deg",
                 mounting->x(), mounting->y(), mounting->theta() * 180.0 / M_PI);
  }
  return config;
}

}  // namespace

int main(int argc, char** argv) {
  mrslam::logToStandardError("robot_agent");
  CLI::App app{"mrslam robot agent: pose, map and status of one robot on DDS"};
  Options options;
  std::string log_level = "info";
  app.add_option("log", options.positional_log, "a log to replay (as --log)");
  app.add_option("--config,--robot-config", options.config_path,
                 "robot config YAML (default with a log: carmen.yaml or breezyslam.yaml from "
                 "--config-dir, by the log's format)");
  app.add_option("--config-dir", options.config_dir,
                 "folder of the default robot configs (default: config)");
  app.add_option("--estimator", options.estimator, "odometry, ekf or slam (overrides the config)")
      ->check(CLI::IsMember({"odometry", "ekf", "slam"}));
  app.add_option("--odom-noise", options.odom_noise,
                 "DIST_FRACTION,DEG_PER_M: seeded noise added to the log's odometry poses "
                 "(e.g. 0.1,2; overrides the config)");
  app.add_option("--seed", options.seed, "seed of the odometry noise (overrides the config)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--domain", options.domain, "DDS domain id (overrides the config)")
      ->check(CLI::Range(0, 232));
  app.add_option("--delivery-readers", options.delivery_readers,
                 "at the end, wait until this many fusion agents hold the final map; 0: do not "
                 "wait (overrides publish.delivery_readers)")
      ->check(CLI::Range(0, 64));
  app.add_option("--discovery-server", options.discovery_server,
                 "IPv4:port of a Discovery Server to discover through (overrides the config)")
      ->check(
          [](const std::string& address) { return mrslam::checkDiscoveryServerAddress(address); });
  app.add_option("--security-dir", options.security_dir,
                 "DDS Security from this folder's files (scripts/make_test_pki.sh)");
  app.add_option("--security-identity", options.security_identity,
                 "the identity to prove (default: the config's, else the robot id)");
  app.add_option("--robot-id", options.robot_id,
                 "the robot's id on DDS and in file names (overrides the config)");
  app.add_option(
         "--speed", options.speed,
         "replay speed factor of the log clock, 0 = as fast as possible (overrides the config)")
      ->check(CLI::Range(0.0, 1000.0));
  app.add_option("--log", options.log, "replay this log instead of the configured source's");
  app.add_option("--out", options.out, "write the final map (YAML/PGM/PNG) into this folder");
  app.add_option("--trajectory-out", options.trajectory_out,
                 "write the pose at every scan in TUM format to this file");
  app.add_option("--record", options.record,
                 "write every sample read to this mrslam log (replay it with --log)");
  app.add_flag("--no-dds", options.no_dds, "run without DDS (offline replay)");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error");
  app.set_version_flag("--version", mrslam::versionLine("robot_agent"));
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::from_str(log_level));
  try {
    RobotConfig config = loadConfig(options);
    return runRobot(options, config);
  } catch (const std::exception& error) {
    spdlog::error("robot_agent: {}", error.what());
    return 1;
  }
}
