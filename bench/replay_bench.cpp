// Log replay throughput: scans and lines per second through the reader alone, and through the whole
// robot pipeline (reader, odometry, grid mapping), on the real logs of ../shared/data.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "mrslam/drivers/line_reader.hpp"
#include "mrslam/drivers/log_format.hpp"
#include "mrslam/robot/grid_mapper.hpp"
#include "mrslam/robot/odometry_estimator.hpp"
#include "mrslam/robot/robot_pipeline.hpp"

namespace mrslam {
namespace {

std::string logPath(const std::string& name) {
  return (std::filesystem::path(MRSLAM_DATA_DIR) / "logs" / name).string();
}

bool skipWithoutLog(benchmark::State& state, const std::string& path) {
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("needs " + path).c_str());
    return true;
  }
  return false;
}

void countScans(benchmark::State& state, double scans) {
  state.counters["scans/s"] = benchmark::Counter(scans * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}

// Lines of the (decompressed) log, for a lines-per-second figure.
double countLines(const std::string& path) {
  drivers::LineReader reader(path);
  std::string line;
  double lines = 0.0;
  while (reader.next(line)) {
    lines += 1.0;
  }
  return lines;
}

void BM_ReadLog(benchmark::State& state, const std::string& name) {
  const std::string path = logPath(name);
  if (skipWithoutLog(state, path)) {
    return;
  }
  const double lines = countLines(path);
  double scans = 0.0;
  for (auto _ : state) {
    auto reader = drivers::openLogReader(path, drivers::MalformedPolicy::kStop);
    scans = 0.0;
    while (auto sample = reader->next()) {
      scans += std::holds_alternative<LaserScan>(*sample) ? 1.0 : 0.0;
    }
  }
  countScans(state, scans);
  state.counters["lines/s"] = benchmark::Counter(lines * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}

void BM_ReplayLog(benchmark::State& state, const std::string& name, double max_range_m,
                  const SensorMounting& mounting, const DiffDriveParams& platform) {
  const std::string path = logPath(name);
  if (skipWithoutLog(state, path)) {
    return;
  }
  robot::MappingSettings mapping;
  mapping.max_range_m = max_range_m;
  double scans = 0.0;
  for (auto _ : state) {
    auto reader = drivers::openLogReader(path, drivers::MalformedPolicy::kStop);
    robot::RobotPipeline pipeline(
        mapping, mounting,
        std::make_unique<robot::OdometryEstimator>(platform, robot::OdometryNoise{}));
    while (auto sample = reader->next()) {
      pipeline.process(*sample);
    }
    scans = static_cast<double>(pipeline.counters().scans);
    benchmark::DoNotOptimize(pipeline.grid().knownCellCount());
  }
  countScans(state, scans);
}

SensorMounting breezySlamMounting() {
  SensorMounting mounting;
  mounting.T_robot_laser = SE2(0.145, 0.0, 0.0);
  return mounting;
}

DiffDriveParams breezySlamPlatform() {
  DiffDriveParams platform;
  platform.wheel_radius_m = 0.077;
  platform.track_width_m = 0.33;
  platform.ticks_per_revolution = 4000;
  return platform;
}

BENCHMARK_CAPTURE(BM_ReadLog, breezyslam_exp1, std::string("breezyslam-exp1.dat"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadLog, carmen_intel, std::string("carmen-intel-corrected.log.gz"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReplayLog, breezyslam_exp1, std::string("breezyslam-exp1.dat"), 4.0,
                  breezySlamMounting(), breezySlamPlatform())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReplayLog, carmen_intel, std::string("carmen-intel-corrected.log.gz"), 50.0,
                  SensorMounting{}, DiffDriveParams{})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mrslam

BENCHMARK_MAIN();
