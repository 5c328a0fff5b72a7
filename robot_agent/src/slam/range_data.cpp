#include "mrslam/robot/slam/range_data.hpp"

#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace mrslam::robot::slam {

RangeData rangeDataOf(const LaserScan& scan, const SE2& T_robot_laser,
                      const RangeDataSettings& settings) {
  RangeData data;
  data.origin = T_robot_laser.translation();
  const double max_range = std::min(
      settings.max_range_m, scan.range_max_m > 0.0 ? scan.range_max_m : settings.max_range_m);
  const double min_range = std::max(settings.min_range_m, scan.range_min_m);
  std::vector<Eigen::Vector2d> hits;
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double range = scan.ranges_m[i];
    if (std::isnan(range) || range < min_range) {
      continue;
    }
    const double angle = scan.beamAngle(i);
    const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
    if (std::isfinite(range) && range < max_range) {
      hits.push_back(T_robot_laser * (range * direction));
    } else if (settings.missing_data_ray_length_m > 0.0) {
      data.misses.push_back(T_robot_laser * (settings.missing_data_ray_length_m * direction));
    }
  }
  data.hits = voxelFiltered(hits, settings.voxel_m);
  return data;
}

std::vector<Eigen::Vector2d> voxelFiltered(const std::vector<Eigen::Vector2d>& points,
                                           double voxel_m) {
  if (voxel_m <= 0.0) {
    return points;
  }
  std::unordered_set<std::uint64_t> occupied;
  occupied.reserve(points.size() * 2);
  std::vector<Eigen::Vector2d> kept;
  kept.reserve(points.size());
  for (const Eigen::Vector2d& p : points) {
    const auto ix = static_cast<std::int64_t>(std::floor(p.x() / voxel_m));
    const auto iy = static_cast<std::int64_t>(std::floor(p.y() / voxel_m));
    const std::uint64_t key =
        (static_cast<std::uint64_t>(ix) << 32) ^ (static_cast<std::uint64_t>(iy) & 0xffffffffULL);
    if (occupied.insert(key).second) {
      kept.push_back(p);
    }
  }
  return kept;
}

std::vector<Eigen::Vector2d> matchingPoints(const std::vector<Eigen::Vector2d>& hits,
                                            const RangeDataSettings& settings) {
  std::vector<Eigen::Vector2d> points = voxelFiltered(hits, settings.match_voxel_m);
  const auto max_points = static_cast<std::size_t>(settings.match_max_points);
  const auto min_points = static_cast<std::size_t>(settings.match_min_points);
  double voxel = settings.match_voxel_m;
  constexpr double kGrowth = 1.25;  // steps fine enough to stop near the wanted count
  constexpr int kMaxSteps = 20;     // a voxel 86 × the first: beyond it a scan is a few points
  for (int step = 0; step < kMaxSteps && points.size() > max_points; ++step) {
    voxel *= kGrowth;
    std::vector<Eigen::Vector2d> coarser = voxelFiltered(hits, voxel);
    if (coarser.size() < min_points) {
      break;
    }
    points.swap(coarser);
  }
  return points;
}

std::vector<Eigen::Vector2d> transformed(const std::vector<Eigen::Vector2d>& points_a,
                                         const SE2& T_b_a) {
  std::vector<Eigen::Vector2d> points_b;
  points_b.reserve(points_a.size());
  const Eigen::Matrix2d R = T_b_a.rotation();
  const Eigen::Vector2d t = T_b_a.translation();
  for (const Eigen::Vector2d& p : points_a) {
    points_b.push_back(R * p + t);
  }
  return points_b;
}

RangeData transformed(const RangeData& data_a, const SE2& T_b_a) {
  return {T_b_a * data_a.origin, transformed(data_a.hits, T_b_a),
          transformed(data_a.misses, T_b_a)};
}

}  // namespace mrslam::robot::slam
