#pragma once
// Scan-to-submap matching by least squares on the smoothly interpolated grid (Hess et al., ICRA
// 2016, section IV.C):
//   argmin_ξ  Σ_k (w_o / √K · (1 − M_smooth(T_ξ h_k)))²  +  (w_t ‖t − t₀‖)²  +  (w_r (θ − θ₀))²
// over the K matching points h_k, with M_smooth the bicubic interpolation of the submap's
// probabilities (unknown cells count as p_min, so leaving the map costs) and (t₀, θ₀) the initial
// pose. Solved by Ceres (automatic derivatives). The fit's covariance comes from the Jacobian of
// the grid residuals at the optimum: Σ = s · (JᵀJ)⁻¹ (a corridor's length stays uncertain),
// floored at min_sigma_xy_m and min_sigma_theta_rad.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "mrslam/common/se2.hpp"
#include "mrslam/robot/slam/probability_grid.hpp"

namespace mrslam::robot::slam {

struct CeresScanMatcherSettings {
  double occupied_space_weight = 1.0;  ///< w_o of the grid residuals
  double translation_weight = 0.1;     ///< w_t pulling towards the initial translation
  double rotation_weight = 0.1;        ///< w_r pulling towards the initial heading
  int max_iterations = 20;             ///< Ceres iterations per match
  double covariance_scale = 1e-3;      ///< s of Σ = s (JᵀJ)⁻¹
  double min_sigma_xy_m = 0.01;        ///< floor of the fit's translation σ
  double min_sigma_theta_rad = 0.002;  ///< floor of the fit's heading σ
};

struct CeresMatch {
  SE2 T_submap_robot;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  ///< of (x, y, θ)
  double score = 0.0;  ///< mean probability of the points' cells at the optimum
  bool converged = false;
};

class CeresScanMatcher {
 public:
  explicit CeresScanMatcher(const CeresScanMatcherSettings& settings);

  /// Matches robot-frame points against `grid` from T_submap_robot_initial; nullopt when there
  /// are no points or the solver fails.
  std::optional<CeresMatch> match(const ProbabilityGrid& grid, const SE2& T_submap_robot_initial,
                                  const std::vector<Eigen::Vector2d>& points_robot) const;

  const CeresScanMatcherSettings& settings() const { return settings_; }

 private:
  const CeresScanMatcherSettings settings_;
};

/// Mean probability of the grid cells holding T_submap_robot · points (unknown: p_min).
double scoreOf(const ProbabilityGrid& grid, const SE2& T_submap_robot,
               const std::vector<Eigen::Vector2d>& points_robot);

}  // namespace mrslam::robot::slam
