// mrslam_scan: checks a Hokuyo laser ranger (SCIP 2.0). Prints its identity (VV, PP) and N
// scans, as text or, with --json, one JSON object per scan and line:
//   {"timestamp_ms": t, "angle_min_rad": a, "angle_increment_rad": d, "ranges_m": [...],
//    "range_min_m": …, "range_max_m": …, "no_return": [indices]}
// ranges_m holds null where the sensor reported an error code (below DMIN) and where it saw
// nothing in range (above DMAX); the latter beams are also listed in "no_return".
// Exit codes: 0 done; 1 bad arguments; 2 the device does not answer SCIP 2.0 (absent, silent,
// garbage, failed start-up); 3 the device vanished or stopped sending scans.

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "mrslam/common/shutdown.hpp"
#include "mrslam/common/version.hpp"
#include "mrslam/drivers/hokuyo_driver.hpp"

namespace {

using mrslam::LaserScan;
using mrslam::drivers::HokuyoDriver;
using mrslam::drivers::HokuyoIdentity;
using mrslam::drivers::HokuyoState;

struct ScanOptions {
  std::string device;
  int count = 1;
  bool json = false;
  int baud = 115200;
  double timeout_s = 2.0;
  bool verbose = false;
};

int failWith(const ScanOptions& options, int code, std::string reason) {
  const std::string device_prefix = options.device + ": ";
  // Serial port errors name the device already: name it once.
  for (auto at = reason.find(device_prefix); at != std::string::npos;
       at = reason.find(device_prefix, at)) {
    reason.erase(at, device_prefix.size());
  }
  std::fprintf(stderr, "mrslam_scan: %s: %s\n", options.device.c_str(), reason.c_str());
  return code;
}

void printIdentity(const HokuyoIdentity& identity, std::FILE* out) {
  std::fprintf(out, "baud: %d%s\n", identity.baud,
               identity.switched_from_scip11 ? " (switched from SCIP 1.1)" : "");
  for (const auto* group : {&identity.version, &identity.parameters}) {
    for (const auto& [key, value] : *group) {
      std::fprintf(out, "%s: %s\n", key.c_str(), value.c_str());
    }
  }
  std::fflush(out);
}

nlohmann::json scanAsJson(const LaserScan& scan) {
  nlohmann::json ranges = nlohmann::json::array();
  nlohmann::json no_return = nlohmann::json::array();
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const float range = scan.ranges_m[i];
    if (std::isfinite(range)) {
      ranges.push_back(std::round(range * 1000.0) / 1000.0);  // the sensor's resolution: 1 mm
      continue;
    }
    ranges.push_back(nullptr);
    if (std::isinf(range)) {
      no_return.push_back(i);
    }
  }
  return {{"timestamp_ms", static_cast<double>(scan.stamp.ns) * 1e-6},
          {"angle_min_rad", scan.angle_min_rad},
          {"angle_increment_rad", scan.angle_increment_rad},
          {"range_min_m", scan.range_min_m},
          {"range_max_m", scan.range_max_m},
          {"ranges_m", ranges},
          {"no_return", no_return}};
}

void printScanSummary(int index, const LaserScan& scan) {
  std::size_t hits = 0;
  std::size_t no_return = 0;
  for (const float range : scan.ranges_m) {
    hits += std::isfinite(range) ? 1 : 0;
    no_return += std::isinf(range) ? 1 : 0;
  }
  std::printf(
      "scan %d: stamp %s s, %zu beams from %.4f rad by %.6f rad: %zu hits, %zu no return, "
      "%zu invalid\n",
      index, scan.stamp.toString().c_str(), scan.ranges_m.size(), scan.angle_min_rad,
      scan.angle_increment_rad, hits, no_return, scan.ranges_m.size() - hits - no_return);
  std::fflush(stdout);
}

int runScan(const ScanOptions& options) {
  mrslam::drivers::HokuyoSettings settings;
  settings.device = options.device;
  settings.baud = options.baud;
  settings.read_timeout = std::chrono::milliseconds(static_cast<long>(options.timeout_s * 1e3));
  HokuyoDriver driver(settings);
  const auto identity = driver.connect();
  if (!identity) {
    return failWith(options, 2, identity.reason());
  }
  printIdentity(identity.value(), options.json ? stderr : stdout);
  const auto& shutdown = mrslam::shutdownRequested();
  for (int index = 0; options.count == 0 || index < options.count; ++index) {
    const auto scan = driver.poll(settings.read_timeout);
    if (shutdown.load()) {
      return 0;
    }
    if (!scan) {
      const auto health = driver.health();
      const bool vanished = health.state != HokuyoState::kConnected;
      return failWith(
          options, 3,
          std::string(vanished ? "device vanished: " : "no scan in time: ") + health.last_error);
    }
    if (options.json) {
      std::cout << scanAsJson(*scan).dump() << std::endl;
    } else {
      printScanSummary(index, *scan);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  ScanOptions options;
  CLI::App app{"mrslam_scan: identity and scans of a Hokuyo laser ranger (SCIP 2.0)"};
  app.add_option("device", options.device, "serial device, e.g. /dev/ttyACM0")->required();
  app.add_option("--count", options.count, "scans to print (0: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--json", options.json, "one JSON object per scan and line (identity to stderr)");
  app.add_option("--baud", options.baud, "baud rate tried first (then 19200, 38400, 115200)");
  app.add_option("--timeout", options.timeout_s, "seconds to wait for each reply and scan")
      ->check(CLI::Range(0.05, 600.0));
  app.add_flag("--verbose", options.verbose, "log every dropped reply (rate-limited) to stderr");
  app.set_version_flag("--version", mrslam::versionLine("scan"));
  CLI11_PARSE(app, argc, argv);
  spdlog::set_default_logger(spdlog::stderr_color_st("mrslam_scan"));  // stdout: scans only
  spdlog::set_level(options.verbose ? spdlog::level::info : spdlog::level::err);
  try {
    return runScan(options);
  } catch (const std::exception& error) {
    return failWith(options, 2, error.what());
  }
}
