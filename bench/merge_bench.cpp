// Merge costs: one merge of two 400 × 400 crops of a real map (Intel lab, ACES), turned and
// shifted by a seeded random transform with 40-100 % overlap, on one core. BM_SeedMerge400
// reports the median of one merge over the cases and each block's share of the time
// (SeedMerger::lastTimings), BM_FeatureMerge400 the same for the feature baseline; BM_Merge400
// the median, the 90th percentile and the share merged within 2 cells and 1° of the truth for
// other mergers of the registry (the exhaustive search, the chain) on the same cases, searching
// every rotation or only those near the turns the walls suggest (`rotation_peaks`);
// BM_MergeBlocks400 the default merger's median and each of its blocks' share of the time
// (MapMerger::lastBlockTimes), BM_RefusalBlocks400 the same for pairs from two buildings, which
// it refuses; BM_ExhaustiveSearch400 the exhaustive search alone, with and without
// its early stop, and near the suggested turns. BM_MergeWholeBuilding: two turned 700-cell windows
// of the ACES map (crops of about 1000 cells a side, which the exhaustive search takes on larger
// cells, max_grid_cells).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <opencv2/core.hpp>
#include <random>
#include <string>
#include <vector>

#include "crop_cases.hpp"
#include "mrslam/common/heap.hpp"
#include "mrslam/fusion/merge/exhaustive_search.hpp"
#include "mrslam/fusion/merge/feature_merger.hpp"
#include "mrslam/fusion/merge/merge_cases.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion {
namespace {

using bench::cases;
using bench::kCases;
using bench::kSize;
using bench::percentileOf;
using bench::totalOf;

/// One merge, its wall-clock time appended to `times_ms`.
MergeResult timedMerge(MapMerger& merger, const GridMap& from, const GridMap& to,
                       std::vector<double>& times_ms) {
  const auto start = std::chrono::steady_clock::now();
  MergeResult result = merger.merge(from, to);
  times_ms.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  benchmark::DoNotOptimize(result);
  return result;
}

/// Within 2 cells (at the overlap's centre) and 1° of the truth.
bool withinTolerance(const MergeResult& result, const merge_test::KnownCase& pair) {
  const double cells = (result.T_to_from.apply(pair.overlap_centre_from) -
                        pair.T_to_from.apply(pair.overlap_centre_from))
                           .norm();
  const double turn =
      std::abs(std::remainder(result.T_to_from.theta_rad - pair.T_to_from.theta_rad, 2.0 * M_PI));
  return result.accepted && cells <= 2.0 && turn <= M_PI / 180.0;
}

/// Runs `merger` on the file's cases in turn, one merge per iteration on one core, each time
/// appended to `times_ms` and `after(result, pair)` called; false (the benchmark skipped) when
/// the shared maps are absent.
template <typename After>
bool mergeCases(benchmark::State& state, const char* file, MapMerger& merger,
                std::vector<double>& times_ms, After after) {
  cv::setNumThreads(1);  // one core
  const std::vector<merge_test::KnownCase> known = cases(file);
  if (known.empty()) {
    state.SkipWithError("needs ../shared/data/maps");
    return false;
  }
  std::size_t next = 0;
  for (auto _ : state) {
    const merge_test::KnownCase& pair = known[next++ % known.size()];
    after(timedMerge(merger, pair.from, pair.to, times_ms), pair);
  }
  return true;
}

/// `method` with the merge settings of `yaml` (a merge config's sections; "" for the defaults).
void BM_Merge400(benchmark::State& state, const char* method, const char* file, const char* yaml) {
  const std::unique_ptr<MapMerger> merger =
      makeMergerFrom(method, Config::loadString(yaml, "bench.yaml"));
  std::vector<double> times;
  int correct = 0;
  if (!mergeCases(state, file, *merger, times,
                  [&](const MergeResult& result, const merge_test::KnownCase& pair) {
                    correct += withinTolerance(result, pair) ? 1 : 0;
                  })) {
    return;
  }
  state.counters["median_ms"] = percentileOf(times, 0.5);
  state.counters["p90_ms"] = percentileOf(times, 0.9);
  state.counters["correct_share"] =
      static_cast<double>(correct) / static_cast<double>(times.size());
}
/// The exhaustive search over every rotation of the full turn, or near two peaks of the walls'
/// directions and their quarter turns only (`rotation_peaks`).
constexpr const char* kEveryRotation = "exhaustive: {rotation_peaks: 0}\n";
constexpr const char* kSuggestedTurns = "exhaustive: {rotation_peaks: 2, rotation_window_deg: 6}\n";
BENCHMARK_CAPTURE(BM_Merge400, exhaustive_intel, "exhaustive", "carpin-intel.txt", kEveryRotation)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(kCases);
BENCHMARK_CAPTURE(BM_Merge400, chain_intel, "chain", "carpin-intel.txt", kEveryRotation)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(kCases);
BENCHMARK_CAPTURE(BM_Merge400, exhaustive_turns_intel, "exhaustive", "carpin-intel.txt",
                  kSuggestedTurns)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(kCases);
BENCHMARK_CAPTURE(BM_Merge400, chain_turns_intel, "chain", "carpin-intel.txt", kSuggestedTurns)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(kCases);
/// Chains by name: the seed pipeline alone as a chain, and refined by Carpin's ψ random walk (the
/// difference is the refinement's cost).
BENCHMARK_CAPTURE(BM_Merge400, chain_seed_intel, "chain:seed", "carpin-intel.txt", "")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(kCases);
BENCHMARK_CAPTURE(BM_Merge400, chain_seed_psi_intel, "chain:seed+psi", "carpin-intel.txt", "")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(kCases);
/// Carpin's psi random walk as a merger of its own (walks from the exhaustive search's hypotheses).
BENCHMARK_CAPTURE(BM_Merge400, psi_walk_intel, "psi_walk", "carpin-intel.txt", "")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(kCases);
/// The virtual robot, its accepted merges verified by ψ over the overlap, and without that check
/// (the difference is the check's cost).
BENCHMARK_CAPTURE(BM_Merge400, virtual_intel, "virtual", "carpin-intel.txt", "")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(kCases);
BENCHMARK_CAPTURE(BM_Merge400, virtual_unchecked_intel, "virtual", "carpin-intel.txt",
                  "virtual: {max_overlap_psi: 1000}\n")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(kCases);

/// The median of `times` and each block of `total` as its share of their sum ("unaccounted": the
/// share no block holds).
void reportBlockShares(benchmark::State& state, const std::vector<double>& times,
                       const BlockTimes& total) {
  const double sum = totalOf(times);
  state.counters["median_ms"] = percentileOf(times, 0.5);
  for (const BlockTime& block : total) {
    state.counters[block.name] = block.ms / sum;
  }
  state.counters["unaccounted"] = 1.0 - totalMs(total) / sum;
}

/// The default merger (the chain, every setting its default) on the same cases: the median and
/// each block's share of the merges' total time (MapMerger::lastBlockTimes: the exhaustive
/// step's preparation, search, judge, the other way's judge and the alignment, the chain's
/// checks, any later step), "unaccounted" the chain's own time between them.
void BM_MergeBlocks400(benchmark::State& state, const char* file) {
  const std::unique_ptr<MapMerger> merger = makeMerger("chain");
  std::vector<double> times;
  BlockTimes total;
  int correct = 0;
  if (!mergeCases(state, file, *merger, times,
                  [&](const MergeResult& result, const merge_test::KnownCase& pair) {
                    correct += withinTolerance(result, pair) ? 1 : 0;
                    for (const BlockTime& block : merger->lastBlockTimes()) {
                      addBlockTime(total, block.name, block.ms);
                    }
                  })) {
    return;
  }
  reportBlockShares(state, times, total);
  state.counters["correct_share"] =
      static_cast<double>(correct) / static_cast<double>(times.size());
}
BENCHMARK_CAPTURE(BM_MergeBlocks400, intel, "carpin-intel.txt")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2 * kCases);
BENCHMARK_CAPTURE(BM_MergeBlocks400, freiburg_aces, "freiburg-aces.pgm")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2 * kCases);

