#pragma once
// How well two maps agree under a cell transform: the verification index of the seed paper
// (V = agr / (agr + dis)) and the map entropy of the merged pair, as the tools score every
// merger. Plus the conversion of a GridTransform to the image coordinates of the map files.

#include <Eigen/Core>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"

namespace mrslam::fusion {

/// The class of a cell value: free (0..49), occupied (51..100); unknown (-1) and 50 have none.
enum class CellClass { kNone, kFree, kOccupied };
CellClass classOf(std::int8_t value);

/// The overlap of map `from`, moved by T_to_from, with map `to`. Every cell of `from` with a class
/// is carried to the nearest cell of `to` (its centre through T_to_from, rounded); where that cell
/// has a class too, the pair counts as an agreement (same class) or a disagreement.
struct OverlapScore {
  std::size_t agreement = 0;     ///< agr: cells known in both maps with the same class
  std::size_t disagreement = 0;  ///< dis: cells known in both maps with different classes
  double entropy_bits = 0.0;     ///< H: mean binary entropy (bits) of the merged pair's cells

  std::size_t overlap() const { return agreement + disagreement; }
  /// V = agr / (agr + dis); 0 when the maps do not overlap.
  double verification() const {
    return overlap() == 0 ? 0.0 : static_cast<double>(agreement) / static_cast<double>(overlap());
  }
};

/// Scores T_to_from. The merged pair for H: every known cell of `to`, and every known cell of
/// `from` at its place in `to`'s cell frame; where both are known the merged occupancy is the mean
/// of the two probabilities (v / 100). H is the mean over those cells of
/// -p log2 p - (1 - p) log2 (1 - p): 0 for a crisp merge, 1 bit per cell where the maps contradict.
OverlapScore scoreOverlap(const GridMap& from, const GridMap& to, const GridTransform& T_to_from);

/// A 2 × 3 affine transform [A | b] of image pixel coordinates: p' = A p + b.
using ImageAffine = Eigen::Matrix<double, 2, 3>;

/// T_to_from in the image coordinates of the two maps' files: (column, row) with row 0 the FIRST
/// row of the file (the top of the map), while GridTransform counts rows from the bottom. With
/// F = diag(1, -1): A = F R F = R(-theta), b = F (R (0, hf - 1) + t) + (0, ht - 1), where hf and
/// ht are the heights of the maps `from` and `to`.
ImageAffine gridTransformToImageAffine(const GridTransform& T_to_from, int from_height,
                                       int to_height);
/// The inverse conversion; the rotation is read from the first column of A (a rigid A assumed).
GridTransform imageAffineToGridTransform(const ImageAffine& affine, int from_height, int to_height);

}  // namespace mrslam::fusion
