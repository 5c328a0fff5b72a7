#include "mrslam/drivers/floor_plan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace mrslam::drivers {
namespace {

// Tolerance on the segment parameter, so that a ray through the exact corner shared by two walls
// hits at least one of them despite rounding.
constexpr double kEndTolerance = 1e-9;

double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  return u.x() * v.y() - u.y() * v.x();
}

void checkWall(const WallSegment& wall) {
  if (!wall.a.allFinite() || !wall.b.allFinite() || (wall.b - wall.a).norm() <= 0.0) {
    throw std::invalid_argument("FloorPlan: a wall needs two distinct, finite end points");
  }
}

}  // namespace

FloorPlan::FloorPlan(std::vector<WallSegment> walls) : walls_(std::move(walls)) {
  for (const WallSegment& wall : walls_) {
    checkWall(wall);
  }
}

void FloorPlan::addWall(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const WallSegment wall{a, b};
  checkWall(wall);
  walls_.push_back(wall);
}

void FloorPlan::addPolyline(std::initializer_list<Eigen::Vector2d> points) {
  const Eigen::Vector2d* previous = nullptr;
  for (const Eigen::Vector2d& point : points) {
    if (previous != nullptr) {
      addWall(*previous, point);
    }
    previous = &point;
  }
}

void FloorPlan::addBox(const Eigen::Vector2d& corner, const Eigen::Vector2d& opposite_corner) {
  const Eigen::Vector2d lo = corner.cwiseMin(opposite_corner);
  const Eigen::Vector2d hi = corner.cwiseMax(opposite_corner);
  addPolyline({lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}, lo});
}

std::optional<double> FloorPlan::castRay(const Eigen::Vector2d& origin, double angle_rad,
                                         double max_range_m) const {
  // Ray o + t·d (t ≥ 0), wall a + s·(b − a) (0 ≤ s ≤ 1). With e = b − a and w = a − o:
  //   t = (w × e) / (d × e),   s = (w × d) / (d × e).
  const Eigen::Vector2d direction(std::cos(angle_rad), std::sin(angle_rad));
  double nearest = std::numeric_limits<double>::infinity();
  for (const WallSegment& wall : walls_) {
    const Eigen::Vector2d e = wall.b - wall.a;
    const double denominator = cross(direction, e);
    if (std::abs(denominator) < 1e-12 * e.norm()) {
      continue;  // parallel to the wall's line
    }
    const Eigen::Vector2d w = wall.a - origin;
    const double t = cross(w, e) / denominator;
    const double s = cross(w, direction) / denominator;
    if (t >= 0.0 && t < nearest && s >= -kEndTolerance && s <= 1.0 + kEndTolerance) {
      nearest = t;
    }
  }
  if (nearest > max_range_m) {
    return std::nullopt;
  }
  return nearest;
}

double distanceToWall(const Eigen::Vector2d& point, const WallSegment& wall) {
  const Eigen::Vector2d e = wall.b - wall.a;
  const double s = std::clamp((point - wall.a).dot(e) / e.squaredNorm(), 0.0, 1.0);
  return (wall.a + s * e - point).norm();
}

double FloorPlan::distanceToNearestWall(const Eigen::Vector2d& point) const {
  double nearest = std::numeric_limits<double>::infinity();
  for (const WallSegment& wall : walls_) {
    nearest = std::min(nearest, distanceToWall(point, wall));
  }
  return nearest;
}

FloorPlan FloorPlan::wallsNear(const Eigen::Vector2d& centre, double radius_m) const {
  FloorPlan near;
  for (const WallSegment& wall : walls_) {
    if (distanceToWall(centre, wall) <= radius_m) {
      near.walls_.push_back(wall);
    }
  }
  return near;
}

PlanBounds FloorPlan::bounds() const {
  if (walls_.empty()) {
    return {};
  }
  PlanBounds box{walls_.front().a, walls_.front().a};
  for (const WallSegment& wall : walls_) {
    box.min = box.min.cwiseMin(wall.a).cwiseMin(wall.b);
    box.max = box.max.cwiseMax(wall.a).cwiseMax(wall.b);
  }
  return box;
}

}  // namespace mrslam::drivers