/// The same for refusals: the default merger on pairs from two buildings (each turned Intel crop
/// of the cases above onto an ACES crop), its median, the share it accepted (wrongly) and each
/// block's share of the time. A refusal runs every step of the chain.
void BM_RefusalBlocks400(benchmark::State& state) {
  cv::setNumThreads(1);  // one core
  const std::vector<merge_test::KnownCase> intel = cases("carpin-intel.txt");
  const std::vector<merge_test::KnownCase> aces = cases("freiburg-aces.pgm");
  if (intel.empty() || aces.empty()) {
    state.SkipWithError("needs ../shared/data/maps");
    return;
  }
  const std::unique_ptr<MapMerger> merger = makeMerger("chain");
  std::vector<double> times;
  BlockTimes total;
  int accepted = 0;
  std::size_t next = 0;
  for (auto _ : state) {
    const std::size_t k = next++;
    const MergeResult result =
        timedMerge(*merger, intel[k % intel.size()].from, aces[(k + 5) % aces.size()].to, times);
    accepted += result.accepted ? 1 : 0;
    for (const BlockTime& block : merger->lastBlockTimes()) {
      addBlockTime(total, block.name, block.ms);
    }
  }
  reportBlockShares(state, times, total);
  state.counters["accepted_share"] =
      static_cast<double>(accepted) / static_cast<double>(times.size());
}
BENCHMARK(BM_RefusalBlocks400)->Unit(benchmark::kMillisecond)->Iterations(kCases);

