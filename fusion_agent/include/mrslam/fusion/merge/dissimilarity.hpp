#pragma once
// Carpin's map dissimilarity (seed 002, eq. 11-13; after Birk & Carpin) and the distance maps it
// is computed from (seed 002, Algorithm 1).
//
// A distance map of class c holds, for every cell, the Manhattan distance to the nearest cell of
// class c (occupied or free), computed in two passes over the grid: top-left to bottom-right
// with the left and upper neighbours, then back with the right and lower ones. Linear in the
// number of cells.
//
//   d(m1, m2, c) = Σ over cells p of class c in m1 of dist_c(m2)[T(p)] / #c(m1)
//   ψ(m1, m2)    = Σ over c ∈ {occupied, free} of d(m1, m2, c) + d(m2, m1, c)
//
// Here m1 = `from` mapped into m2 = `to` by T_to_from (and m2 back by its inverse); cells that
// land outside the other map are left out of both the sum and the count. ψ = 0 for maps that
// agree cell for cell; it grows with every cell that lands away from cells of its class.
//
// ψ over the overlap (overlapDissimilarity) counts only the cells that land on a known cell of the
// other map. Plain ψ also counts the cells that land on the other map's unknown space, whose
// distances measure how much of the maps does not overlap, not whether the overlap agrees: two
// right merges of crops at 20 % and 80 % overlap differ in ψ by tens of cells.

#include <cstdint>
#include <limits>
#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {

/// The two cell classes of the dissimilarity ψ. (overlap_score.hpp's CellClass has a third, kNone:
/// two enums of one name in one namespace break the one-definition rule, as -flto reports.)
enum class PsiClass : std::uint8_t { kOccupied = 0, kFree = 1 };

/// Manhattan distances (cells) to the nearest cell of one class; kFar where there is none.
struct DistanceMap {
  static constexpr std::int32_t kFar = std::numeric_limits<std::int32_t>::max() / 4;
  int width = 0;
  int height = 0;
  std::vector<std::int32_t> distance;  ///< row by row
  /// Row-by-row index of cell (x, y), in `distance` and in any grid of the same size.
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(x);
  }
  std::int32_t at(int x, int y) const { return distance[index(x, y)]; }
};

/// Algorithm 1 of seed 002 for the cells of `cell_class` (thresholds of `settings`).
DistanceMap distanceMap(const GridMap& map, PsiClass cell_class,
                        const SimilaritySettings& settings);

/// One map prepared for ψ: its distance maps and the cells of each class.
struct DissimilarityMap {
  DistanceMap occupied;
  DistanceMap free;
  std::vector<Eigen::Vector2i> occupied_cells;
  std::vector<Eigen::Vector2i> free_cells;
  std::vector<std::uint8_t> known;  ///< 1 where the map's cell is known, row by row
};

DissimilarityMap prepareDissimilarity(const GridMap& map, const SimilaritySettings& settings);

/// ψ of `from` mapped by T_to_from onto `to` (eq. 13); infinity when no cell lands inside.
double dissimilarity(const DissimilarityMap& from, const DissimilarityMap& to,
                     const GridTransform& T_to_from);

/// ψ over the overlap: as dissimilarity(), but a cell counts only where it lands on a known cell of
/// the other map; infinity when no cell does.
double overlapDissimilarity(const DissimilarityMap& from, const DissimilarityMap& to,
                            const GridTransform& T_to_from);

}  // namespace mrslam::fusion
