#pragma once
// Whether the accepted transform sits in the best basin of V nearby: a check of a merge against
// the same room placed a few cells and degrees off.
//
// V (block 9) over all known cells, as a function of the transform, has many small basins: a
// climb from a transform ends within a cell or so of it. An accepted transform is the peak of the
// basin it lies in, but the searches' grids (whole cells, rotation steps of a degree or two) can
// leave it in a basin 3-10 cells and 1-4 degrees from the truth's, where walls still meet walls
// but V is lower. This climbs V from the accepted transform (its own basin's peak) and from the
// best `climbs` points of a grid of turns (±turn_steps × turn_step_deg about the centroid of
// the sampled known cells of `from`) and shifts (±shift_steps × shift_step_cells on each axis)
// around it, and reports the highest peak more than `distinct_cells` from the own one. Climbs and
// peaks keep at least `min_overlap_share` of the overlap at the accepted transform: V of a
// placement that slides most of the overlap off is high for want of cells to disagree (right merges
// of seed 232: V 1.0 ten cells away, 0.995 thirteen cells away, against 0.977 and 0.976 at the
// right transform).
//
// A scratch probe (scoring V with the case tools' scoreOverlap, a grid of ±4° and ±8 cells, five
// climbs) found on 160 right merges of the default chain (seeds 231-250, drawn at random) no other
// peak higher than the own basin's, and on 19 false accepts of seeds 231-290 a higher one in 7,
// four of them at the truth. As built (the chain's `neighbour_basin_min_v_gain`), at a bar of 0
// on the 60 case sets of seeds 231-290: the other peak was higher at 5 right merges (by at most
// 0.0013) and 3 false accepts (by 0.00004, 0.0023 and 0.0167; docs/merge_tuning.md).
//
// The climb: a pattern search of V over turns about the same pivot and shifts along the axes,
// from steps of `climb_turn_deg` and `climb_shift_cells`, each step halved where no move raises V
// until the turn step is below `min_climb_turn_deg`. The climbs compare every n-th known cell
// of `from` (the classes keep their shares); the two peaks' V is then taken over all of them, and
// the own peak is the accepted transform where V over all of them is higher there.

#include <vector>

#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {

struct NeighbourBasinSettings {
  double turn_step_deg = 2.0;       ///< grid: turns of this step ...
  int turn_steps = 1;               ///< ... this many a side
  double shift_step_cells = 3.0;    ///< grid: shifts of this step on each axis ...
  int shift_steps = 2;              ///< ... this many a side
  int climbs = 3;                   ///< the best grid points climbed
  double distinct_cells = 2.0;      ///< a peak nearer than this to the own one is the same basin
  double climb_turn_deg = 1.0;      ///< the climb's first turn step
  double climb_shift_cells = 2.0;   ///< the climb's first shift step
  double min_climb_turn_deg = 0.1;  ///< the climb ends when its turn step falls below this
  double min_overlap_share = 0.9;   ///< peaks and climbs keep at least this share of the overlap
                                    ///< (known cells of both) at the accepted transform
  int sampled_cells = 5000;  ///< the climbs compare every n-th known cell of `from`, n the least
                             ///< that keeps at most this many (0: all)
};

/// The peak of V's basin at a transform, and the highest other peak nearby.
struct NeighbourBasins {
  GridTransform own;         ///< the peak of the accepted transform's basin (or the transform)
  double own_v = 0.0;        ///< V there (over all known cells)
  GridTransform other;       ///< the highest peak more than distinct_cells from `own`
  double other_v = 0.0;      ///< V there (0 when no grid point climbed to a distinct peak
                             ///< keeping the overlap)
  double other_cells = 0.0;  ///< how far `other` puts the pivot from where `own` puts it
  double other_deg = 0.0;    ///< their turn apart, degrees
  int comparisons = 0;       ///< V taken this many times
};

/// The basins of V around T_to_from: `known_from` the known cells of `from`, `to` its codes.
NeighbourBasins neighbourBasins(const std::vector<CellSample>& known_from, const CodeImage& to,
                                const ComparisonTables& tables, const GridTransform& T_to_from,
                                const NeighbourBasinSettings& settings);

/// The same from the two maps.
NeighbourBasins neighbourBasins(const GridMap& from, const GridMap& to,
                                const SimilaritySettings& classes, const GridTransform& T_to_from,
                                const NeighbourBasinSettings& settings);

}  // namespace mrslam::fusion
