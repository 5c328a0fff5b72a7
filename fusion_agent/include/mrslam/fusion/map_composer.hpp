#pragma once
// Composes robots' local maps into one global map in the reference robot's frame.
//
// Rule: every robot's cell value is taken as independent evidence, so the global cell's log-odds
// is the sum of the log-odds of the cells it falls in (nearest cell of each placed robot map);
// a cell stays unknown when no robot has observed it. Where robots agree the result gets more
// certain; where they disagree it moves towards 50 %, which is what the evidence says.

#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/common/occupancy_grid.hpp"
#include "mrslam/common/se2.hpp"

namespace mrslam::fusion {

/// A robot's map and where its origin lies in the reference frame.
struct PlacedMap {
  const GridMap* map = nullptr;
  SE2 T_reference_robot;
};

struct ComposerSettings {
  double resolution_m = 0.0;  ///< global map cell size; 0: the first placed map's
  /// Bound of the summed log-odds: beyond logit(0.996), so one map composed alone keeps its
  /// values exactly (0 and 100 included).
  float max_abs_log_odds = 5.6f;
};

/// The axis-aligned box (reference frame) that holds every known cell of the placed maps;
/// false when no cell is known.
bool placedBounds(const std::vector<PlacedMap>& maps, Eigen::Vector2d& min_m,
                  Eigen::Vector2d& max_m);

/// The cells of `global` that are occupied there and in the placed map (for pictures).
std::vector<Eigen::Vector2i> occupiedCellsOf(const PlacedMap& placed, const GridMap& global);

/// The global map, cropped to the known cells; empty (0 × 0) when no cell is known.
GridMap composeGlobalMap(const std::vector<PlacedMap>& maps, const ComposerSettings& settings);

}  // namespace mrslam::fusion
