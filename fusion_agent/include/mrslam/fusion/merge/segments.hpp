#pragma once
// Block 3 of the seed merge: segments of the edge image and their vectors D and Δ.
//
// 1. A segment starts at a random (seeded) edge cell of the smoothed edge image.
// 2. Edge following walks from cell to unvisited edge cell, in the 8-neighbourhood first and,
//    at a break, up to `gap_jump_cells` away; it prefers the candidate that turns least and never
//    turns by more than ~107° in one step. At a dead end it walks from the start the other way.
// 3. The cell chain is smoothed (moving average of 5) and resampled to n points one cell of arc
//    length apart, so that a segment covers the same length of wall whatever its orientation in
//    the grid (a chain of raw cells would be √2 longer along diagonals).
// 4. D_i is the distance of point i to the total-least-squares line of the segment; Δ is the
//    sequence of turning angles between the chords p_i - p_(i-k) and p_(i+k) - p_i for
//    i = k … n-1-k. Both are invariant to the rigid transform between two maps, so the
//    segments of one wall in two maps have matching D and Δ.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace mrslam::fusion {

/// Settings of block 3.
struct SegmentSettings {
  int segment_points_n = 48;  ///< n: points of a segment, one cell of arc length apart
  int turn_chord_k = 3;       ///< k: chord length (points) of the turning angles Δ
  int gap_jump_cells = 2;     ///< edge following jumps breaks of the edge up to this (cells)
};

/// A total-least-squares line: centroid and direction angle (defined modulo π).
struct FittedLine {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  double angle_rad = 0.0;  ///< direction of the line in [0, π)
};

/// A segment of an edge: n points along it with its D and Δ vectors.
struct Segment {
  std::vector<Eigen::Vector2d> points;  ///< n points, cell coordinates (x = column, y = row)
  FittedLine line;                      ///< line fitted to all points
  std::vector<double> distances;        ///< D: distance (cells) of each point to `line`
  std::vector<double> turns;            ///< Δ: turning angle (rad) at points k … n-1-k
};

/// Fits a total-least-squares line to points[first, first + count).
FittedLine fitLine(const std::vector<Eigen::Vector2d>& points, std::size_t first,
                   std::size_t count);

/// Follows edges from cell to cell. Keeps a visit stamp per cell, so one follower serves many
/// segments of one edge image without clearing.
class EdgeFollower {
 public:
  EdgeFollower(const cv::Mat& edges, int gap_jump_cells);
  /// The chain of edge cells through `start`, about `length_cells` long (shorter at dead ends).
  std::vector<cv::Point> follow(cv::Point start, double length_cells);

 private:
  std::vector<cv::Point> walk(cv::Point from, cv::Point direction_hint, double length_cells);
  std::optional<cv::Point> nextCell(cv::Point current, const Eigen::Vector2d& direction) const;
  bool isFreshEdge(int x, int y) const;
  void visit(cv::Point cell);

  cv::Mat edges_;
  int gap_jump_cells_;
  std::vector<int> stamps_;
  int stamp_ = 0;
};

/// Blocks 3.3-3.4: the segment of a cell chain, or nothing when the chain is shorter than n.
std::optional<Segment> makeSegment(const std::vector<cv::Point>& chain,
                                   const SegmentSettings& settings);

}  // namespace mrslam::fusion
