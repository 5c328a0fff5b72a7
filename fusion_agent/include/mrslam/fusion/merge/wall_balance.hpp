#pragma once

// The wall balance of a transform at every integer shift around it, for block 8's wall
// anchoring: near - far of structureAgreement() summed over a window of shifts at once. Each
// wall sample is placed once and the (2r + 1)² shifts become a window read from an image of
// +1 (known, within one cell of a wall), -1 (known, away from walls) and 0 (unknown), so a
// sample costs one row of additions per shift row instead of a placement per shift.

#include <vector>

#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {

/// Σ over `centres` of `values` (CV_8S) at centre + (dx, dy) for dx, dy = -reach, -reach + step,
/// ... up to reach, cells off the image counting 0; in row order (dy, then dx). The sums of a
/// score that adds one cell per sample, at every whole-cell shift of the samples at once.
std::vector<long long> windowSums(const cv::Mat& values, const std::vector<cv::Point>& centres,
                                  int reach, int step);

/// CV_8S image of a code image's cells: +1 known and within one cell of a wall, -1 known and
/// away from walls, 0 unknown (the terms of StructureAgreement's near - far).
cv::Mat wallBalanceImage(const CodeImage& image);

/// near - far of structureAgreement(samples, to, T_to_from shifted by (dx, dy)) for every
/// dx, dy within ±reach, in row order (dy, then dx). `balance_to` is wallBalanceImage(to).
std::vector<long long> wallBalancesAfterShifts(const std::vector<CellSample>& samples,
                                               const CodeImage& to, const cv::Mat& balance_to,
                                               const GridTransform& T_to_from, int reach,
                                               const ComparisonTables& tables);

/// The reverse direction: near - far of structureAgreement(samples_to, from, (T_to_from shifted
/// by (dx, dy))⁻¹), samples of `to` placed on `from`, in the same order. `balance_from` is
/// wallBalanceImage(from).
std::vector<long long> wallBalancesOfInverseShifts(const std::vector<CellSample>& samples_to,
                                                   const CodeImage& from,
                                                   const cv::Mat& balance_from,
                                                   const GridTransform& T_to_from, int reach,
                                                   const ComparisonTables& tables);

}  // namespace mrslam::fusion
