#include "mrslam/robot/scan_points.hpp"

#include <cmath>

namespace mrslam::robot {

namespace {

// True when hits i and j (neighbours in beam order) are on one surface.
bool sameSurface(const ScanHits& hits, std::size_t i, std::size_t j,
                 const ScanPointSettings& settings) {
  const double spacing = std::max(hits.ranges[i], hits.ranges[j]) * hits.angle_increment_rad;
  const double limit = std::max(settings.max_step_m, settings.max_step_beam_factor * spacing);
  return (hits.points[i] - hits.points[j]).norm() <= limit;
}

// The hits around i (in beam order) on the same surface, i included.
std::vector<Eigen::Vector2d> surfaceNeighbours(const ScanHits& hits, std::size_t i,
                                               const ScanPointSettings& settings) {
  std::vector<Eigen::Vector2d> neighbours{hits.points[i]};
  for (std::size_t j = i; j > 0 && i - (j - 1) <= std::size_t(settings.normal_half_window); --j) {
    if (!sameSurface(hits, j, j - 1, settings)) {
      break;
    }
    neighbours.push_back(hits.points[j - 1]);
  }
  for (std::size_t j = i;
       j + 1 < hits.points.size() && (j + 1) - i <= std::size_t(settings.normal_half_window); ++j) {
    if (!sameSurface(hits, j, j + 1, settings)) {
      break;
    }
    neighbours.push_back(hits.points[j + 1]);
  }
  return neighbours;
}

}  // namespace

ScanHits scanHits(const LaserScan& scan, const SE2& T_robot_laser,
                  const ScanPointSettings& settings) {
  ScanHits hits;
  hits.angle_increment_rad = std::abs(scan.angle_increment_rad);
  hits.points.reserve(scan.ranges_m.size());
  hits.ranges.reserve(scan.ranges_m.size());
  hits.beams.reserve(scan.ranges_m.size());
  const double min_range = std::max(settings.min_range_m, scan.range_min_m);
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double range = scan.ranges_m[i];
    if (!std::isfinite(range) || range < min_range || range > settings.max_range_m) {
      continue;  // no return, invalid, or out of the matching range
    }
    const double angle = scan.beamAngle(i);
    hits.points.push_back(T_robot_laser *
                          Eigen::Vector2d(range * std::cos(angle), range * std::sin(angle)));
    hits.ranges.push_back(range);
    hits.beams.push_back(i);
  }
  return hits;
}

std::vector<Eigen::Vector2d> thinned(const ScanHits& hits, const ScanPointSettings& settings) {
  std::vector<Eigen::Vector2d> kept;
  kept.reserve(hits.points.size());
  const double spacing_sq = settings.min_spacing_m * settings.min_spacing_m;
  for (const Eigen::Vector2d& point : hits.points) {
    if (kept.empty() || (point - kept.back()).squaredNorm() >= spacing_sq) {
      kept.push_back(point);
    }
  }
  return kept;
}

LineFit fitLine(const std::vector<Eigen::Vector2d>& points) {
  LineFit fit;
  if (points.size() < 3) {
    return fit;
  }
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) {
    mean += p;
  }
  mean /= static_cast<double>(points.size());
  double sxx = 0.0;
  double sxy = 0.0;
  double syy = 0.0;
  for (const Eigen::Vector2d& p : points) {
    const Eigen::Vector2d d = p - mean;
    sxx += d.x() * d.x();
    sxy += d.x() * d.y();
    syy += d.y() * d.y();
  }
  // Eigen-decomposition of the 2 × 2 scatter in closed form: the line runs at
  // φ = ½ atan2(2 sxy, sxx − syy); λ = (sxx + syy)/2 ± √(((sxx − syy)/2)² + sxy²).
  const double phi = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  fit.normal = Eigen::Vector2d(-std::sin(phi), std::cos(phi));
  const double centre = 0.5 * (sxx + syy);
  const double spread = std::hypot(0.5 * (sxx - syy), sxy);
  const double largest = centre + spread;
  fit.ratio = largest > 0.0 ? std::sqrt(std::max(centre - spread, 0.0) / largest) : 1.0;
  return fit;
}

OrientedPoints orientedHits(const ScanHits& hits, const ScanPointSettings& settings) {
  OrientedPoints oriented;
  const double spacing_sq = settings.min_spacing_m * settings.min_spacing_m;
  for (std::size_t i = 0; i < hits.points.size(); ++i) {
    if (!oriented.points.empty() &&
        (hits.points[i] - oriented.points.back()).squaredNorm() < spacing_sq) {
      continue;
    }
    const LineFit fit = fitLine(surfaceNeighbours(hits, i, settings));
    if (fit.ratio > settings.max_line_ratio) {
      continue;
    }
    oriented.points.push_back(hits.points[i]);
    oriented.normals.push_back(fit.normal);
  }
  return oriented;
}

OrientedPoints transformed(const OrientedPoints& points_a, const SE2& T_b_a) {
  OrientedPoints points_b;
  points_b.points.reserve(points_a.points.size());
  points_b.normals.reserve(points_a.normals.size());
  const Eigen::Matrix2d rotation = T_b_a.rotation();
  for (const Eigen::Vector2d& p : points_a.points) {
    points_b.points.push_back(T_b_a * p);
  }
  for (const Eigen::Vector2d& n : points_a.normals) {
    points_b.normals.push_back(rotation * n);
  }
  return points_b;
}

}  // namespace mrslam::robot
