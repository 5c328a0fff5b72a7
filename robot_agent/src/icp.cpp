#include "mrslam/robot/icp.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrslam::robot {

namespace {

// The normal equations of one iteration (eq. 3) or of the final fit (eq. 4).
struct NormalEquations {
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  double sum_sq_residual = 0.0;
  std::size_t pairs = 0;
};

// Pairs every source point moved by T with its nearest target point within `gate` and
// accumulates eqs. 1-3; kernel_scale 0 means unit weights.
NormalEquations accumulate(const IcpTarget& target, const std::vector<Eigen::Vector2d>& source,
                           const SE2& T, double gate, double kernel_scale) {
  NormalEquations eq;
  const Eigen::Matrix2d rotation = T.rotation();
  const Eigen::Vector2d translation = T.translation();
  for (const Eigen::Vector2d& p : source) {
    const Eigen::Vector2d rotated = rotation * p;
    const Eigen::Vector2d x = rotated + translation;
    const KdTree2d::Neighbour pair = target.tree().nearest(x, gate);
    if (pair.index < 0) {
      continue;
    }
    const Eigen::Vector2d& n = target.points().normals[pair.index];
    const double r = n.dot(x - target.points().points[pair.index]);                    // eq. 1
    const Eigen::Vector3d J(n.x(), n.y(), n.y() * rotated.x() - n.x() * rotated.y());  // eq. 2
    const double u = kernel_scale > 0.0 ? r / kernel_scale : 0.0;
    const double w = 1.0 / (1.0 + u * u);
    eq.hessian.noalias() += w * J * J.transpose();
    eq.gradient.noalias() += w * r * J;
    eq.sum_sq_residual += r * r;
    ++eq.pairs;
  }
  return eq;
}

// Λ of eq. 3: the soft prior's information in the units of Σ w J Jᵀ (zero where σ = 0).
Eigen::Vector3d priorInformation(const IcpSettings& settings) {
  const auto information = [&settings](double sigma) {
    return sigma > 0.0 ? (settings.residual_sigma_m * settings.residual_sigma_m) / (sigma * sigma)
                       : 0.0;
  };
  const double xy = information(settings.prior_sigma_xy_m);
  return Eigen::Vector3d(xy, xy, information(settings.prior_sigma_theta_rad));
}

// δ of eq. 3 at T with the prior Λ on T₀, with a tiny damping so a degenerate direction (a
// corridor) does not blow up.
Eigen::Vector3d gaussNewtonStep(const NormalEquations& eq, const Eigen::Vector3d& prior,
                                const SE2& T, const SE2& T0) {
  const Eigen::Vector3d from_guess(T.x() - T0.x(), T.y() - T0.y(),
                                   wrapAngle(T.theta() - T0.theta()));
  const double damping = 1e-9 * std::max(eq.hessian.trace(), 1e-12);
  Eigen::Matrix3d damped = eq.hessian + damping * Eigen::Matrix3d::Identity();
  damped.diagonal() += prior;
  return damped.ldlt().solve(-eq.gradient - prior.cwiseProduct(from_guess));
}

// Inliers, RMS and the covariance of eq. 4 at the final estimate.
void finish(const IcpTarget& target, const std::vector<Eigen::Vector2d>& source,
            const IcpSettings& settings, IcpResult& result) {
  const NormalEquations eq =
      accumulate(target, source, result.T_target_source, settings.min_correspondence_m, 0.0);
  result.inliers = eq.pairs;
  result.inlier_fraction =
      source.empty() ? 0.0 : static_cast<double>(eq.pairs) / static_cast<double>(source.size());
  if (eq.pairs < std::max<std::size_t>(settings.min_inliers, 4) ||
      result.inlier_fraction < settings.min_inlier_fraction) {
    result.status = IcpStatus::kTooFewInliers;
    result.converged = false;
    return;
  }
  result.rms_m = std::sqrt(eq.sum_sq_residual / static_cast<double>(eq.pairs));
  const double sigma_sq = eq.sum_sq_residual / static_cast<double>(eq.pairs - 3);
  const double damping = 1e-12 * std::max(eq.hessian.trace(), 1e-12);
  result.covariance =
      sigma_sq * (eq.hessian + damping * Eigen::Matrix3d::Identity()).inverse();  // eq. 4
}

}  // namespace

const char* icpStatusName(IcpStatus status) {
  switch (status) {
    case IcpStatus::kConverged:
      return "converged";
    case IcpStatus::kNotConverged:
      return "not converged";
    case IcpStatus::kTooFewPoints:
      return "too few points";
    case IcpStatus::kTooFewInliers:
      return "too few inliers";
  }
  return "unknown";
}

IcpTarget::IcpTarget(OrientedPoints points) : points_(std::move(points)), tree_(points_.points) {
  if (points_.normals.size() != points_.points.size()) {
    throw std::invalid_argument("IcpTarget: one normal per point is needed");
  }
}

IcpResult alignPointToLine(const IcpTarget& target, const std::vector<Eigen::Vector2d>& source,
                           const SE2& T_target_source_guess, const IcpSettings& settings) {
  IcpResult result;
  result.T_target_source = T_target_source_guess;
  if (source.size() < settings.min_inliers || target.size() < settings.min_inliers) {
    result.status = IcpStatus::kTooFewPoints;
    return result;
  }
  const Eigen::Vector3d prior = priorInformation(settings);
  double gate = settings.max_correspondence_m;
  result.status = IcpStatus::kNotConverged;
  Eigen::Vector3d previous_step = Eigen::Vector3d::Zero();
  double step_scale = 1.0;
  while (result.iterations < settings.max_iterations) {
    ++result.iterations;
    const NormalEquations eq =
        accumulate(target, source, result.T_target_source, gate, settings.kernel_fraction * gate);
    if (eq.pairs < std::max<std::size_t>(settings.min_inliers, 4)) {
      result.status = IcpStatus::kTooFewInliers;
      return result;
    }
    const Eigen::Vector3d full_step =
        gaussNewtonStep(eq, prior, result.T_target_source, T_target_source_guess);
    // Pairs flipping between neighbours make Gauss-Newton jump back and forth along a weakly
    // constrained direction: each reversal halves the applied steps from then on, so the jumps
    // settle in between.
    const bool at_floor = gate <= settings.min_correspondence_m;
    if (at_floor && full_step.dot(previous_step) < 0.0) {
      step_scale *= 0.5;
    }
    previous_step = full_step;
    const Eigen::Vector3d step = step_scale * full_step;
    const SE2& T = result.T_target_source;
    result.T_target_source = SE2(T.x() + step.x(), T.y() + step.y(), T.theta() + step.z());
    const auto small = [&settings](const Eigen::Vector3d& v) {
      return v.head<2>().norm() < settings.convergence_translation_m &&
             std::abs(v.z()) < settings.convergence_rotation_rad;
    };
    if (at_floor && (small(full_step) || (small(step) && step_scale < 1.0 / 16))) {
      result.status = IcpStatus::kConverged;
      break;
    }
    gate = std::max(settings.min_correspondence_m, gate * settings.gate_decay);
  }
  finish(target, source, settings, result);
  result.converged = result.status == IcpStatus::kConverged;
  return result;
}

}  // namespace mrslam::robot
