#pragma once
// Block 5 of the seed merge: cross correlation of two segments, one from each map.
//
// 1. Histogram score: the mean of the normalised cross correlations (Pearson) of the two
//    distance histograms and of the two arc histograms.
// 2. Sequence score: the segments start at random cells, so the same wall appears shifted along
//    the segment, and it may be walked the other way (reversing a segment reverses D and Δ and
//    negates Δ). For both directions and every offset that overlaps at least
//    `min_overlap_fraction` of the points, the normalised cross correlation of the overlapping Δ;
//    at the best offset, the mean of that and of the correlation of D over the overlap, with D
//    measured from lines fitted to the two overlapping spans alone (a segment's own D depends on
//    its whole extent, which differs between two cuts of one wall). The best direction wins.
// 3. Score = w · histogram score + (1 - w) · sequence score, w = `histogram_weight`.
// The matched span (`offset`, `reversed`) pairs point i of the first segment with point
// i + offset of the second (reversed when `reversed`): block 6 fits its pose to that span.

#include <vector>

#include "mrslam/fusion/merge/histograms.hpp"
#include "mrslam/fusion/merge/segments.hpp"

namespace mrslam::fusion {

/// Settings of block 5.
struct CorrelationSettings {
  double histogram_weight = 0.3;      ///< w: share of the histogram score in a pair's score
  double min_overlap_fraction = 0.6;  ///< least share of the points an offset must overlap
};

/// How well two segments match, and where.
struct SegmentMatch {
  double score = -1.0;            ///< w · histogram_score + (1 - w) · sequence_score
  double histogram_score = -1.0;  ///< mean normalised correlation of the two histograms
  double sequence_score = -1.0;   ///< mean normalised correlation of D and Δ at `offset`
  int offset = 0;                 ///< point i of the first ↔ point i + offset of the second
  bool reversed = false;          ///< the second segment is walked backwards
};

/// Normalised (zero-mean, unit-variance) cross correlation of two equal-length sequences at
/// zero lag, in [-1, 1]; 0 when either is constant.
double normalizedCorrelation(const double* a, const double* b, std::size_t count);

/// The histogram score alone (block 5.1): cheap, so it can rank all pairs first.
double histogramScore(const SegmentHistograms& a, const SegmentHistograms& b, bool reversed);

/// Blocks 5.1-5.3 for one pair.
SegmentMatch matchSegments(const Segment& a, const SegmentHistograms& histograms_a,
                           const Segment& b, const SegmentHistograms& histograms_b,
                           const CorrelationSettings& settings);

/// The same with `b` walked backwards given (reversedSegment(b), computed once per segment).
SegmentMatch matchSegments(const Segment& a, const SegmentHistograms& histograms_a,
                           const Segment& b, const Segment& b_reversed,
                           const SegmentHistograms& histograms_b,
                           const CorrelationSettings& settings);

/// Segment `b` walked backwards (points, D and Δ reversed, Δ negated).
Segment reversedSegment(const Segment& b);

}  // namespace mrslam::fusion