/// The exhaustive search alone (exhaustive_search.hpp, default settings) on the same cases, each
/// searched three times in turn: summing every point of every node, and stopping a node's sums
/// once it cannot beat the bar (the default; the same hypotheses), whose medians and ratio of
/// total times are reported side by side; and near two peaks of the walls' turns only (its
/// median).
void BM_ExhaustiveSearch400(benchmark::State& state, const char* file) {
  cv::setNumThreads(1);  // one core
  const std::vector<merge_test::KnownCase> known = cases(file);
  if (known.empty()) {
    state.SkipWithError("needs ../shared/data/maps");
    return;
  }
  ExhaustiveSearchSettings every_point;
  every_point.rotation_peaks = 0;  // every rotation of the full turn
  every_point.stop_early = false;
  ExhaustiveSearchSettings stop_early;
  stop_early.rotation_peaks = 0;
  std::vector<double> early_ms;
  std::vector<double> every_ms;
  std::vector<double> turns_ms;
  ExhaustiveSearchSettings near_turns;
  near_turns.rotation_peaks = 2;
  near_turns.rotation_window_deg = 6.0;
  int same = 0;
  std::size_t next = 0;
  for (auto _ : state) {
    const merge_test::KnownCase& pair = known[next++ % known.size()];
    const auto search = [&](const ExhaustiveSearchSettings& settings, std::vector<double>& times) {
      const auto start = std::chrono::steady_clock::now();
      std::vector<ExhaustiveHypothesis> found = exhaustiveSearch(pair.from, pair.to, settings, {});
      times.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count());
      return found;
    };
    const std::vector<ExhaustiveHypothesis> early = search(stop_early, early_ms);
    const std::vector<ExhaustiveHypothesis> every = search(every_point, every_ms);
    search(near_turns, turns_ms);
    same += early.size() == every.size() &&
                    std::equal(early.begin(), early.end(), every.begin(),
                               [](const ExhaustiveHypothesis& a, const ExhaustiveHypothesis& b) {
                                 return a.score == b.score;
                               })
                ? 1
                : 0;
  }
  state.counters["median_ms"] = percentileOf(early_ms, 0.5);
  state.counters["every_point_median_ms"] = percentileOf(every_ms, 0.5);
  state.counters["suggested_turns_median_ms"] = percentileOf(turns_ms, 0.5);
  state.counters["time_ratio"] = totalOf(early_ms) / totalOf(every_ms);
  state.counters["same_share"] = static_cast<double>(same) / static_cast<double>(early_ms.size());
}
BENCHMARK_CAPTURE(BM_ExhaustiveSearch400, intel, "carpin-intel.txt")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(kCases);

