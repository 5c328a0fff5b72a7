#pragma once
// A building as a set of straight wall segments in a world frame (metres), with the two
// queries a simulated laser and a route check need: ray casting and distance to the nearest wall.

#include <Eigen/Core>
#include <initializer_list>
#include <optional>
#include <vector>

namespace mrslam::drivers {

/// One wall: a straight segment from a to b in the world frame (metres). Walls have no thickness.
struct WallSegment {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
};

/// Axis-aligned bounds of a floor plan.
struct PlanBounds {
  Eigen::Vector2d min = Eigen::Vector2d::Zero();
  Eigen::Vector2d max = Eigen::Vector2d::Zero();
};

class FloorPlan {
 public:
  FloorPlan() = default;
  explicit FloorPlan(std::vector<WallSegment> walls);

  /// Adds one wall from a to b (a != b).
  void addWall(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
  /// Adds the walls of the open polyline p0 → p1 → … (e.g. a cabinet standing against a wall).
  void addPolyline(std::initializer_list<Eigen::Vector2d> points);
  /// Adds a free-standing box: the four walls of the rectangle between two opposite corners.
  void addBox(const Eigen::Vector2d& corner, const Eigen::Vector2d& opposite_corner);

  const std::vector<WallSegment>& walls() const { return walls_; }

  /// Distance from `origin` along the ray at `angle_rad` (world frame) to the nearest wall it
  /// hits, or nothing when no wall lies within `max_range_m`. A ray grazing a wall end counts
  /// as a hit; a ray running along a wall's own line hits only the walls that cross it.
  std::optional<double> castRay(const Eigen::Vector2d& origin, double angle_rad,
                                double max_range_m) const;

  /// Distance from `point` to the nearest wall (infinity for an empty plan).
  double distanceToNearestWall(const Eigen::Vector2d& point) const;

  /// The walls that come within `radius_m` of `centre`: a smaller plan that answers every ray
  /// from `centre` up to `radius_m` exactly as this one does.
  FloorPlan wallsNear(const Eigen::Vector2d& centre, double radius_m) const;

  /// Bounds of all wall end points (zero for an empty plan).
  PlanBounds bounds() const;

 private:
  std::vector<WallSegment> walls_;
};

/// Distance from `point` to the segment `wall`.
double distanceToWall(const Eigen::Vector2d& point, const WallSegment& wall);

/// The built-in test building (modelled on the seed paper's test site): about 17 × 10 m, a 1.8 m
/// corridor along its length (y 4.2…6.0), three rooms south and four north of it with 0.9 m
/// doors, a door between the two eastern south rooms, pillars in the corridor and furniture
/// (tables, cabinets, shelves, pillars) in the rooms. World frame: x east, y north, origin at the
/// south-west outer corner.
FloorPlan builtInFloorPlan();

}  // namespace mrslam::drivers
