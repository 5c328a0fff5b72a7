#pragma once
// The best fit of two maps near a given transform, with block 9's figures there: what checks a
// transform that came from outside the maps (a rendezvous, a virtual robot's hypothesis).

#include <cstddef>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"

namespace mrslam::fusion {

struct LocalFitSettings {
  double max_shift_m = 0.5;                    ///< shifts searched up to this far
  double max_turn_rad = 3.0 * M_PI / 180.0;    ///< turns searched up to this far
  double turn_step_rad = 0.25 * M_PI / 180.0;  ///< turn step
};

struct LocalFit {
  GridTransform T_to_from;
  double verification = 0.0;      ///< V over every known cell
  double structure = 0.0;         ///< the lesser share of either map's walls meeting walls
  std::size_t overlap_cells = 0;  ///< cells known in both
  /// agr − dis over every known cell (= overlap · (2V − 1)).
  double similarity() const {
    return static_cast<double>(overlap_cells) * (2.0 * verification - 1.0);
  }
};

/// T_to_from turned by `delta_rad` about the cell `pivot` of `from` (the pivot stays put).
GridTransform turnedAbout(const GridTransform& T_to_from, const Eigen::Vector2d& pivot,
                          double delta_rad);

/// The largest agr − dis (the seed's similarity index, block 8) over turns within ±max_turn_rad
/// (about the centroid of `from`'s known cells) and shifts within ±max_shift_m of `start`.
LocalFit fitNear(const GridMap& from, const GridMap& to, const GridTransform& start,
                 const LocalFitSettings& settings);

}  // namespace mrslam::fusion
