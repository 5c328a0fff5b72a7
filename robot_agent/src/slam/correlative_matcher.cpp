#include "mrslam/robot/slam/correlative_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrslam::robot::slam {

namespace {

// Cells beyond ±2^29 are far outside any grid; clamping there keeps whole-cell shifts of the
// window from overflowing an int, whatever the guess.
constexpr double kFarCell = 536870912.0;

void check(const CorrelativeMatcherSettings& s) {
  const auto valid = [](double value) { return std::isfinite(value) && value >= 0.0; };
  if (!valid(s.linear_search_window_m) || !valid(s.angular_search_window_rad)) {
    throw std::invalid_argument("correlative matcher: search windows must be finite and >= 0");
  }
  if (!valid(s.translation_delta_cost_weight) || !valid(s.rotation_delta_cost_weight)) {
    throw std::invalid_argument("correlative matcher: cost weights must be finite and >= 0");
  }
}

/// ⌈window / step⌉, forgiving the rounding of a window that is a whole number of steps.
int stepsIn(double window, double step) {
  return static_cast<int>(std::ceil(window / step - 1e-9));
}

/// Grid cell of a submap-frame point, clamped far outside instead of overflowing.
Eigen::Vector2i cellOf(const ProbabilityGrid& grid, const Eigen::Vector2d& point_submap) {
  const Eigen::Vector2d lattice = (point_submap / grid.resolution()).array().floor();
  const Eigen::Vector2d clamped = lattice.cwiseMax(-kFarCell).cwiseMin(kFarCell);
  return clamped.cast<int>() - grid.originCell();
}

/// Cells of the points moved by T_submap_robot (step 3).
void cellsOf(const ProbabilityGrid& grid, const SE2& T_submap_robot,
             const std::vector<Eigen::Vector2d>& points_robot,
             std::vector<Eigen::Vector2i>* cells) {
  cells->resize(points_robot.size());
  const Eigen::Matrix2d R = T_submap_robot.rotation();  // once, not per point
  const Eigen::Vector2d t = T_submap_robot.translation();
  for (std::size_t k = 0; k < points_robot.size(); ++k) {
    (*cells)[k] = cellOf(grid, R * points_robot[k] + t);
  }
}

/// Sums, over the points, of the probability of each point's cell shifted by every (jx, jy) of
/// the window |j| ≤ w (step 4), row-major in `sums`. Points outer, shifts inner: one bounds check
/// per point and the grid's rows read in order.
void sumShiftedProbabilities(const ProbabilityGrid& grid, const std::vector<Eigen::Vector2i>& cells,
                             int w, float p_min, std::vector<double>* sums) {
  const int side = 2 * w + 1;
  sums->assign(static_cast<std::size_t>(side) * static_cast<std::size_t>(side), 0.0);
  const std::vector<float>& probability = grid.cells();
  const Eigen::Vector2i corner = Eigen::Vector2i::Constant(w);
  for (const Eigen::Vector2i& cell : cells) {
    const bool inside = grid.contains(cell - corner) && grid.contains(cell + corner);
    for (int jy = -w; jy <= w; ++jy) {
      double* out =
          sums->data() + static_cast<std::size_t>(jy + w) * static_cast<std::size_t>(side);
      if (inside) {
        const float* row =
            probability.data() +
            static_cast<std::size_t>(cell.y() + jy) * static_cast<std::size_t>(grid.width()) +
            static_cast<std::size_t>(cell.x() - w);
        for (int k = 0; k < side; ++k) {
          out[k] += row[k] > 0.0f ? row[k] : p_min;
        }
      } else {
        for (int jx = -w; jx <= w; ++jx) {
          out[jx + w] += grid.probability(cell + Eigen::Vector2i(jx, jy), p_min);
        }
      }
    }
  }
}

}  // namespace

CorrelativeMatcher::CorrelativeMatcher(const CorrelativeMatcherSettings& settings)
    : settings_(settings) {
  check(settings_);
}

std::optional<CorrelativeMatch> CorrelativeMatcher::match(
    const ProbabilityGrid& grid, const SE2& T_submap_robot_guess,
    const std::vector<Eigen::Vector2d>& points_robot) const {
  if (points_robot.empty()) {
    return std::nullopt;
  }
  const double r = grid.resolution();
  const int w = stepsIn(settings_.linear_search_window_m, r);
  const auto p_min = static_cast<float>(grid.settings().min_probability);
  const double step = angularSearchStep(r, points_robot);
  std::optional<CorrelativeMatch> best;
  std::vector<Eigen::Vector2i> cells;
  std::vector<double> sums;
  const auto count = static_cast<double>(points_robot.size());
  for (const double dtheta : rotationOffsets(settings_.angular_search_window_rad, step)) {
    const double theta = T_submap_robot_guess.theta() + dtheta;
    cellsOf(grid, SE2(T_submap_robot_guess.x(), T_submap_robot_guess.y(), theta), points_robot,
            &cells);
    sumShiftedProbabilities(grid, cells, w, p_min, &sums);
    for (int jy = -w; jy <= w; ++jy) {
      for (int jx = -w; jx <= w; ++jx) {
        const double score =
            sums[static_cast<std::size_t>(jy + w) * static_cast<std::size_t>(2 * w + 1) +
                 static_cast<std::size_t>(jx + w)] /
            count;
        const double cost = settings_.translation_delta_cost_weight * r * std::hypot(jx, jy) +
                            settings_.rotation_delta_cost_weight * std::abs(dtheta);
        const double weighted = score * std::exp(-cost);  // step 5
        if (!best || weighted > best->weighted_score) {
          best = CorrelativeMatch{
              SE2(T_submap_robot_guess.x() + jx * r, T_submap_robot_guess.y() + jy * r, theta),
              score, weighted};
        }
      }
    }
  }
  return best;
}

double angularSearchStep(double resolution_m, const std::vector<Eigen::Vector2d>& points_robot) {
  double d_max = 0.0;
  for (const Eigen::Vector2d& point : points_robot) {
    d_max = std::max(d_max, point.norm());
  }
  if (d_max <= 0.5 * resolution_m) {
    return M_PI;
  }
  return std::acos(1.0 - resolution_m * resolution_m / (2.0 * d_max * d_max));  // eq. 7
}

std::vector<double> rotationOffsets(double angular_window_rad, double step_rad) {
  std::vector<double> offsets;
  if (angular_window_rad >= M_PI) {
    const int n = std::max(1, stepsIn(2.0 * M_PI, step_rad));
    const double even_step = 2.0 * M_PI / n;
    for (int j = -(n / 2) + (n % 2 == 0 ? 1 : 0); j <= n / 2; ++j) {
      offsets.push_back(j * even_step);
    }
    return offsets;
  }
  const int w = stepsIn(angular_window_rad, step_rad);
  for (int j = -w; j <= w; ++j) {
    offsets.push_back(j * step_rad);
  }
  return offsets;
}

}  // namespace mrslam::robot::slam
