#pragma once
// Accuracy of an estimated trajectory against ground truth (Sturm et al., "A benchmark for the
// evaluation of RGB-D SLAM systems", IROS 2012; Kümmerle et al., "On measuring the accuracy of
// SLAM algorithms", Auton. Robots 2009), in SE(2):
//   RPE(Δ): E_i = (G_i⁻¹ G_{i+Δ})⁻¹ (T_i⁻¹ T_{i+Δ}) for every pair Δ apart: |t(E_i)|, |θ(E_i)|.
//   ATE: the translations after the rigid transform S minimising Σ |g_i − S t_i|² (Umeyama 1991,
//        without scale): |g_i − S t_i|, and the headings' differences after S.
// And the consistency of a filter: NEES ε = eᵀ P⁻¹ e, e = (x̂ − x, ŷ − y, wrap(θ̂ − θ)).

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "mrslam/common/se2.hpp"

namespace mrslam::robot {

struct ErrorStats {
  std::size_t count = 0;
  double translation_mean_m = 0.0;
  double translation_rms_m = 0.0;
  double translation_max_m = 0.0;
  double rotation_mean_deg = 0.0;
  double rotation_rms_deg = 0.0;
  double rotation_max_deg = 0.0;
};

/// RPE over all pairs (i, i + delta). Throws std::invalid_argument when the sizes differ.
ErrorStats relativePoseError(const std::vector<SE2>& estimate, const std::vector<SE2>& truth,
                             std::size_t delta);

/// S = T_truth_estimate minimising Σ |g_i − S t_i|² (translations only).
SE2 alignTrajectory(const std::vector<SE2>& estimate, const std::vector<SE2>& truth);

/// ATE after alignTrajectory. Throws std::invalid_argument when the sizes differ.
ErrorStats absoluteTrajectoryError(const std::vector<SE2>& estimate, const std::vector<SE2>& truth);

/// Normalised estimation error squared of a pose estimate with covariance of (x, y, θ).
double nees(const SE2& estimate, const Eigen::Matrix3d& covariance, const SE2& truth);

}  // namespace mrslam::robot
