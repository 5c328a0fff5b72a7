// mrslam_hokuyo_emulator: an emulated Hokuyo laser ranger (SCIP 2.0) on a pseudo-terminal,
// reachable at LINK_PATH, until SIGINT or SIGTERM. For tests and demos of the driver and of
// mrslam_scan without hardware.

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <thread>

#include "mrslam/common/logging.hpp"
#include "mrslam/common/shutdown.hpp"
#include "mrslam/common/version.hpp"
#include "mrslam/drivers/hokuyo_emulator.hpp"

namespace {

struct EmulatorOptions {
  std::string link_path;
  std::string model = "urg04lx";
  std::string pattern = "room";
  bool scip11 = false;
  int baud = 0;
  std::uint32_t clock_start_ms = 0;
};

int runEmulator(const EmulatorOptions& options) {
  mrslam::drivers::HokuyoEmulatorSettings settings;
  settings.model = options.model == "ubg05ln" ? mrslam::drivers::HokuyoModel::ubg05ln()
                                              : mrslam::drivers::HokuyoModel::urg04lx();
  settings.ranges = mrslam::drivers::hokuyoRangePattern(options.pattern, settings.model);
  settings.protocol.start_in_scip11 = options.scip11;
  settings.device_baud = options.baud;
  settings.clock_start_ms = options.clock_start_ms;
  const auto& shutdown = mrslam::shutdownRequested();
  mrslam::drivers::HokuyoEmulator emulator(settings, options.link_path);
  emulator.start();
  std::printf("mrslam_hokuyo_emulator: %s (%s pattern) at %s\n", options.model.c_str(),
              options.pattern.c_str(), emulator.devicePath().c_str());
  std::fflush(stdout);
  while (!shutdown.load()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  emulator.stop();
  std::printf("mrslam_hokuyo_emulator: stopped after %llu scans\n",
              static_cast<unsigned long long>(emulator.scansSent()));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  mrslam::logToStandardError("mrslam_hokuyo_emulator");
  EmulatorOptions options;
  CLI::App app{"mrslam_hokuyo_emulator: an emulated Hokuyo ranger on a pseudo-terminal"};
  app.add_option("link_path", options.link_path, "path of the link to the emulated device")
      ->required();
  app.add_option("--model", options.model, "urg04lx or ubg05ln")
      ->check(CLI::IsMember({"urg04lx", "ubg05ln"}));
  app.add_option("--pattern", options.pattern, "ranges: room, ramp or constant")
      ->check(CLI::IsMember({"room", "ramp", "constant"}));
  app.add_flag("--scip11", options.scip11, "start in SCIP 1.1 (the driver must switch it)");
  app.add_option("--baud", options.baud, "RS-232 rate of the device (0: USB, any rate)");
  app.add_option("--clock-start-ms", options.clock_start_ms,
                 "the device's 24-bit ms counter at start")
      ->check(CLI::Range(0u, (1u << 24) - 1));
  app.set_version_flag("--version", mrslam::versionLine("hokuyo_emulator"));
  CLI11_PARSE(app, argc, argv);
  try {
    return runEmulator(options);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "mrslam_hokuyo_emulator: %s\n", error.what());
    return 2;
  }
}
