#pragma once
// The free-space skeleton of a map (seed 002, §3.1): free cells thinned to one-cell-wide lines
// that keep the free space's connectivity, by the two sub-iterations of Zhang & Suen's parallel
// thinning. A cell P with neighbours P2…P9 (clockwise from north) is removed when
//   2 ≤ B(P) ≤ 6        (B: free neighbours),
//   A(P) = 1            (A: free-after-not-free transitions around P2, P3, …, P9, P2),
//   first pass:  P2·P4·P6 = 0 and P4·P6·P8 = 0   (south-east boundary and north-west corner),
//   second pass: P2·P4·P8 = 0 and P2·P6·P8 = 0   (north-west boundary and south-east corner),
// and the two passes repeat until neither removes a cell (each pass looks only at the set cells
// beside an unset one: with B(P) = 8 no other can go). The virtual robot walks the skeleton.

#include <opencv2/core.hpp>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {

/// Thins a binary image (non-zero: set) in place; returns the passes made.
int thinZhangSuen(cv::Mat& binary);

/// The skeleton of `map`'s free cells (occupancy ≤ free_threshold): 255 on it, 0 elsewhere.
/// Islands of other cells of at most `max_hole_cells` (noise, a chair leg) are taken as free
/// first: each would otherwise put a loop into the skeleton.
cv::Mat freeSpaceSkeleton(const GridMap& map, const SimilaritySettings& settings,
                          int max_hole_cells = 4);

}  // namespace mrslam::fusion
