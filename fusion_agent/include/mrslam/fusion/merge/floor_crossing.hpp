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
// cell), which `other` holds as certain open floor (occupancy at most `floor_max_occupancy`, below
// the free class's bar) and which lies farther than `clearance_cells` from every wall of `other`
// (so a wall drawn a cell or two apart in the two maps does not count), with every cell within
// that clearance known to `other` (`known_around`: floor at `other`'s frontier may end at a wall
// `other` never saw, or at the window of a crop). The crossing is the largest 8-connected run of
// such cells, and its share the run over the walls of `own` that land on known cells of `other`.
// On crops of one map, a wrong room crosses the floor with a large share of its few overlapping
// walls and a right placement hardly at all.
//
// Real team maps of one building hold long runs too. While the ACES team's maps grow, a robot's
// map holds corridor and room floor that a few beams crossed (occupancy 17-31: two to four more
// misses than hits under the robots' inverse sensor model) where the other robot saw a solid wall
// (85-98): a door open in one and shut in the other, a person standing, beams passing a gap. Runs
// on such floor reach 14-20 cells at 1.5-2.2 % of the walls. On floor of occupancy 12 or less
// (five more misses than hits) the growing maps of the ACES, intel and CSAIL teams stay at
// 0.55 %, 0.76 % and 0.96 % (docs/merge_tuning.md). The maps of merge
// cases are read from trinary files, where all floor is 0.
//
// The clearance is tested on the cells around each landed wall and the run found among the
// crossing cells alone, so the check costs time in proportion to the walls, not the cells.

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

struct FloorCrossingSettings {
  double clearance_cells = 2.5;  ///< crossing cells lie farther than this from `other`'s walls
  /// Cells of `other` of at most this occupancy (percent) are open floor; cells of the free class
  /// above it (floor few beams crossed) are not.
  int floor_max_occupancy = 12;
  /// Only floor whose cells within the clearance are all known (none unknown, none off the map)
  /// counts: floor at `other`'s frontier may end at a wall `other` never saw.
  bool known_around = true;
};

/// The walls of `own` placed on `other` by T_other_own, measured as above.
FloorCrossing floorCrossing(const GridMap& own, const GridMap& other,
                            const GridTransform& T_other_own, const SimilaritySettings& classes,
                            const FloorCrossingSettings& settings);

}  // namespace mrslam::fusion
