#pragma once
// The 400 × 400 crop pairs the merge benchmarks share (merge_bench.cpp, radon_bench.cpp): 12
// seeded known-answer cases of one shared map at 40–100 % overlap, and the percentile of a run's
// times.

#include <algorithm>
#include <filesystem>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "../tests/unit/fusion/merge_test_maps.hpp"

namespace mrslam::fusion::bench {

constexpr int kCases = 12;
constexpr int kSize = 400;

/// The cases of the shared map `file` (empty when the shared maps are absent).
inline std::vector<merge_test::KnownCase> cases(const std::string& file) {
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

/// The value at `fraction` of the sorted values (rank rounded down).
inline double percentileOf(std::vector<double> values, double fraction) {
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1));
  return values[rank];
}

/// The sum of the times (or any values).
inline double totalOf(const std::vector<double>& values) {
  return std::accumulate(values.begin(), values.end(), 0.0);
}

}  // namespace mrslam::fusion::bench
