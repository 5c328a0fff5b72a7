// robot_agent: reads one robot's sensors (devices, a log or the simulator), estimates its pose,
// builds its occupancy grid and publishes pose, map and status on DDS.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <filesystem>

#include "mrslam/common/map_io.hpp"
#include "mrslam/common/shutdown.hpp"
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
};

struct Options {
  std::string config_path;
  int domain = -1;
  double speed = -1.0;
  std::string log;
  std::string out;
  std::string trajectory_out;
  bool no_dds = false;
};

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
  auto source = mrslam::robot::openSource(config);
  auto pipeline = mrslam::robot::makePipeline(config);
  NoOutput no_output;
  std::unique_ptr<mrslam::robot::RobotNode> node;
  if (!options.no_dds) {
    node = std::make_unique<mrslam::robot::RobotNode>(config.dds, config.robot_id);
  }
  mrslam::robot::RobotOutput& output =
      node ? static_cast<mrslam::robot::RobotOutput&>(*node) : no_output;
  spdlog::info("{}: running on {}", config.robot_id, source->describe());
  mrslam::robot::RobotRunner runner(config.runner, *source, *pipeline, output);
  const auto summary = runner.run(mrslam::shutdownRequested());
  const auto counters = source->counters();
  spdlog::info("{}: {} samples, {} scans, {} maps published, {} malformed records skipped",
               config.robot_id, summary.samples, pipeline->counters().scans, summary.maps_published,
               counters.malformed_records);
  writeOutputs(options, *pipeline, config);
  if (node && config.delivery_readers > 0 &&
      !node->waitForMapDelivery(config.delivery_readers, config.delivery_timeout_s)) {
    spdlog::warn("{}: no fusion agent took the final map within {} s", config.robot_id,
                 config.delivery_timeout_s);
    return 3;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mrslam robot agent: pose, map and status of one robot on DDS"};
  Options options;
  std::string log_level = "info";
  app.add_option("--config", options.config_path, "robot config YAML")->required();
  app.add_option("--domain", options.domain, "DDS domain id (overrides the config)")
      ->check(CLI::Range(0, 232));
  app.add_option(
         "--speed", options.speed,
         "replay speed factor of the log clock, 0 = as fast as possible (overrides the config)")
      ->check(CLI::Range(0.0, 1000.0));
  app.add_option("--log", options.log, "replay this log instead of the configured source's");
  app.add_option("--out", options.out, "write the final map (YAML/PGM/PNG) into this folder");
  app.add_option("--trajectory-out", options.trajectory_out,
                 "write the pose at every scan in TUM format to this file");
  app.add_flag("--no-dds", options.no_dds, "run without DDS (offline replay)");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error");
  app.set_version_flag("--version", "mrslam robot_agent 0.1.0");
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::from_str(log_level));
  try {
    RobotConfig config = mrslam::robot::loadRobotConfig(options.config_path);
    if (options.domain >= 0) {
      config.dds.domain_id = options.domain;
    }
    if (!options.log.empty()) {
      config.source.path = options.log;
      if (config.source.type == mrslam::robot::SourceType::kSimulator) {
        config.source.type = mrslam::robot::SourceType::kLog;
      }
    }
    if (options.speed >= 0.0) {
      config.runner.speed = options.speed;
    }
    return runRobot(options, config);
  } catch (const std::exception& error) {
    spdlog::error("robot_agent: {}", error.what());
    return 1;
  }
}
