// The Radon angular profile of a 400 × 400 crop's walls (the exhaustive search's suggested turns,
// radon.hpp), on one core: through the Radon image (radonTransform, then radonSpectrum) against
// radonSpectrumOfCells, which counts each angle in one row and keeps no image. Both give the same
// profile (`same_share` counts the crops where every value is equal); `time_ratio` is the second's
// total time over the first's.
#include <benchmark/benchmark.h>

#include <chrono>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "crop_cases.hpp"
#include "mrslam/fusion/merge/edges.hpp"
#include "mrslam/fusion/merge/radon.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {
namespace {

using bench::kCases;
using bench::kSize;
using bench::percentileOf;
using bench::totalOf;

/// The wall cells of the turned crops of the merge benchmark's cases (each case's `from`).
std::vector<std::vector<cv::Point>> wallsOfCrops(const std::string& file) {
  const SimilaritySettings classes;
  std::vector<std::vector<cv::Point>> crops;
  for (const merge_test::KnownCase& known : bench::cases(file)) {
    crops.push_back(nonZeroCells(occupiedImage(known.from, classes.occupied_threshold)));
  }
  return crops;
}

void BM_RadonProfile400(benchmark::State& state, const char* file) {
  cv::setNumThreads(1);
  const std::vector<std::vector<cv::Point>> crops = wallsOfCrops(file);
  if (crops.empty()) {
    state.SkipWithError("needs ../shared/data/maps");
    return;
  }
  const RadonSettings radon;
  const cv::Size size(kSize, kSize);
  std::vector<double> image_ms;
  std::vector<double> cells_ms;
  int same = 0;
  std::size_t next = 0;
  double walls = 0.0;
  for (auto _ : state) {
    const std::vector<cv::Point>& cells = crops[next++ % crops.size()];
    walls += static_cast<double>(cells.size());
    const auto timed = [](std::vector<double>& times, const auto& profile) {
      const auto start = std::chrono::steady_clock::now();
      std::vector<double> result = profile();
      times.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count());
      return result;
    };
    const std::vector<double> by_image = timed(image_ms, [&] {
      return radonSpectrum(radonTransform(cells, size, radon.angle_step_rad),
                           radon.profile_highpass_rad);
    });
    const std::vector<double> by_cells = timed(cells_ms, [&] {
      return radonSpectrumOfCells(cells, size, radon.angle_step_rad, radon.profile_highpass_rad);
    });
    same += by_image == by_cells ? 1 : 0;
    benchmark::DoNotOptimize(by_cells.data());
  }
  state.counters["image_median_ms"] = percentileOf(image_ms, 0.5);
  state.counters["cells_median_ms"] = percentileOf(cells_ms, 0.5);
  state.counters["time_ratio"] = totalOf(cells_ms) / totalOf(image_ms);
  state.counters["same_share"] = static_cast<double>(same) / static_cast<double>(image_ms.size());
  state.counters["walls"] = walls / static_cast<double>(image_ms.size());
}
BENCHMARK_CAPTURE(BM_RadonProfile400, intel, "carpin-intel.txt")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(4 * kCases);
BENCHMARK_CAPTURE(BM_RadonProfile400, freiburg_aces, "freiburg-aces.pgm")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(4 * kCases);

}  // namespace
}  // namespace mrslam::fusion

BENCHMARK_MAIN();
