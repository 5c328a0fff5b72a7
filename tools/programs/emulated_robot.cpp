// mrslam_emulated_robot: a robot's devices, emulated — the source of a config (the simulator or
// a log) played in real time through an emulated Hokuyo and 3DM-GX1 on pseudo-terminals and the
// emulated Phidget encoder board, at the paths a robot agent's devices config names. The agent
// then runs exactly as on a robot.
//   mrslam_emulated_robot --robot-config AGENT.yaml --source-config SIM.yaml [--log FILE]
//                         [--speed X] [--duration S] [--truth-out FILE] [--encoder-feed FILE]
// The encoder feed defaults to $MRSLAM_PHIDGET_EMULATOR_FEED (what the emulated board reads).
// Ends when the source ends (exit 0), or on SIGINT / SIGTERM.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>

#include "mrslam/common/logging.hpp"
#include "mrslam/common/shutdown.hpp"
#include "mrslam/common/version.hpp"
#include "mrslam/drivers/emulated_robot.hpp"
#include "mrslam/drivers/log_format.hpp"
#include "mrslam/robot/robot_config.hpp"

namespace {

using mrslam::drivers::EmulatedDevices;
using mrslam::drivers::EmulatedRobot;
using mrslam::robot::RobotConfig;

struct Options {
  std::string robot_config;
  std::string source_config;
  std::string log;
  double speed = 1.0;
  double duration_s = 0.0;
  std::string truth_out;
  std::string encoder_feed;
};

// Where the agent of `agent` looks for its devices.
EmulatedDevices devicesOf(const RobotConfig& agent, const std::string& encoder_feed) {
  if (agent.source.type != mrslam::robot::SourceType::kDevices) {
    throw std::invalid_argument("--robot-config: the agent's source is not `devices`");
  }
  const mrslam::robot::DeviceSourceSettings& d = agent.source.devices;
  EmulatedDevices devices;
  if (d.laser) {
    devices.laser_path = d.laser->device;
  }
  if (d.imu) {
    devices.imu_path = d.imu->device;
    devices.imu_z_down = d.imu->device_z_down;
  }
  if (d.encoders) {
    if (encoder_feed.empty()) {
      throw std::invalid_argument(
          "the agent reads encoders: give --encoder-feed or set MRSLAM_PHIDGET_EMULATOR_FEED");
    }
    devices.encoder_feed_path = encoder_feed;
    devices.left_channel = d.encoders->left.channel;
    devices.right_channel = d.encoders->right.channel;
    devices.left_direction = d.encoders->left.direction;
    devices.right_direction = d.encoders->right.direction;
  }
  return devices;
}

// The source config, with --log in place of its source (read by the reader its content asks for).
RobotConfig sourceConfigOf(const Options& options) {
  RobotConfig config = mrslam::robot::loadRobotConfig(options.source_config);
  if (!options.log.empty()) {
    using mrslam::drivers::LogFormat;
    const LogFormat format = mrslam::drivers::detectLogFormat(options.log);
    if (format == LogFormat::kUnknown) {
      throw std::invalid_argument(options.log +
                                  ": neither a CARMEN, a BreezySLAM nor an mrslam log");
    }
    config.source.path = options.log;
    config.source.type = format == LogFormat::kCarmen   ? mrslam::robot::SourceType::kCarmen
                         : format == LogFormat::kMrslam ? mrslam::robot::SourceType::kLog
                                                        : mrslam::robot::SourceType::kBreezySlam;
  }
  if (config.source.type == mrslam::robot::SourceType::kDevices) {
    throw std::invalid_argument("--source-config: a devices source cannot feed emulated devices");
  }
  return config;
}

int run(const Options& options) {
  const RobotConfig agent = mrslam::robot::loadRobotConfig(options.robot_config);
  const RobotConfig source_config = sourceConfigOf(options);
  mrslam::drivers::EmulatedRobotSettings settings;
  settings.speed = options.speed;
  if (options.duration_s > 0.0) {
    settings.duration_s = options.duration_s;
  }
  settings.drive = agent.platform;
  EmulatedRobot robot(mrslam::robot::openSource(source_config),
                      devicesOf(agent, options.encoder_feed), settings);
  robot.start();
  const EmulatedDevices devices = devicesOf(agent, options.encoder_feed);
  spdlog::info(
      "mrslam_emulated_robot: devices ready: laser {} ({}); IMU {} and encoder feed {} (each "
      "once the source has its samples)",
      devices.laser_path.empty() ? "none" : devices.laser_path,
      devices.laser_path.empty() ? "-" : robot.laserModel().product,
      devices.imu_path.empty() ? "none" : devices.imu_path,
      devices.encoder_feed_path.empty() ? "none" : devices.encoder_feed_path);
  std::ofstream truth;
  if (!options.truth_out.empty()) {
    truth.open(options.truth_out);
    if (!truth) {
      throw std::runtime_error("cannot write " + options.truth_out);
    }
    truth << std::fixed << std::setprecision(9);
  }
  const auto observer = [&truth](double host_time_s, const mrslam::LaserScan& scan) {
    if (truth.is_open() && scan.logged_pose) {
      const mrslam::SE2& T = *scan.logged_pose;
      truth << host_time_s << ' ' << T.x() << ' ' << T.y() << " 0 0 0 " << std::sin(0.5 * T.theta())
            << ' ' << std::cos(0.5 * T.theta()) << '\n';
    }
  };
  const mrslam::drivers::EmulatedRobotCounters counters =
      robot.run(mrslam::shutdownRequested(), observer);
  spdlog::info(
      "mrslam_emulated_robot: {:.1f} s of {} played: {} scans ({} sent by the laser), {} IMU "
      "samples ({} frames sent), {} encoder readings",
      counters.source_time_s,
      source_config.source.path.empty() ? options.source_config : source_config.source.path,
      counters.scans, counters.hokuyo_scans_sent, counters.imu_samples, counters.gx1_frames_sent,
      counters.tick_readings);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  mrslam::logToStandardError("mrslam_emulated_robot");
  Options options;
  if (const char* feed = std::getenv("MRSLAM_PHIDGET_EMULATOR_FEED")) {
    options.encoder_feed = feed;
  }
  CLI::App app{"mrslam_emulated_robot: a robot's devices emulated on pseudo-terminals"};
  app.add_option("--robot-config", options.robot_config,
                 "the robot agent's config (source: devices): where its devices are")
      ->required();
  app.add_option("--source-config", options.source_config,
                 "a config whose source (simulator or log) is played")
      ->required();
  app.add_option("--log", options.log, "play this log instead of the source config's");
  app.add_option("--speed", options.speed, "source seconds per second")
      ->check(CLI::Range(0.01, 100.0));
  app.add_option("--duration", options.duration_s, "stop after this much source time (s)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--truth-out", options.truth_out,
                 "write the source's true pose at each scan (TUM, host time)");
  app.add_option("--encoder-feed", options.encoder_feed,
                 "the emulated Phidget board's feed file (default $MRSLAM_PHIDGET_EMULATOR_FEED)");
  app.set_version_flag("--version", mrslam::versionLine("emulated_robot"));
  CLI11_PARSE(app, argc, argv);
  try {
    return run(options);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "mrslam_emulated_robot: %s\n", error.what());
    return 2;
  }
}
