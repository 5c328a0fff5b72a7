#include "mrslam/robot/map_quality.hpp"

#include <cmath>
#include <stdexcept>

namespace mrslam::robot {

std::vector<Eigen::Vector2d> occupiedCellCentres(const OccupancyGrid& grid, int threshold_percent) {
  std::vector<Eigen::Vector2d> centres;
  const GridGeometry& geometry = grid.geometry();
  for (int cy = 0; cy < geometry.height; ++cy) {
    for (int cx = 0; cx < geometry.width; ++cx) {
      if (grid.occupancy(cx, cy) > threshold_percent) {
        centres.push_back(geometry.cellCenter(cx, cy));
      }
    }
  }
  return centres;
}

OrientedPoints withNeighbourNormals(const std::vector<Eigen::Vector2d>& points, std::size_t k,
                                    double radius_m, double max_line_ratio) {
  const KdTree2d tree(points);
  OrientedPoints oriented;
  std::vector<Eigen::Vector2d> neighbourhood;
  for (const Eigen::Vector2d& point : points) {
    neighbourhood.clear();
    for (const KdTree2d::Neighbour& neighbour : tree.nearestK(point, k, radius_m)) {
      neighbourhood.push_back(points[neighbour.index]);
    }
    const LineFit fit = fitLine(neighbourhood);
    if (fit.ratio <= max_line_ratio) {
      oriented.points.push_back(point);
      oriented.normals.push_back(fit.normal);
    }
  }
  return oriented;
}

HitAgreement hitAgreement(const OccupancyGrid& grid, const std::vector<LaserScan>& scans,
                          const std::vector<SE2>& T_map_robot, const SensorMounting& mounting,
                          double max_range_m, int occupied_threshold_percent) {
  if (scans.size() != T_map_robot.size()) {
    throw std::invalid_argument("hitAgreement: one pose per scan is needed");
  }
  const std::vector<Eigen::Vector2d> occupied =
      occupiedCellCentres(grid, occupied_threshold_percent);
  const KdTree2d tree(occupied);
  ScanPointSettings points;
  points.max_range_m = max_range_m;
  points.min_range_m = 0.0;
  HitAgreement agreement;
  double on_occupied = 0.0;
  double distance_sum = 0.0;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    for (const Eigen::Vector2d& hit : scanHits(scans[i], mounting.T_robot_laser, points).points) {
      const Eigen::Vector2d p = T_map_robot[i] * hit;
      const Eigen::Vector2i cell = grid.cellOf(p);
      on_occupied += grid.occupancy(cell.x(), cell.y()) > occupied_threshold_percent ? 1.0 : 0.0;
      const KdTree2d::Neighbour nearest = tree.nearest(p, 1.0);
      distance_sum += nearest.index >= 0 ? std::sqrt(nearest.distance_sq) : 1.0;
      ++agreement.hits;
    }
  }
  if (agreement.hits > 0) {
    agreement.fraction_on_occupied = on_occupied / static_cast<double>(agreement.hits);
    agreement.mean_distance_m = distance_sum / static_cast<double>(agreement.hits);
  }
  return agreement;
}

ReregistrationResult reregisterScans(const OccupancyGrid& grid, const std::vector<LaserScan>& scans,
                                     const std::vector<SE2>& T_map_robot,
                                     const SensorMounting& mounting,
                                     const ReregistrationSettings& settings) {
  if (scans.size() != T_map_robot.size()) {
    throw std::invalid_argument("reregisterScans: one pose per scan is needed");
  }
  const IcpTarget target(withNeighbourNormals(
      occupiedCellCentres(grid, settings.occupied_threshold_percent), settings.normal_neighbours,
      settings.normal_radius_m, settings.max_line_ratio));
  ReregistrationResult result;
  double rms_sum = 0.0;
  double inlier_sum = 0.0;
  double correction_sum = 0.0;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const ScanHits hits = scanHits(scans[i], mounting.T_robot_laser, settings.points);
    const IcpResult icp =
        alignPointToLine(target, thinned(hits, settings.points), T_map_robot[i], settings.icp);
    ++result.scans;
    if (!icp.converged) {
      ++result.failed;
      continue;
    }
    rms_sum += icp.rms_m;
    inlier_sum += icp.inlier_fraction;
    correction_sum += (icp.T_target_source.translation() - T_map_robot[i].translation()).norm();
  }
  const std::size_t ok = result.scans - result.failed;
  if (ok > 0) {
    result.mean_rms_m = rms_sum / static_cast<double>(ok);
    result.mean_inlier_fraction = inlier_sum / static_cast<double>(ok);
    result.mean_correction_m = correction_sum / static_cast<double>(ok);
  }
  return result;
}

}  // namespace mrslam::robot
