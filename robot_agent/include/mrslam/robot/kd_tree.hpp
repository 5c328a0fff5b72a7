#pragma once
// A static 2-D k-d tree over a point set (Bentley 1975; Friedman, Bentley & Finkel 1977):
//  1. Build: split the points at the median of the axis with the larger extent, recursively,
//     storing the tree implicitly in the point order (the median of [lo, hi) sits at its middle).
//  2. Query: descend to the query's side first, then visit the far side only when the splitting
//     line is closer than the current k-th best distance.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace mrslam::robot {

class KdTree2d {
 public:
  /// A neighbour found by a query: its index in the input point set and its squared distance.
  struct Neighbour {
    int index = -1;
    double distance_sq = std::numeric_limits<double>::infinity();
  };

  KdTree2d() = default;
  explicit KdTree2d(const std::vector<Eigen::Vector2d>& points);

  std::size_t size() const { return points_.size(); }

  /// The nearest point closer than `max_distance_m`; index -1 when there is none.
  Neighbour nearest(const Eigen::Vector2d& query, double max_distance_m) const;

  /// Up to `k` nearest points closer than `max_distance_m`, nearest first.
  std::vector<Neighbour> nearestK(const Eigen::Vector2d& query, std::size_t k,
                                  double max_distance_m) const;

 private:
  void build(std::vector<std::pair<Eigen::Vector2d, int>>& entries, int lo, int hi);
  void searchNearest(int lo, int hi, const Eigen::Vector2d& query, Neighbour& best) const;
  /// The k best so far (nearest first) within the search radius.
  struct KBest {
    std::size_t k;
    double radius_sq;
    std::vector<Neighbour> found;
    void offer(const Neighbour& candidate);
    double bound() const;  ///< squared distance a candidate must beat
  };
  void searchK(int lo, int hi, const Eigen::Vector2d& query, KBest& best) const;

  std::vector<Eigen::Vector2d> points_;   ///< reordered into the implicit tree
  std::vector<int> original_index_;       ///< input index of each reordered point
  std::vector<std::uint8_t> split_axis_;  ///< axis of the split at each median position
};

}  // namespace mrslam::robot
