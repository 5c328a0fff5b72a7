#pragma once
// How sharp a finished map is: scans re-registered against it should fit it closely. Occupied
// cells become a point set with normals (line fits of their k nearest neighbours); each scan is
// aligned to it by point-to-line ICP from the pose it was inserted at; a blurred map (walls
// doubled or thickened by pose errors) leaves larger residuals.

#include <vector>

#include "mrslam/common/occupancy_grid.hpp"
#include "mrslam/common/platform.hpp"
#include "mrslam/common/samples.hpp"
#include "mrslam/robot/icp.hpp"

namespace mrslam::robot {

/// Map-frame centres of the cells whose occupancy is above `threshold_percent`.
std::vector<Eigen::Vector2d> occupiedCellCentres(const OccupancyGrid& grid, int threshold_percent);

/// Points with normals from their `k` nearest neighbours within `radius_m`; points whose
/// neighbourhood is not line-like (√(λmin/λmax) > max_line_ratio) are dropped.
OrientedPoints withNeighbourNormals(const std::vector<Eigen::Vector2d>& points, std::size_t k,
                                    double radius_m, double max_line_ratio);

struct ReregistrationSettings {
  int occupied_threshold_percent = 65;       ///< cells above this are walls
  std::size_t normal_neighbours = 6;         ///< k of withNeighbourNormals
  double normal_radius_m = 0.25;             ///< radius of withNeighbourNormals
  double max_line_ratio = 0.3;               ///< line test of withNeighbourNormals
  ScanPointSettings points = densePoints();  ///< which hits of a scan are used
  IcpSettings icp = lenientIcp();            ///< the re-registration
  /// Scan points 2 cm apart at least.
  static ScanPointSettings densePoints() {
    ScanPointSettings points;
    points.min_spacing_m = 0.02;
    return points;
  }
  /// ICP that accepts a scan seeing little of the map (walls a map has cleared since).
  static IcpSettings lenientIcp() {
    IcpSettings icp;
    icp.min_inlier_fraction = 0.1;
    return icp;
  }
};

struct ReregistrationResult {
  std::size_t scans = 0;              ///< scans re-registered
  std::size_t failed = 0;             ///< of which ICP failed
  double mean_rms_m = 0.0;            ///< mean point-to-line RMS of the successful ones
  double mean_inlier_fraction = 0.0;  ///< mean fraction of points within the ICP's d_min
  double mean_correction_m = 0.0;     ///< mean translation ICP moved the scans by
};

/// How well scans agree with a finished map at the poses they were inserted at: a sharp map keeps
/// the cells the hits fell in occupied; where poses were wrong, other beams cleared them.
struct HitAgreement {
  std::size_t hits = 0;               ///< hit points tested
  double fraction_on_occupied = 0.0;  ///< of hits in a cell above the occupied threshold
  double mean_distance_m = 0.0;       ///< mean distance of a hit to the nearest occupied centre
};

/// Hit agreement of `scans` at `T_map_robot` (hits up to max_range_m) with `grid`.
HitAgreement hitAgreement(const OccupancyGrid& grid, const std::vector<LaserScan>& scans,
                          const std::vector<SE2>& T_map_robot, const SensorMounting& mounting,
                          double max_range_m, int occupied_threshold_percent = 50);

/// Re-registers `scans` (inserted at `T_map_robot`) against `grid`.
ReregistrationResult reregisterScans(const OccupancyGrid& grid, const std::vector<LaserScan>& scans,
                                     const std::vector<SE2>& T_map_robot,
                                     const SensorMounting& mounting,
                                     const ReregistrationSettings& settings);

}  // namespace mrslam::robot
