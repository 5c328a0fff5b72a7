#include "mrslam/robot/trajectory_metrics.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrslam::robot {

namespace {

constexpr double kDegPerRad = 180.0 / M_PI;

void checkSizes(const std::vector<SE2>& estimate, const std::vector<SE2>& truth) {
  if (estimate.size() != truth.size()) {
    throw std::invalid_argument("trajectory metrics: estimate and truth differ in length");
  }
}

// Accumulates translation and rotation errors into the statistics.
class StatsBuilder {
 public:
  void add(double translation_m, double rotation_rad) {
    const double rotation_deg = std::abs(rotation_rad) * kDegPerRad;
    ++stats_.count;
    stats_.translation_mean_m += translation_m;
    stats_.translation_rms_m += translation_m * translation_m;
    stats_.translation_max_m = std::max(stats_.translation_max_m, translation_m);
    stats_.rotation_mean_deg += rotation_deg;
    stats_.rotation_rms_deg += rotation_deg * rotation_deg;
    stats_.rotation_max_deg = std::max(stats_.rotation_max_deg, rotation_deg);
  }
  ErrorStats finish() const {
    ErrorStats stats = stats_;
    if (stats.count > 0) {
      const double n = static_cast<double>(stats.count);
      stats.translation_mean_m /= n;
      stats.translation_rms_m = std::sqrt(stats.translation_rms_m / n);
      stats.rotation_mean_deg /= n;
      stats.rotation_rms_deg = std::sqrt(stats.rotation_rms_deg / n);
    }
    return stats;
  }

 private:
  ErrorStats stats_;
};

}  // namespace

ErrorStats relativePoseError(const std::vector<SE2>& estimate, const std::vector<SE2>& truth,
                             std::size_t delta) {
  checkSizes(estimate, truth);
  StatsBuilder builder;
  for (std::size_t i = 0; delta > 0 && i + delta < estimate.size(); ++i) {
    const SE2 estimated = estimate[i].inverse() * estimate[i + delta];
    const SE2 true_motion = truth[i].inverse() * truth[i + delta];
    const SE2 error = true_motion.inverse() * estimated;
    builder.add(error.translation().norm(), error.theta());
  }
  return builder.finish();
}

SE2 alignTrajectory(const std::vector<SE2>& estimate, const std::vector<SE2>& truth) {
  checkSizes(estimate, truth);
  if (estimate.empty()) {
    return SE2();
  }
  Eigen::Vector2d mean_e = Eigen::Vector2d::Zero();
  Eigen::Vector2d mean_g = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    mean_e += estimate[i].translation();
    mean_g += truth[i].translation();
  }
  mean_e /= static_cast<double>(estimate.size());
  mean_g /= static_cast<double>(estimate.size());
  // W = Σ (g − ḡ)(t − t̄)ᵀ; the best rotation angle is atan2(W₁₀ − W₀₁, W₀₀ + W₁₁).
  Eigen::Matrix2d W = Eigen::Matrix2d::Zero();
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    W += (truth[i].translation() - mean_g) * (estimate[i].translation() - mean_e).transpose();
  }
  const double angle = std::atan2(W(1, 0) - W(0, 1), W(0, 0) + W(1, 1));
  const SE2 rotation(0.0, 0.0, angle);
  const Eigen::Vector2d t = mean_g - rotation.rotation() * mean_e;
  return SE2(t.x(), t.y(), angle);
}

ErrorStats absoluteTrajectoryError(const std::vector<SE2>& estimate,
                                   const std::vector<SE2>& truth) {
  const SE2 S = alignTrajectory(estimate, truth);
  StatsBuilder builder;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    const SE2 aligned = S * estimate[i];
    builder.add((aligned.translation() - truth[i].translation()).norm(),
                wrapAngle(aligned.theta() - truth[i].theta()));
  }
  return builder.finish();
}

double nees(const SE2& estimate, const Eigen::Matrix3d& covariance, const SE2& truth) {
  const Eigen::Vector3d e(estimate.x() - truth.x(), estimate.y() - truth.y(),
                          wrapAngle(estimate.theta() - truth.theta()));
  return e.dot(covariance.ldlt().solve(e));
}

}  // namespace mrslam::robot
