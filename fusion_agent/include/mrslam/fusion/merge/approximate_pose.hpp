#pragma once
// Block 6 of the seed merge: the approximate pose from one matched pair of segments.
//
// 1. Lines are fitted (total least squares) to the matched spans of the two segments, the
//    segment of map `from` and the segment of map `to`.
// 2. Rotation: the difference of the two lines' angles. A line's angle is known modulo π, so
//    the rotation is too: both θ and θ + π are returned and tried.
// 3. Translation from the centroids of the matched spans: t = c_to - R(θ) c_from.

#include <array>
#include <utility>

#include "mrslam/fusion/merge/correlation.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/merge/segments.hpp"

namespace mrslam::fusion {

/// Blocks 6.2-6.3 for two fitted lines: the two candidate transforms T_to_from.
std::array<GridTransform, 2> posesFromLines(const FittedLine& from, const FittedLine& to);

/// Block 6.1: the lines fitted to the matched spans of a pair of segments (`match` from
/// matchSegments(from, ·, to, ·)); first of `from`, second of `to`.
std::pair<FittedLine, FittedLine> matchedLines(const Segment& from, const Segment& to,
                                               const SegmentMatch& match);

/// Blocks 6.1-6.3 for a matched pair of segments.
std::array<GridTransform, 2> approximatePoses(const Segment& from, const Segment& to,
                                              const SegmentMatch& match);

/// The translation that maps `centroid_from` onto `centroid_to` under rotation `theta_rad`.
Eigen::Vector2d translationFromCentroids(double theta_rad, const Eigen::Vector2d& centroid_from,
                                         const Eigen::Vector2d& centroid_to);

}  // namespace mrslam::fusion