/// The feature baseline on the same cases: the median, the share within tolerance and each
/// step's share of the time (FeatureMerger::lastTimings).
void BM_FeatureMerge400(benchmark::State& state, const char* file) {
  FeatureMerger merger(FeatureMergerSettings{});
  std::vector<double> times;
  FeatureMergeTimings total;
  int correct = 0;
  if (!mergeCases(state, file, merger, times,
                  [&](const MergeResult& result, const merge_test::KnownCase& pair) {
                    correct += withinTolerance(result, pair) ? 1 : 0;
                    const FeatureMergeTimings& last = merger.lastTimings();
                    total.detection += last.detection;
                    total.matching += last.matching;
                    total.ransac += last.ransac;
                    total.verification += last.verification;
                  })) {
    return;
  }
  state.counters["median_ms"] = percentileOf(times, 0.5);
  state.counters["correct_share"] =
      static_cast<double>(correct) / static_cast<double>(times.size());
  const double sum = (total.detection + total.matching + total.ransac + total.verification).count();
  state.counters["detection"] = total.detection.count() / sum;
  state.counters["matching"] = total.matching.count() / sum;
  state.counters["ransac"] = total.ransac.count() / sum;
  state.counters["verification"] = total.verification.count() / sum;
}
BENCHMARK_CAPTURE(BM_FeatureMerge400, intel, "carpin-intel.txt")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3 * kCases);
BENCHMARK_CAPTURE(BM_FeatureMerge400, freiburg_aces, "freiburg-aces.pgm")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3 * kCases);

void BM_MergeWholeBuilding(benchmark::State& state, const char* method) {
  cv::setNumThreads(1);  // one core
  const std::string path = std::string(MRSLAM_DATA_DIR) + "/maps/freiburg-aces.pgm";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("needs ../shared/data/maps");
    return;
  }
  const SourceMap source{"freiburg-aces.pgm", "aces", merge_test::loadMap(path)};
  const MergeCase pair = makeCase(source, {{150, 120}, 700, 0.6, {10, 20}, {30, 5}}, source,
                                  {{380, 330}, 700, -0.35, {25, 3}, {4, 18}});
  const std::unique_ptr<MapMerger> merger = makeMerger(method);
  std::vector<double> times;
  int correct = 0;
  for (auto _ : state) {
    const MergeResult result = timedMerge(*merger, pair.a, pair.b, times);
    correct += result.accepted && isCorrect(caseError(pair, result.T_to_from)) ? 1 : 0;
  }
  state.counters["median_ms"] = percentileOf(times, 0.5);
  state.counters["correct_share"] =
      static_cast<double>(correct) / static_cast<double>(times.size());
}
BENCHMARK_CAPTURE(BM_MergeWholeBuilding, seed, "seed")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_MergeWholeBuilding, exhaustive, "exhaustive")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

double milliseconds(SeedMergeTimings::Duration duration) {
  return duration.count();
}

void BM_SeedMerge400(benchmark::State& state, const char* file) {
  SeedMerger merger;
  std::vector<double> times;
  SeedMergeTimings total;
  int accepted = 0;
  if (!mergeCases(state, file, merger, times,
                  [&](const MergeResult& result, const merge_test::KnownCase&) {
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
                    total.alignment += last.alignment;
                  })) {
    return;
  }
  std::nth_element(times.begin(), times.begin() + static_cast<long>(times.size() / 2), times.end());
  state.counters["median_ms"] = times[times.size() / 2];
  state.counters["accepted_share"] =
      static_cast<double>(accepted) / static_cast<double>(times.size());
  const double sum = milliseconds(total.edges + total.radon + total.segments + total.correlation +
                                  total.poses + total.translation + total.verification +
                                  total.fallback + total.global + total.alignment);
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
  share("alignment", total.alignment);
}
BENCHMARK_CAPTURE(BM_SeedMerge400, intel, "carpin-intel.txt")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3 * kCases);
BENCHMARK_CAPTURE(BM_SeedMerge400, freiburg_aces, "freiburg-aces.pgm")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3 * kCases);

}  // namespace
}  // namespace mrslam::fusion

// As in the fusion agent and the merge tools, freed memory is kept for the next merge; with
// --default_heap the C library's own settings are measured instead.
int main(int argc, char** argv) {
  bool default_heap = false;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--default_heap") {
      default_heap = true;
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  if (!default_heap && !mrslam::retainHeapForReuse()) {
    std::fprintf(stderr, "merge_bench: the C library keeps its own heap settings\n");
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
    return 1;
  }
  benchmark::AddCustomContext("heap", default_heap ? "default" : "retained for reuse");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
