// mrslam_gx1_emulator: a MicroStrain 3DM-GX1 on a pseudo-terminal, for trying the driver and
// the tools without the device. LINK_PATH becomes a symbolic link to the pty's slave side.
//   mrslam_gx1_emulator LINK_PATH [--roll DEG] [--pitch DEG] [--yaw DEG] [--rate-z DEG_S] ...
// Angles and rates are in the device's axes (z down, heading clockwise); a level device at rest
// reads -1 g on z. Runs until SIGINT or SIGTERM.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <climits>
#include <cmath>
#include <thread>

#include "mrslam/common/logging.hpp"
#include "mrslam/common/shutdown.hpp"
#include "mrslam/common/version.hpp"
#include "mrslam/drivers/gx1_emulator.hpp"

namespace {

using mrslam::drivers::Gx1Emulator;
using mrslam::drivers::Gx1EmulatorSettings;
using mrslam::drivers::Gx1Fault;

constexpr double kRadiansPerDegree = M_PI / 180.0;

struct Options {
  std::string link_path;
  double roll_deg = 0.0;
  double pitch_deg = 0.0;
  double yaw_deg = 0.0;
  double rate_z_deg_s = 0.0;
  double accel_z_g = -1.0;
  int start_ticks = 0;
  double interval_ms = 10.0;
  bool garbage = false;
  bool silent = false;
};

mrslam::drivers::gx1::DeviceState stateFrom(const Options& options) {
  mrslam::drivers::gx1::DeviceState state;
  state.roll_rad = options.roll_deg * kRadiansPerDegree;
  state.pitch_rad = options.pitch_deg * kRadiansPerDegree;
  state.yaw_rad = options.yaw_deg * kRadiansPerDegree;
  state.angular_rate_rad_s.z() = options.rate_z_deg_s * kRadiansPerDegree;
  state.acceleration_g.z() = options.accel_z_g;
  state.magnetic_gauss = Eigen::Vector3d(0.2, 0.0, 0.4);
  return state;
}

int run(const Options& options) {
  Gx1EmulatorSettings settings;
  settings.link_path = options.link_path;
  settings.initial_ticks = static_cast<std::uint16_t>(options.start_ticks);
  settings.continuous_interval =
      std::chrono::microseconds(std::llround(options.interval_ms * 1000.0));
  const mrslam::drivers::gx1::DeviceState state = stateFrom(options);
  Gx1Emulator emulator(settings, [state] { return state; });
  if (options.garbage) {
    emulator.injectFault(Gx1Fault::kGarbageReply, INT_MAX);
  }
  emulator.setStalled(options.silent);
  const std::atomic<bool>& shutdown = mrslam::shutdownRequested();
  emulator.start();
  spdlog::info("3DM-GX1 emulator on {}{}", emulator.devicePath(),
               options.garbage  ? " (answering garbage)"
               : options.silent ? " (silent)"
                                : "");
  while (!shutdown.load()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  emulator.stop();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  mrslam::logToStandardError("mrslam_gx1_emulator");
  Options options;
  CLI::App app{"A MicroStrain 3DM-GX1 emulator on a pseudo-terminal."};
  app.add_option("link_path", options.link_path, "symbolic link to create for the device")
      ->required();
  app.add_option("--roll", options.roll_deg, "roll in degrees");
  app.add_option("--pitch", options.pitch_deg, "pitch in degrees");
  app.add_option("--yaw", options.yaw_deg, "heading in degrees (clockwise)");
  app.add_option("--rate-z", options.rate_z_deg_s, "angular rate about z in degrees/s");
  app.add_option("--accel-z", options.accel_z_g, "acceleration on z in g");
  app.add_option("--start-ticks", options.start_ticks, "timer at power-up")
      ->check(CLI::Range(0, 65535));
  app.add_option("--interval-ms", options.interval_ms, "time between frames when streaming")
      ->check(CLI::Range(1.0, 1000.0));
  app.add_flag("--garbage", options.garbage, "answer every request with garbage");
  app.add_flag("--silent", options.silent, "answer nothing");
  app.set_version_flag("--version", mrslam::versionLine("gx1_emulator"));
  CLI11_PARSE(app, argc, argv);
  try {
    return run(options);
  } catch (const std::exception& error) {
    spdlog::error("mrslam_gx1_emulator: {}", error.what());
    return 1;
  }
}
