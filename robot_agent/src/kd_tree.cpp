#include "mrslam/robot/kd_tree.hpp"

#include <algorithm>
#include <utility>

namespace mrslam::robot {

namespace {

constexpr int kLeafSize = 8;  // ranges this small are scanned linearly

}  // namespace

KdTree2d::KdTree2d(const std::vector<Eigen::Vector2d>& points) : split_axis_(points.size(), 0) {
  std::vector<std::pair<Eigen::Vector2d, int>> entries(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    entries[i] = {points[i], static_cast<int>(i)};
  }
  build(entries, 0, static_cast<int>(entries.size()));
  points_.reserve(entries.size());
  original_index_.reserve(entries.size());
  for (const auto& [point, index] : entries) {
    points_.push_back(point);
    original_index_.push_back(index);
  }
}

void KdTree2d::build(std::vector<std::pair<Eigen::Vector2d, int>>& entries, int lo, int hi) {
  if (hi - lo <= kLeafSize) {
    return;
  }
  Eigen::Vector2d low = entries[lo].first;
  Eigen::Vector2d high = low;
  for (int i = lo + 1; i < hi; ++i) {
    low = low.cwiseMin(entries[i].first);
    high = high.cwiseMax(entries[i].first);
  }
  const int axis = (high.x() - low.x()) >= (high.y() - low.y()) ? 0 : 1;
  const int mid = lo + (hi - lo) / 2;
  std::nth_element(entries.begin() + lo, entries.begin() + mid, entries.begin() + hi,
                   [axis](const auto& a, const auto& b) { return a.first[axis] < b.first[axis]; });
  split_axis_[mid] = static_cast<std::uint8_t>(axis);
  build(entries, lo, mid);
  build(entries, mid + 1, hi);
}

KdTree2d::Neighbour KdTree2d::nearest(const Eigen::Vector2d& query, double max_distance_m) const {
  Neighbour best;
  best.distance_sq = max_distance_m * max_distance_m;
  searchNearest(0, static_cast<int>(points_.size()), query, best);
  if (best.index >= 0) {
    best.index = original_index_[best.index];
  }
  return best;
}

void KdTree2d::searchNearest(int lo, int hi, const Eigen::Vector2d& query, Neighbour& best) const {
  if (hi - lo <= kLeafSize) {
    for (int i = lo; i < hi; ++i) {
      const double d = (points_[i] - query).squaredNorm();
      if (d < best.distance_sq) {
        best = {i, d};
      }
    }
    return;
  }
  const int mid = lo + (hi - lo) / 2;
  const int axis = split_axis_[mid];
  const double d_mid = (points_[mid] - query).squaredNorm();
  if (d_mid < best.distance_sq) {
    best = {mid, d_mid};
  }
  const double offset = query[axis] - points_[mid][axis];
  const bool left_first = offset < 0.0;
  searchNearest(left_first ? lo : mid + 1, left_first ? mid : hi, query, best);
  if (offset * offset < best.distance_sq) {
    searchNearest(left_first ? mid + 1 : lo, left_first ? hi : mid, query, best);
  }
}

std::vector<KdTree2d::Neighbour> KdTree2d::nearestK(const Eigen::Vector2d& query, std::size_t k,
                                                    double max_distance_m) const {
  KBest best{k, max_distance_m * max_distance_m, {}};
  if (k == 0) {
    return {};
  }
  best.found.reserve(k + 1);
  searchK(0, static_cast<int>(points_.size()), query, best);
  for (Neighbour& neighbour : best.found) {
    neighbour.index = original_index_[neighbour.index];
  }
  return best.found;
}

void KdTree2d::searchK(int lo, int hi, const Eigen::Vector2d& query, KBest& best) const {
  if (hi - lo <= kLeafSize) {
    for (int i = lo; i < hi; ++i) {
      best.offer({i, (points_[i] - query).squaredNorm()});
    }
    return;
  }
  const int mid = lo + (hi - lo) / 2;
  const int axis = split_axis_[mid];
  best.offer({mid, (points_[mid] - query).squaredNorm()});
  const double offset = query[axis] - points_[mid][axis];
  const bool left_first = offset < 0.0;
  searchK(left_first ? lo : mid + 1, left_first ? mid : hi, query, best);
  if (offset * offset < best.bound()) {
    searchK(left_first ? mid + 1 : lo, left_first ? hi : mid, query, best);
  }
}

void KdTree2d::KBest::offer(const Neighbour& candidate) {
  if (candidate.distance_sq >= bound()) {
    return;
  }
  auto place = std::upper_bound(
      found.begin(), found.end(), candidate,
      [](const Neighbour& a, const Neighbour& b) { return a.distance_sq < b.distance_sq; });
  found.insert(place, candidate);
  if (found.size() > k) {
    found.pop_back();
  }
}

double KdTree2d::KBest::bound() const {
  return found.size() < k ? radius_sq : found.back().distance_sq;
}

}  // namespace mrslam::robot
