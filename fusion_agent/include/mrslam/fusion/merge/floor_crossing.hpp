#pragma once
// Walls of one map that cross the other's open floor at a placement: a check of a merge's
// transform against a wrong placement of a room that looks alike (a room along a corridor, or
// the room turned by a quarter).
//
// At a right placement, a wall of `own` lands on or beside a wall of `other`, on `other`'s
// unknown cells, or (where a door stood open in one map and shut in the other, a person stood, a
// chair moved) on a few cells of open floor. At a wrong placement of a room that looks alike, a
// whole wall of one map runs through the open floor of the other: its outer walls match, but an
// inner wall, a doorway's side or a corner of a wall that one room has and the other lacks lies
// where the other map saw nothing. The V and structure figures average such a run over the whole
// overlap; this measures it where it lies.
//
// A crossing cell is a cell of `other` that a wall of `own` lands on (rounded to the nearest
// cell) which `other` holds as free and which lies farther than `clearance_cells` from every wall
// of `other` (so a wall drawn a cell or two apart in the two maps does not count). The crossing is
// the largest 8-connected run of such cells, and its share the run over the walls of `own` that
// land on known cells of `other`. On crops of one map, a wrong room crosses the floor with a large
// share of its few overlapping walls and a right placement hardly at all. Real team maps of one
// building hold long runs too (people, doors, their robots' drift): the final maps of the Carpin,
// intel, ACES and CSAIL teams keep their share below 1.2 %, but the ACES team's maps reach 2.2 %
// while they grow, which is why the chain's check on it is off by default (docs/merge_tuning.md,
// forty-sixth session).

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {

struct FloorCrossing {
  int run_cells = 0;       ///< the largest 8-connected run of crossing cells
  int crossing_cells = 0;  ///< every crossing cell
  int walls_on_known = 0;  ///< walls of `own` landing on known cells of `other`
  /// run_cells / walls_on_known (0 when no wall lands on a known cell).
  double share() const {
    return walls_on_known > 0 ? static_cast<double>(run_cells) / walls_on_known : 0.0;
  }
};

/// The walls of `own` placed on `other` by T_other_own, measured as above.
FloorCrossing floorCrossing(const GridMap& own, const GridMap& other,
                            const GridTransform& T_other_own, const SimilaritySettings& classes,
                            double clearance_cells);

}  // namespace mrslam::fusion
