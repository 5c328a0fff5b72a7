#pragma once
// A laser scan as the point sets scan matching needs: hit points in the robot frame, thinned, and
// (for a matching target) each with the normal of the surface it lies on.
//
// Normals follow the ordered-scan approach of PL-ICP (Censi, ICRA 2008): the neighbours of a hit
// in beam order that belong to the same surface (no jump between consecutive hits) are fitted
// with a line by principal component analysis; the normal is the eigenvector of the smallest
// eigenvalue of their scatter matrix, kept only when the points lie close to a line.

#include <Eigen/Core>
#include <vector>

#include "mrslam/common/samples.hpp"
#include "mrslam/common/se2.hpp"

namespace mrslam::robot {

struct ScanPointSettings {
  double min_range_m = 0.1;     ///< closer readings are not used for matching
  double max_range_m = 30.0;    ///< farther readings are not used (sparse, angular error grows)
  double min_spacing_m = 0.05;  ///< thinning: a point closer than this to the last kept one goes
  int normal_half_window = 3;   ///< neighbours in beam order on each side fitted for a normal
  double max_step_m = 0.25;     ///< consecutive hits further apart (beyond the beam spacing) are
                                ///< on different surfaces
  double max_step_beam_factor = 3.0;  ///< ... or further than this many beam spacings at that range
  double max_line_ratio = 0.15;       ///< √(λmin/λmax) above this: not a line, no normal
};

/// Points with unit normals (normals may be empty for source point sets).
struct OrientedPoints {
  std::vector<Eigen::Vector2d> points;
  std::vector<Eigen::Vector2d> normals;
};

/// The hits of `scan` within the ranges of `settings`, in the robot frame, in beam order,
/// with the range of each (for the beam-spacing test).
struct ScanHits {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> ranges;
  std::vector<std::size_t> beams;  ///< index of each hit's beam in the scan
  double angle_increment_rad = 0.0;
};
ScanHits scanHits(const LaserScan& scan, const SE2& T_robot_laser,
                  const ScanPointSettings& settings);

/// Keeps hits (in order) at least min_spacing_m from the last kept one.
std::vector<Eigen::Vector2d> thinned(const ScanHits& hits, const ScanPointSettings& settings);

/// Hits with a line-like neighbourhood, with their normals, thinned as above.
OrientedPoints orientedHits(const ScanHits& hits, const ScanPointSettings& settings);

/// Every point and normal moved by T_b_a (from frame a to frame b).
OrientedPoints transformed(const OrientedPoints& points_a, const SE2& T_b_a);

/// The normal of a set of points fitted with a line (unit, its sign arbitrary) and
/// √(λmin/λmax) of their scatter; ratio 1 when there are fewer than 3 points.
struct LineFit {
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();
  double ratio = 1.0;
};
LineFit fitLine(const std::vector<Eigen::Vector2d>& points);

}  // namespace mrslam::robot
