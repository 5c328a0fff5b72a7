#include "mrslam/fusion/merge/correlation.hpp"

#include <algorithm>
#include <cmath>

namespace mrslam::fusion {

namespace {

struct OffsetScore {
  double score = -2.0;
  int offset = 0;
};

// Distances of points[first, first + count) to the line fitted to just those points.
std::vector<double> spanDistances(const std::vector<Eigen::Vector2d>& points, int first,
                                  int count) {
  const FittedLine line =
      fitLine(points, static_cast<std::size_t>(first), static_cast<std::size_t>(count));
  const Eigen::Vector2d normal(-std::sin(line.angle_rad), std::cos(line.angle_rad));
  std::vector<double> distances;
  for (int i = first; i < first + count; ++i) {
    distances.push_back(std::abs(normal.dot(points[static_cast<std::size_t>(i)] - line.centroid)));
  }
  return distances;
}

// The best offset of b against a: Δ is correlated at every offset; D, measured from lines
// fitted to the two overlapping spans alone (so that both refer to the same stretch of wall),
// at the best one.
OffsetScore bestOffset(const Segment& a, const Segment& b, double min_overlap_fraction) {
  const int n = static_cast<int>(std::min(a.distances.size(), b.distances.size()));
  const int k = (n - static_cast<int>(a.turns.size())) / 2;
  const int least = std::max(2 * k + 3, static_cast<int>(std::ceil(min_overlap_fraction * n)));
  OffsetScore best;
  double best_turns = -2.0;
  for (int offset = -(n - least); offset <= n - least; ++offset) {
    const int first = std::max(0, -offset);  // first point of a in the overlap
    const int turn_count = n - std::abs(offset) - 2 * k;
    const double turns = normalizedCorrelation(&a.turns[static_cast<std::size_t>(first)],
                                               &b.turns[static_cast<std::size_t>(first + offset)],
                                               static_cast<std::size_t>(turn_count));
    if (turns > best_turns) {
      best_turns = turns;
      best.offset = offset;
    }
  }
  const int first = std::max(0, -best.offset);
  const int count = n - std::abs(best.offset);
  const std::vector<double> span_a = spanDistances(a.points, first, count);
  const std::vector<double> span_b = spanDistances(b.points, first + best.offset, count);
  const double distances =
      normalizedCorrelation(span_a.data(), span_b.data(), static_cast<std::size_t>(count));
  best.score = 0.5 * (best_turns + distances);
  return best;
}

}  // namespace

double normalizedCorrelation(const double* a, const double* b, std::size_t count) {
  if (count == 0) {
    return 0.0;
  }
  double sum_a = 0.0;
  double sum_b = 0.0;
  double sum_ab = 0.0;
  double sum_aa = 0.0;
  double sum_bb = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    sum_a += a[i];
    sum_b += b[i];
    sum_ab += a[i] * b[i];
    sum_aa += a[i] * a[i];
    sum_bb += b[i] * b[i];
  }
  const double n = static_cast<double>(count);
  const double ab = sum_ab - sum_a * sum_b / n;  // n · covariance
  const double aa = sum_aa - sum_a * sum_a / n;
  const double bb = sum_bb - sum_b * sum_b / n;
  constexpr double kTiny = 1e-9;
  return aa > kTiny && bb > kTiny ? std::clamp(ab / std::sqrt(aa * bb), -1.0, 1.0) : 0.0;
}

double histogramScore(const SegmentHistograms& a, const SegmentHistograms& b, bool reversed) {
  const double distance =
      normalizedCorrelation(a.distance.data(), b.distance.data(), a.distance.size());
  std::vector<double> arc_b = b.arc;
  if (reversed) {  // walking backwards negates every turn: the arc histogram mirrors
    std::reverse(arc_b.begin(), arc_b.end());
  }
  const double arc = normalizedCorrelation(a.arc.data(), arc_b.data(), a.arc.size());
  return 0.5 * (distance + arc);
}

Segment reversedSegment(const Segment& b) {
  Segment reversed = b;
  std::reverse(reversed.points.begin(), reversed.points.end());
  std::reverse(reversed.distances.begin(), reversed.distances.end());
  std::reverse(reversed.turns.begin(), reversed.turns.end());
  for (double& turn : reversed.turns) {
    turn = -turn;
  }
  return reversed;
}

SegmentMatch matchSegments(const Segment& a, const SegmentHistograms& histograms_a,
                           const Segment& b, const SegmentHistograms& histograms_b,
                           const CorrelationSettings& settings) {
  return matchSegments(a, histograms_a, b, reversedSegment(b), histograms_b, settings);
}

SegmentMatch matchSegments(const Segment& a, const SegmentHistograms& histograms_a,
                           const Segment& b, const Segment& b_reversed,
                           const SegmentHistograms& histograms_b,
                           const CorrelationSettings& settings) {
  SegmentMatch best;
  for (const bool reversed : {false, true}) {
    const OffsetScore sequence =
        bestOffset(a, reversed ? b_reversed : b, settings.min_overlap_fraction);
    const double histogram = histogramScore(histograms_a, histograms_b, reversed);
    const double score =
        settings.histogram_weight * histogram + (1.0 - settings.histogram_weight) * sequence.score;
    if (score > best.score) {
      best = {score, histogram, sequence.score, sequence.offset, reversed};
    }
  }
  return best;
}

}  // namespace mrslam::fusion
