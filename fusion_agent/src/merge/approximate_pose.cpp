#include "mrslam/fusion/merge/approximate_pose.hpp"

#include <algorithm>
#include <cmath>

namespace mrslam::fusion {

Eigen::Vector2d translationFromCentroids(double theta_rad, const Eigen::Vector2d& centroid_from,
                                         const Eigen::Vector2d& centroid_to) {
  const double c = std::cos(theta_rad);
  const double s = std::sin(theta_rad);
  return centroid_to - Eigen::Vector2d(c * centroid_from.x() - s * centroid_from.y(),
                                       s * centroid_from.x() + c * centroid_from.y());
}

std::array<GridTransform, 2> posesFromLines(const FittedLine& from, const FittedLine& to) {
  std::array<GridTransform, 2> poses;
  const double theta = std::remainder(to.angle_rad - from.angle_rad, 2.0 * M_PI);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    poses[i].theta_rad = std::remainder(theta + static_cast<double>(i) * M_PI, 2.0 * M_PI);
    poses[i].t_cells = translationFromCentroids(poses[i].theta_rad, from.centroid, to.centroid);
  }
  return poses;
}

std::pair<FittedLine, FittedLine> matchedLines(const Segment& from, const Segment& to,
                                               const SegmentMatch& match) {
  const int n = static_cast<int>(std::min(from.points.size(), to.points.size()));
  const int first = std::max(0, -match.offset);
  const int count = std::max(1, n - std::abs(match.offset));
  const Segment to_walked = match.reversed ? reversedSegment(to) : to;
  const FittedLine line_from =
      fitLine(from.points, static_cast<std::size_t>(first), static_cast<std::size_t>(count));
  const FittedLine line_to =
      fitLine(to_walked.points, static_cast<std::size_t>(first + match.offset),
              static_cast<std::size_t>(count));
  return {line_from, line_to};
}

std::array<GridTransform, 2> approximatePoses(const Segment& from, const Segment& to,
                                              const SegmentMatch& match) {
  const auto [line_from, line_to] = matchedLines(from, to, match);
  return posesFromLines(line_from, line_to);
}

}  // namespace mrslam::fusion
