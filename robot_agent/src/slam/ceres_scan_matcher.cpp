#include "mrslam/robot/slam/ceres_scan_matcher.hpp"

#include <ceres/ceres.h>
#include <ceres/cubic_interpolation.h>

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

namespace mrslam::robot::slam {

namespace {

// The grid as Ceres' interpolator reads it: the cost 1 − p of each cell (row y, column x),
// p_min where unknown or outside, so a point that leaves the map is pulled back.
class CostGrid {
 public:
  enum { DATA_DIMENSION = 1 };
  explicit CostGrid(const ProbabilityGrid& grid)
      : grid_(grid), unknown_cost_(1.0 - grid.settings().min_probability) {}
  void GetValue(int row, int column, double* value) const {
    if (row < 0 || column < 0 || row >= grid_.height() || column >= grid_.width()) {
      *value = unknown_cost_;
      return;
    }
    const float p = grid_.cells()[static_cast<std::size_t>(row) * grid_.width() + column];
    *value = p > 0.0f ? 1.0 - p : unknown_cost_;
  }

 private:
  const ProbabilityGrid& grid_;
  const double unknown_cost_;
};

// w_o/√K · (1 − M_smooth(T h_k)) for every point.
class OccupiedSpaceCost {
 public:
  OccupiedSpaceCost(const ProbabilityGrid& grid, const std::vector<Eigen::Vector2d>& points,
                    double weight)
      : grid_(grid),
        interpolator_(grid_),
        points_(points),
        scale_(weight / std::sqrt(static_cast<double>(points.size()))),
        inverse_resolution_(1.0 / grid.resolution()),
        offset_(grid.originCell().cast<double>() + Eigen::Vector2d::Constant(0.5)) {}

  template <typename T>
  bool operator()(const T* const pose, T* residuals) const {
    const T c = ceres::cos(pose[2]);
    const T s = ceres::sin(pose[2]);
    for (std::size_t k = 0; k < points_.size(); ++k) {
      const T x = c * points_[k].x() - s * points_[k].y() + pose[0];
      const T y = s * points_[k].x() + c * points_[k].y() + pose[1];
      // Cell centres sit at (lattice + 0.5) · r: continuous index = p / r − origin − 0.5.
      const T column = x * inverse_resolution_ - offset_.x();
      const T row = y * inverse_resolution_ - offset_.y();
      interpolator_.Evaluate(row, column, &residuals[k]);
      residuals[k] = scale_ * residuals[k];
    }
    return true;
  }

 private:
  CostGrid grid_;
  ceres::BiCubicInterpolator<CostGrid> interpolator_;
  const std::vector<Eigen::Vector2d>& points_;
  const double scale_;
  const double inverse_resolution_;
  const Eigen::Vector2d offset_;
};

// w · (pose − target) on the chosen components.
struct PriorCost {
  Eigen::Vector3d target;
  double translation_weight;
  double rotation_weight;
  template <typename T>
  bool operator()(const T* const pose, T* residuals) const {
    residuals[0] = translation_weight * (pose[0] - target.x());
    residuals[1] = translation_weight * (pose[1] - target.y());
    residuals[2] = rotation_weight * (pose[2] - target.z());
    return true;
  }
};

Eigen::Matrix3d fitCovariance(ceres::Problem& problem, ceres::ResidualBlockId grid_block,
                              const CeresScanMatcherSettings& settings) {
  ceres::Problem::EvaluateOptions options;
  options.residual_blocks = {grid_block};
  ceres::CRSMatrix crs;
  problem.Evaluate(options, nullptr, nullptr, nullptr, &crs);
  Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
  for (int row = 0; row < crs.num_rows; ++row) {
    Eigen::Vector3d j = Eigen::Vector3d::Zero();
    for (int k = crs.rows[row]; k < crs.rows[row + 1]; ++k) {
      j(crs.cols[k]) = crs.values[k];
    }
    JtJ += j * j.transpose();
  }
  const double floor_xy = settings.min_sigma_xy_m * settings.min_sigma_xy_m;
  const double floor_theta = settings.min_sigma_theta_rad * settings.min_sigma_theta_rad;
  // A tiny ridge keeps a flat direction (no walls at all) finite: it is then left to the prior.
  constexpr double kRidge = 1e-9;
  const Eigen::Matrix3d information = JtJ + kRidge * Eigen::Matrix3d::Identity();
  Eigen::Matrix3d covariance = settings.covariance_scale * information.inverse();
  covariance(0, 0) += floor_xy;
  covariance(1, 1) += floor_xy;
  covariance(2, 2) += floor_theta;
  return covariance;
}

}  // namespace

CeresScanMatcher::CeresScanMatcher(const CeresScanMatcherSettings& settings) : settings_(settings) {
  if (!(settings_.occupied_space_weight > 0.0) || settings_.translation_weight < 0.0 ||
      settings_.rotation_weight < 0.0 || settings_.max_iterations < 1 ||
      !(settings_.covariance_scale > 0.0)) {
    throw std::invalid_argument("ceres scan matcher: weights, iterations or scale out of range");
  }
}

std::optional<CeresMatch> CeresScanMatcher::match(
    const ProbabilityGrid& grid, const SE2& T_submap_robot_initial,
    const std::vector<Eigen::Vector2d>& points_robot) const {
  if (points_robot.empty() || grid.width() == 0) {
    return std::nullopt;
  }
  double pose[3] = {T_submap_robot_initial.x(), T_submap_robot_initial.y(),
                    T_submap_robot_initial.theta()};
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  auto* grid_cost = new ceres::AutoDiffCostFunction<OccupiedSpaceCost, ceres::DYNAMIC, 3>(
      new OccupiedSpaceCost(grid, points_robot, settings_.occupied_space_weight),
      static_cast<int>(points_robot.size()));
  const ceres::ResidualBlockId grid_block = problem.AddResidualBlock(grid_cost, nullptr, pose);
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PriorCost, 3, 3>(new PriorCost{
                               Eigen::Vector3d(pose[0], pose[1], pose[2]),
                               settings_.translation_weight, settings_.rotation_weight}),
                           nullptr, pose);
  ceres::Solver::Options options;
  options.max_num_iterations = settings_.max_iterations;
  options.linear_solver_type = ceres::DENSE_QR;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable() || !std::isfinite(pose[0] + pose[1] + pose[2])) {
    return std::nullopt;
  }
  CeresMatch result;
  result.T_submap_robot = SE2(pose[0], pose[1], pose[2]);
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.covariance = fitCovariance(problem, grid_block, settings_);
  result.score = scoreOf(grid, result.T_submap_robot, points_robot);
  return result;
}

double scoreOf(const ProbabilityGrid& grid, const SE2& T_submap_robot,
               const std::vector<Eigen::Vector2d>& points_robot) {
  if (points_robot.empty()) {
    return 0.0;
  }
  const auto unknown = static_cast<float>(grid.settings().min_probability);
  double sum = 0.0;
  for (const Eigen::Vector2d& p : points_robot) {
    sum += grid.probability(grid.cellOf(T_submap_robot * p), unknown);
  }
  return sum / static_cast<double>(points_robot.size());
}

}  // namespace mrslam::robot::slam
