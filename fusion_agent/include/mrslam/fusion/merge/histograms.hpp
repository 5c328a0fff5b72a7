#pragma once
// Block 4 of the seed merge: segment verification with the distance and arc histograms.
//
// 1. The distance histogram counts the D values of a segment in `distance_bins` equal bins
//    over [min D, max D]; the arc histogram counts its turning angles Δ in `arc_bins` equal bins
//    over [-π, π]. Both are normalised to sum 1 (block 5 correlates them).
// 2. A segment is kept only when
//    - max D - min D ≥ hd: it bends away from its fitted line, so it fixes a pose (a flat wall
//      leaves the translation along it free and is refused);
//    - no distance bin is empty: its points spread continuously over that range (a gap means the
//      edge following jumped between separate structures);
//    - max |Δ| ≤ ωc: no hairpin or spike (the end cap of a thick wall, noise).
//    An L-shaped corner passes all three.

#include <vector>

#include "mrslam/fusion/merge/segments.hpp"

namespace mrslam::fusion {

/// Settings of block 4.
struct SegmentVerificationSettings {
  int distance_bins = 6;             ///< bins of the distance histogram over [min D, max D]
  int arc_bins = 12;                 ///< bins of the arc histogram of Δ over [-π, π]
  double histogram_spread_hd = 4.0;  ///< hd: least max D - min D (cells) of a kept segment
  double max_turn_omega_c = 2.0;     ///< ωc: largest turning angle |Δ| (rad) of a kept segment
};

/// The two histograms of a segment, each normalised to sum 1 (all zero when empty).
struct SegmentHistograms {
  std::vector<double> distance;  ///< of D over [min D, max D]
  std::vector<double> arc;       ///< of Δ over [-π, π]
};

enum class SegmentVerdict {
  kAccepted,
  kFlat,              ///< max D - min D < hd
  kEmptyDistanceBin,  ///< the points do not spread continuously
  kSharpTurn,         ///< max |Δ| > ωc
};

/// Block 4.1: the normalised histograms of a segment.
SegmentHistograms segmentHistograms(const Segment& segment,
                                    const SegmentVerificationSettings& settings);

/// Block 4.2: whether a segment has the shape to fix a pose.
SegmentVerdict verifySegment(const Segment& segment, const SegmentHistograms& histograms,
                             const SegmentVerificationSettings& settings);

}  // namespace mrslam::fusion
