// Seed merger costs: one merge of two 400 × 400 crops of a real map (Intel lab), turned and
// shifted by a seeded random transform with 40-100 % overlap, on one core. Reports the median of
// one merge over the cases and each block's share of the time (SeedMerger::lastTimings).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "../tests/unit/fusion/merge_test_maps.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion {
namespace {

constexpr int kCases = 12;
constexpr int kSize = 400;

std::vector<merge_test::KnownCase> cases(const std::string& file) {
  const std::string path = std::string(MRSLAM_DATA_DIR) + "/maps/" + file;
  std::vector<merge_test::KnownCase> known;
  if (!std::filesystem::exists(path)) {
    return known;
  }
  const GridMap map = merge_test::loadMap(path);
  std::mt19937 random(7);
  while (static_cast<int>(known.size()) < kCases) {
    merge_test::KnownCase next = merge_test::randomCase(map, kSize, 0.4, 1.01, random);
    if (next.overlap > 0.0) {
      known.push_back(std::move(next));
    }
  }
  return known;
}

double milliseconds(SeedMergeTimings::Duration duration) {
  return duration.count();
}

void BM_SeedMerge400(benchmark::State& state, const char* file) {
  cv::setNumThreads(1);  // one core
  const std::vector<merge_test::KnownCase> known = cases(file);
  if (known.empty()) {
    state.SkipWithError("needs ../shared/data/maps");
    return;
  }
  SeedMerger merger;
  std::vector<double> times;
  SeedMergeTimings total;
  int accepted = 0;
  std::size_t next = 0;
  for (auto _ : state) {
    const merge_test::KnownCase& pair = known[next++ % known.size()];
    const auto start = std::chrono::steady_clock::now();
    const MergeResult result = merger.merge(pair.from, pair.to);
    times.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    benchmark::DoNotOptimize(result);
    accepted += result.accepted ? 1 : 0;
    const SeedMergeTimings& last = merger.lastTimings();
    total.edges += last.edges;
    total.radon += last.radon;
    total.segments += last.segments;
    total.correlation += last.correlation;
    total.poses += last.poses;
    total.translation += last.translation;
    total.verification += last.verification;
    total.fallback += last.fallback;
    total.global += last.global;
  }
  std::nth_element(times.begin(), times.begin() + static_cast<long>(times.size() / 2), times.end());
  state.counters["median_ms"] = times[times.size() / 2];
  state.counters["accepted_share"] =
      static_cast<double>(accepted) / static_cast<double>(times.size());
  const double sum =
      milliseconds(total.edges + total.radon + total.segments + total.correlation + total.poses +
                   total.translation + total.verification + total.fallback + total.global);
  const auto share = [&](const char* name, SeedMergeTimings::Duration block) {
    state.counters[name] = milliseconds(block) / sum;
  };
  share("edges", total.edges);
  share("radon", total.radon);
  share("segments", total.segments);
  share("correlation", total.correlation);
  share("poses", total.poses);
  share("translation", total.translation);
  share("verification", total.verification);
  share("fallback", total.fallback);
  share("global", total.global);
}
BENCHMARK_CAPTURE(BM_SeedMerge400, intel, "carpin-intel.txt")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3 * kCases);
BENCHMARK_CAPTURE(BM_SeedMerge400, freiburg_aces, "freiburg-aces.pgm")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3 * kCases);

}  // namespace
}  // namespace mrslam::fusion

BENCHMARK_MAIN();
