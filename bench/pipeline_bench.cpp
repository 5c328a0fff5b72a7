// The whole robot pipeline (EKF with scan-to-map ICP, grid mapping) replaying real logs on one
// core: speed as a multiple of the log's real time, the per-scan cost of scan matching, of the
// filter and of grid insertion, and the process's peak memory. Run it alone (other load skews it).
//   build/bench/pipeline_bench [--benchmark_filter=breezyslam]
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "mrslam/robot/evaluation.hpp"

namespace mrslam {
namespace {

// The robot config of this source tree (bench/../config).
std::string sourceConfig(const std::string& name) {
  return (std::filesystem::path(__FILE__).parent_path() / ".." / "config" / name).string();
}

double peakMemoryMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

double logSeconds(const std::vector<Sample>& samples) {
  Stamp first = stampOf(samples.front());
  Stamp last = first;
  for (const Sample& sample : samples) {
    first = std::min(first, stampOf(sample));
    last = std::max(last, stampOf(sample));
  }
  return secondsBetween(first, last);
}

// Grid insertion alone: every scan at the pose the pipeline gave it.
double gridSecondsPerScan(const robot::RobotConfig& config, const std::vector<LaserScan>& scans,
                          const std::vector<SE2>& poses) {
  robot::GridMapper mapper(config.mapping, config.mounting);
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < scans.size(); ++i) {
    mapper.insertScan(scans[i], poses[i]);
  }
  benchmark::DoNotOptimize(mapper.grid().knownCellCount());
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
         static_cast<double>(scans.size());
}

void BM_Pipeline(benchmark::State& state, const std::string& config_name, const std::string& log,
                 const std::string& noise) {
  const std::string path = (std::filesystem::path(MRSLAM_DATA_DIR) / "logs" / log).string();
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("needs " + path).c_str());
    return;
  }
  robot::RobotConfig config = robot::loadRobotConfig(sourceConfig(config_name));
  config.source.path = path;
  config.source.odometry_noise = drivers::parseOdometryNoise(noise);
  auto source = robot::openSource(config);
  const std::vector<Sample> samples = robot::readAllSamples(*source);
  double scans = 0.0;
  robot::EkfTimings timings;
  std::vector<SE2> poses;
  for (auto _ : state) {
    const robot::PipelineRun run = robot::runPipeline(config, robot::EstimatorType::kEkf, samples);
    scans = static_cast<double>(run.pipeline->counters().scans);
    timings = *run.ekf_timings;
    poses = robot::posesOf(run);
    benchmark::DoNotOptimize(run.pipeline->grid().knownCellCount());
  }
  const double log_s = logSeconds(samples);
  state.counters["x_realtime"] = benchmark::Counter(log_s * static_cast<double>(state.iterations()),
                                                    benchmark::Counter::kIsRate);
  state.counters["scans/s"] = benchmark::Counter(scans * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
  state.counters["icp_us/scan"] = 1e6 * timings.scan_matching_s / scans;
  state.counters["filter_us/scan"] = 1e6 * timings.filter_s / scans;
  state.counters["grid_us/scan"] = 1e6 * gridSecondsPerScan(config, robot::scansOf(samples), poses);
  state.counters["peak_rss_MB"] = peakMemoryMb();
}

BENCHMARK_CAPTURE(BM_Pipeline, breezyslam_exp1, std::string("breezyslam.yaml"),
                  std::string("breezyslam-exp1.dat"), std::string("0,0"))
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK_CAPTURE(BM_Pipeline, carmen_intel_noisy, std::string("carmen.yaml"),
                  std::string("carmen-intel-corrected.log.gz"), std::string("0.1,2"))
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

}  // namespace
}  // namespace mrslam

BENCHMARK_MAIN();
