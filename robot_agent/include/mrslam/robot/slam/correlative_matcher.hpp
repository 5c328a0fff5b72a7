#pragma once
// Real-time correlative scan matching (Olson, "Real-time correlative scan matching", ICRA 2009),
// as local SLAM uses it when the predicted pose is uncertain (Hess et al., ICRA 2016):
//  1. The search window around the guess ξ0 = (x0, y0, θ0): every whole-cell translation
//     (j_x·r, j_y·r) with |j| ≤ ⌈W_xy / r⌉ and every rotation j_θ·δθ with |j_θ| ≤ ⌈W_θ / δθ⌉.
//  2. The angular step comes from the farthest point, so that no point moves more than about one
//     cell between neighbouring rotations (Hess et al. eq. 7):
//       d_max = max_k ‖h_k‖,  δθ = arccos(1 − r² / (2 d_max²)).
//  3. For each rotation the points are rotated once and put in their cells; each translation then
//     only shifts those cells by whole cells (Olson's exhaustive "brute force" search, cheap
//     because the rotation is the costly part).
//  4. A candidate scores the mean probability of the cells its points fall in (Olson's
//     lookup-table likelihood, here the submap's own probabilities). Unknown cells and cells
//     outside the grid count as p_min, so a candidate gains nothing by leaving the map.
//  5. The score is weighted by the prior around the guess,
//       score · exp(−(w_t ‖Δt‖ + w_r |Δθ|)),
//     and the candidate with the highest weighted score is the match (the first found on ties,
//     rotations from −W_θ up, translations from −W_xy up).

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "mrslam/common/se2.hpp"
#include "mrslam/robot/slam/probability_grid.hpp"

namespace mrslam::robot::slam {

struct CorrelativeMatcherSettings {
  double linear_search_window_m = 0.1;                   ///< W_xy: ± this in x and in y
  double angular_search_window_rad = 20.0 * M_PI / 180;  ///< W_θ: ± this about the guess
  double translation_delta_cost_weight = 0.1;  ///< w_t of the prior exp(−w_t ‖Δt‖), per metre
  double rotation_delta_cost_weight = 0.1;     ///< w_r of the prior exp(−w_r |Δθ|), per radian
};

struct CorrelativeMatch {
  SE2 T_submap_robot;
  double score = 0.0;           ///< mean probability of the points' cells (unknown: p_min)
  double weighted_score = 0.0;  ///< score · exp(−(w_t ‖Δt‖ + w_r |Δθ|)), what was maximised
};

class CorrelativeMatcher {
 public:
  /// Throws std::invalid_argument for negative or non-finite windows or weights.
  explicit CorrelativeMatcher(const CorrelativeMatcherSettings& settings);

  /// Best candidate of the window around T_submap_robot_guess for robot-frame points; nullopt
  /// when there are no points.
  std::optional<CorrelativeMatch> match(const ProbabilityGrid& grid,
                                        const SE2& T_submap_robot_guess,
                                        const std::vector<Eigen::Vector2d>& points_robot) const;

  const CorrelativeMatcherSettings& settings() const { return settings_; }

 private:
  const CorrelativeMatcherSettings settings_;
};

/// δθ of step 2 for points in the robot frame; π when every point is within r / 2 of the origin
/// (or there are none), where any rotation moves no point out of its cell's reach.
double angularSearchStep(double resolution_m, const std::vector<Eigen::Vector2d>& points_robot);

/// The rotation offsets j·δθ, |j| ≤ ⌈W_θ / δθ⌉, in increasing order. A window of π or more gives
/// the whole circle instead: n = ⌈2π / δθ⌉ evenly spaced offsets in (−π, π], each angle once.
std::vector<double> rotationOffsets(double angular_window_rad, double step_rad);

}  // namespace mrslam::robot::slam
