#pragma once
// Submaps for the scan matcher tests: a small synthetic room whose scans are cast against its
// walls, and a real submap of the corrected CARMEN intel log.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include "mrslam/common/samples.hpp"
#include "mrslam/common/se2.hpp"
#include "mrslam/drivers/carmen_reader.hpp"
#include "mrslam/robot/slam/probability_grid.hpp"

namespace mrslam::robot::test {

struct Wall {
  Eigen::Vector2d a;
  Eigen::Vector2d b;
};

/// Distance along the ray from `origin` in direction `unit` to the nearest wall; infinity if none.
inline double castRay(const std::vector<Wall>& walls, const Eigen::Vector2d& origin,
                      const Eigen::Vector2d& unit) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Wall& wall : walls) {
    const Eigen::Vector2d along = wall.b - wall.a;
    const double denominator = unit.x() * along.y() - unit.y() * along.x();
    if (std::abs(denominator) < 1e-12) {
      continue;  // parallel
    }
    const Eigen::Vector2d to_a = wall.a - origin;
    const double t = (to_a.x() * along.y() - to_a.y() * along.x()) / denominator;
    const double s = (to_a.x() * unit.y() - to_a.y() * unit.x()) / denominator;
    if (t > 1e-9 && s >= 0.0 && s <= 1.0) {
      nearest = std::min(nearest, t);
    }
  }
  return nearest;
}

/// End points, in the robot frame, of `beams` beams over the full turn from T_world_robot.
inline std::vector<Eigen::Vector2d> castScan(const std::vector<Wall>& walls,
                                             const SE2& T_world_robot, int beams) {
  std::vector<Eigen::Vector2d> points_robot;
  for (int i = 0; i < beams; ++i) {
    const double angle = -M_PI + 2.0 * M_PI * i / beams;
    const Eigen::Vector2d unit(std::cos(angle), std::sin(angle));
    const double range =
        castRay(walls, T_world_robot.translation(), T_world_robot.rotation() * unit);
    if (std::isfinite(range)) {
      points_robot.push_back(range * unit);
    }
  }
  return points_robot;
}

struct SyntheticRoom {
  std::vector<Wall> walls;
  slam::ProbabilityGrid grid;
  SE2 T_submap_robot;                       ///< where the scan to match was taken
  std::vector<Eigen::Vector2d> scan_robot;  ///< its end points
};

/// A square room of side cells·r with `inner_walls` random walls, mapped by scans from six
/// random places; the scan to match is cast from a seventh. The submap frame is the room's.
inline SyntheticRoom syntheticRoom(std::mt19937& random, int cells = 40, double resolution_m = 0.1,
                                   int inner_walls = 4) {
  const double side = cells * resolution_m;
  std::vector<Wall> walls = {{{0.0, 0.0}, {side, 0.0}},
                             {{side, 0.0}, {side, side}},
                             {{side, side}, {0.0, side}},
                             {{0.0, side}, {0.0, 0.0}}};
  std::uniform_real_distribution<double> anywhere(0.1 * side, 0.9 * side);
  for (int i = 0; i < inner_walls; ++i) {
    walls.push_back({{anywhere(random), anywhere(random)}, {anywhere(random), anywhere(random)}});
  }
  slam::ProbabilityGridSettings settings;
  settings.resolution_m = resolution_m;
  slam::ProbabilityGrid grid(settings);
  std::uniform_real_distribution<double> inside(0.2 * side, 0.8 * side);
  std::uniform_real_distribution<double> heading(-M_PI, M_PI);
  for (int i = 0; i < 6; ++i) {
    const SE2 T_submap_scanner(inside(random), inside(random), heading(random));
    std::vector<Eigen::Vector2d> hits = castScan(walls, T_submap_scanner, 360);
    for (Eigen::Vector2d& hit : hits) {
      hit = T_submap_scanner * hit;
    }
    grid.insertScan(T_submap_scanner.translation(), hits, {});
  }
  const SE2 T_submap_robot(inside(random), inside(random), heading(random));
  std::vector<Eigen::Vector2d> scan_robot = castScan(walls, T_submap_robot, 120);
  return SyntheticRoom{walls, grid, T_submap_robot, scan_robot};
}

inline constexpr const char* kIntelLog = "logs/carmen-intel-corrected.log.gz";

/// The first `count` scans of a CARMEN log, each with its logged (corrected) laser pose.
inline std::vector<LaserScan> carmenScans(const std::string& path, std::size_t count) {
  drivers::CarmenSettings settings;
  settings.path = path;
  drivers::CarmenReader reader(settings);
  std::vector<LaserScan> scans;
  while (scans.size() < count) {
    const std::optional<Sample> sample = reader.next();
    if (!sample) {
      break;
    }
    if (const auto* scan = std::get_if<LaserScan>(&*sample); scan && scan->logged_pose) {
      scans.push_back(*scan);
    }
  }
  return scans;
}

/// End points of the finite readings below max_range_m, in the laser frame.
inline std::vector<Eigen::Vector2d> hitsOf(const LaserScan& scan, double max_range_m = 50.0) {
  std::vector<Eigen::Vector2d> hits;
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double range = scan.ranges_m[i];
    if (std::isfinite(range) && range < max_range_m) {
      const double angle = scan.beamAngle(i);
      hits.emplace_back(range * std::cos(angle), range * std::sin(angle));
    }
  }
  return hits;
}

/// A submap of the scans inserted at their logged poses (hits only, no misses); the submap frame
/// is the log's.
inline slam::ProbabilityGrid submapOf(const std::vector<LaserScan>& scans) {
  slam::ProbabilityGrid grid{slam::ProbabilityGridSettings{}};
  for (const LaserScan& scan : scans) {
    const SE2& T_submap_laser = *scan.logged_pose;
    std::vector<Eigen::Vector2d> hits = hitsOf(scan);
    for (Eigen::Vector2d& hit : hits) {
      hit = T_submap_laser * hit;
    }
    grid.insertScan(T_submap_laser.translation(), hits, {});
  }
  return grid;
}

}  // namespace mrslam::robot::test
