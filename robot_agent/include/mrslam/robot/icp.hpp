#pragma once
// 2-D point-to-line ICP (Chen & Medioni 1992; for scans: Censi, "An ICP variant using a
// point-to-line metric", ICRA 2008), solved by Gauss-Newton with robust weights:
//  1. Move every source point by the current estimate T = (t, θ):  x_i = R(θ) p_i + t.
//  2. Pair x_i with its nearest target point q_j (k-d tree), if closer than the current gate d_k;
//     farther pairs are outliers. The gate shrinks each iteration, d_k = max(d_min, d_0 γ^k).
//  3. Residual along the target normal n_j:  r_i = n_jᵀ (x_i − q_j)                      (eq. 1)
//     Jacobian w.r.t. (t_x, t_y, θ):       J_i = [n_jᵀ, n_jᵀ R'(θ) p_i]                  (eq. 2)
//  4. Cauchy weights w_i = 1 / (1 + (r_i / c)²), c a fraction of the gate; solve
//     (Σ w J Jᵀ + Λ) δ = −Σ w J r − Λ (T − T₀) and set T ← (t + δ_t, θ + δ_θ).            (eq. 3)
//     Λ is an optional soft prior on the initial guess T₀ (a MAP step, as in a Gauss-Newton
//     iterated EKF update): Λ = σ_r² diag(σ_xy⁻², σ_xy⁻², σ_θ⁻²), σ_r a pair's residual σ.
//     It holds what the pairs hardly constrain (a corridor's length) near the guess instead of
//     letting flipping pairs walk it away; the pairs decide the rest. Λ = 0: plain ICP.
//  5. Stop when the gate is at d_min and the step is below the thresholds.
// Fit covariance (Hessian estimate, e.g. Bengtsson & Baerveldt 2003; Censi ICRA 2007 discusses its
// limits): with the inliers at d_min,  Σ = σ̂² (Σ J Jᵀ)⁻¹,  σ̂² = Σ r² / (n − 3)            (eq. 4)
// (the pairs' alone: the prior Λ does not enter it, the filter fuses the guess itself).
// Callers scale it and add a floor: the estimate ignores correlated errors and the map's own.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "mrslam/common/se2.hpp"
#include "mrslam/robot/kd_tree.hpp"
#include "mrslam/robot/scan_points.hpp"

namespace mrslam::robot {

struct IcpSettings {
  int max_iterations = 40;                  ///< Gauss-Newton iterations at most
  double max_correspondence_m = 1.0;        ///< d_0: pair gate at the first iteration
  double min_correspondence_m = 0.15;       ///< d_min: the gate never shrinks below this
  double gate_decay = 0.6;                  ///< γ: the gate shrinks by this factor per iteration
  double kernel_fraction = 0.3;             ///< Cauchy kernel scale c as a fraction of the gate
  double convergence_translation_m = 1e-4;  ///< step below this (and the rotation's): converged
  double convergence_rotation_rad = 1e-4;   ///< step below this (and the translation's): converged
  std::size_t min_inliers = 20;             ///< fewer pairs at d_min: the match failed
  double min_inlier_fraction = 0.3;         ///< fewer of the source points paired: failed
  double prior_sigma_xy_m = 0.0;       ///< σ_xy of the soft prior on the guess (eq. 3); 0: none
  double prior_sigma_theta_rad = 0.0;  ///< σ_θ of the soft prior on the guess (eq. 3); 0: none
  double residual_sigma_m = 0.015;     ///< σ_r: one pair's residual σ, weighs the prior (eq. 3)
};

/// Why a match ended.
enum class IcpStatus {
  kConverged,
  kNotConverged,   ///< iterations ran out
  kTooFewPoints,   ///< source or target smaller than min_inliers
  kTooFewInliers,  ///< too few (or too small a fraction of) the source points paired
};

const char* icpStatusName(IcpStatus status);

struct IcpResult {
  SE2 T_target_source;     ///< maps source coordinates into the target frame
  bool converged = false;  ///< status == kConverged
  IcpStatus status = IcpStatus::kTooFewPoints;
  int iterations = 0;
  std::size_t inliers = 0;       ///< pairs within d_min at the end
  double inlier_fraction = 0.0;  ///< inliers / source points
  double rms_m = 0.0;            ///< RMS of the point-to-line residuals of the inliers
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  ///< of (x, y, θ), eq. 4
};

/// A target point set with normals and its k-d tree.
class IcpTarget {
 public:
  IcpTarget() = default;
  /// `points.normals` must hold one unit normal per point.
  explicit IcpTarget(OrientedPoints points);

  const OrientedPoints& points() const { return points_; }
  const KdTree2d& tree() const { return tree_; }
  std::size_t size() const { return points_.points.size(); }

 private:
  OrientedPoints points_;
  KdTree2d tree_;
};

/// Aligns `source` (points in the source frame) to `target`, starting from T_target_source_guess.
IcpResult alignPointToLine(const IcpTarget& target, const std::vector<Eigen::Vector2d>& source,
                           const SE2& T_target_source_guess, const IcpSettings& settings);

}  // namespace mrslam::robot
