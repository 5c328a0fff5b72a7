#include "mrslam/fusion/merge/histograms.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mrslam::fusion {

namespace {

// Counts values in `bins` equal bins over [low, high]; the top value goes into the last bin.
std::vector<double> histogram(const std::vector<double>& values, int bins, double low,
                              double high) {
  std::vector<double> counts(static_cast<std::size_t>(std::max(1, bins)), 0.0);
  const double width = (high - low) / static_cast<double>(counts.size());
  for (const double value : values) {
    int bin = width > 0.0 ? static_cast<int>((value - low) / width) : 0;
    bin = std::clamp(bin, 0, static_cast<int>(counts.size()) - 1);
    counts[static_cast<std::size_t>(bin)] += 1.0;
  }
  return counts;
}

void normalise(std::vector<double>& counts) {
  const double total = std::accumulate(counts.begin(), counts.end(), 0.0);
  if (total > 0.0) {
    for (double& count : counts) {
      count /= total;
    }
  }
}

}  // namespace

SegmentHistograms segmentHistograms(const Segment& segment,
                                    const SegmentVerificationSettings& settings) {
  SegmentHistograms histograms;
  if (!segment.distances.empty()) {
    const auto [low, high] =
        std::minmax_element(segment.distances.begin(), segment.distances.end());
    histograms.distance = histogram(segment.distances, settings.distance_bins, *low, *high);
  } else {
    histograms.distance.assign(static_cast<std::size_t>(settings.distance_bins), 0.0);
  }
  histograms.arc = histogram(segment.turns, settings.arc_bins, -M_PI, M_PI);
  normalise(histograms.distance);
  normalise(histograms.arc);
  return histograms;
}

SegmentVerdict verifySegment(const Segment& segment, const SegmentHistograms& histograms,
                             const SegmentVerificationSettings& settings) {
  if (segment.distances.empty()) {
    return SegmentVerdict::kFlat;
  }
  const auto [low, high] = std::minmax_element(segment.distances.begin(), segment.distances.end());
  if (*high - *low < settings.histogram_spread_hd) {
    return SegmentVerdict::kFlat;
  }
  if (std::any_of(histograms.distance.begin(), histograms.distance.end(),
                  [](double count) { return count <= 0.0; })) {
    return SegmentVerdict::kEmptyDistanceBin;
  }
  for (const double turn : segment.turns) {
    if (std::abs(turn) > settings.max_turn_omega_c) {
      return SegmentVerdict::kSharpTurn;
    }
  }
  return SegmentVerdict::kAccepted;
}

}  // namespace mrslam::fusion
