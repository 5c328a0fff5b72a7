// The virtual robot's scan likelihoods (virtual_robot.hpp) on one core: every particle of one
// localisation step weighted by every scan of a walk, read from the distance field itself (a float
// read, the cap, the square and the division at every point) against HitCosts (one byte and one
// table read a point, hit_costs.hpp). Both give the same sums (`same_share` counts the cases where
// every sum is equal, bit for bit); `time_ratio` is the table's total time over the field's.
// The cases are the 400 × 400 crops of the merge benchmark: scans of `from` along its skeleton,
// 4000 particles on `to`'s skeleton, as the virtual robot draws them.
#include <benchmark/benchmark.h>

#include <chrono>
#include <random>
#include <string>
#include <vector>

#include "crop_cases.hpp"
#include "mrslam/fusion/merge/hit_costs.hpp"
#include "mrslam/fusion/merge/skeleton.hpp"
#include "mrslam/fusion/merge/virtual_robot.hpp"

namespace mrslam::fusion {
namespace {

using bench::kCases;
using bench::percentileOf;
using bench::totalOf;

constexpr int kWallOccupancy = 65;  // as the virtual robot's walls
constexpr int kParticles = 4000;
constexpr double kSigma = 1.5;
constexpr double kCap = 3.0 * kSigma;

struct LikelihoodCase {
  cv::Mat distance;
  std::vector<std::vector<Eigen::Vector2d>> scans;
  std::vector<SE2> particles;
};

std::vector<cv::Point> setCells(const cv::Mat& image) {
  std::vector<cv::Point> cells;
  cv::findNonZero(image, cells);
  return cells;
}

std::vector<LikelihoodCase> likelihoodCases(const std::string& file) {
  const SimilaritySettings classes;
  const VirtualRobotSettings settings;
  std::mt19937_64 random(3);
  std::vector<LikelihoodCase> result;
  for (const merge_test::KnownCase& known : bench::cases(file)) {
    const cv::Mat skeleton_from = freeSpaceSkeleton(known.from, classes);
    const std::vector<cv::Point> starts = setCells(skeleton_from);
    const std::vector<cv::Point> places = setCells(freeSpaceSkeleton(known.to, classes));
    if (starts.empty() || places.empty()) {
      continue;
    }
    LikelihoodCase next;
    next.distance = wallDistance(known.to, kWallOccupancy);
    const cv::Point start = starts[random() % starts.size()];
    for (const CellPose& pose : skeletonWalk(skeleton_from, Eigen::Vector2i(start.x, start.y),
                                             settings.path_poses, settings.path_step_cells)) {
      next.scans.push_back(scanPointsUsed(virtualScan(known.from, pose, settings)));
    }
    std::uniform_real_distribution<double> jitter(-0.5, 0.5);
    std::uniform_real_distribution<double> heading(-M_PI, M_PI);
    for (int i = 0; i < kParticles; ++i) {
      const cv::Point place = places[random() % places.size()];
      next.particles.emplace_back(place.x + jitter(random), place.y + jitter(random),
                                  heading(random));
    }
    result.push_back(std::move(next));
  }
  return result;
}

/// The sum as read from the field itself: the capped distance squared over 2σ² at each point.
double fieldLogLikelihood(const cv::Mat& distance, const std::vector<Eigen::Vector2d>& points,
                          const SE2& pose) {
  double sum = 0.0;
  for (const Eigen::Vector2d& point : points) {
    const Eigen::Vector2d p = pose * point;
    const int x = roundToInt(p.x());
    const int y = roundToInt(p.y());
    double d = kCap;
    if (x >= 0 && y >= 0 && x < distance.cols && y < distance.rows) {
      d = std::min(kCap, static_cast<double>(distance.at<float>(y, x)));
    }
    sum -= d * d / (2.0 * kSigma * kSigma);
  }
  return sum;
}

template <typename LogLikelihood>
std::vector<double> weighAll(const LikelihoodCase& known, const LogLikelihood& log_likelihood) {
  std::vector<double> weights(known.particles.size(), 0.0);
  for (const std::vector<Eigen::Vector2d>& scan : known.scans) {
    for (std::size_t i = 0; i < known.particles.size(); ++i) {
      weights[i] += log_likelihood(scan, known.particles[i]);
    }
  }
  return weights;
}

void BM_ScanLikelihoods400(benchmark::State& state, const char* file) {
  const std::vector<LikelihoodCase> cases = likelihoodCases(file);
  if (cases.empty()) {
    state.SkipWithError("needs ../shared/data/maps");
    return;
  }
  std::vector<double> field_ms;
  std::vector<double> table_ms;
  int same = 0;
  std::size_t next = 0;
  const auto timed = [](std::vector<double>& times, const auto& weigh) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<double> weights = weigh();
    times.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    return weights;
  };
  for (auto _ : state) {
    const LikelihoodCase& known = cases[next++ % cases.size()];
    const std::vector<double> by_field = timed(field_ms, [&] {
      return weighAll(known, [&](const auto& scan, const SE2& pose) {
        return fieldLogLikelihood(known.distance, scan, pose);
      });
    });
    const std::vector<double> by_table = timed(table_ms, [&] {
      const HitCosts costs(known.distance, kCap, kSigma);  // built once a merge, timed with it
      return weighAll(known, [&](const auto& scan, const SE2& pose) {
        return costs.scanLogLikelihood(scan, pose);
      });
    });
    same += by_field == by_table ? 1 : 0;
    benchmark::DoNotOptimize(by_table.data());
  }
  state.counters["field_median_ms"] = percentileOf(field_ms, 0.5);
  state.counters["table_median_ms"] = percentileOf(table_ms, 0.5);
  state.counters["time_ratio"] = totalOf(table_ms) / totalOf(field_ms);
  state.counters["same_share"] = static_cast<double>(same) / static_cast<double>(field_ms.size());
}
BENCHMARK_CAPTURE(BM_ScanLikelihoods400, intel, "carpin-intel.txt")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2 * kCases);
BENCHMARK_CAPTURE(BM_ScanLikelihoods400, freiburg_aces, "freiburg-aces.pgm")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2 * kCases);

}  // namespace
}  // namespace mrslam::fusion

BENCHMARK_MAIN();
