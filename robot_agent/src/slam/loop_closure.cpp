#include "mrslam/robot/slam/loop_closure.hpp"

#include <algorithm>
#include <stdexcept>

namespace mrslam::robot::slam {

namespace {

std::vector<Eigen::Vector2d> withinRange(const std::vector<Eigen::Vector2d>& points,
                                         double max_range_m) {
  std::vector<Eigen::Vector2d> kept;
  kept.reserve(points.size());
  for (const Eigen::Vector2d& p : points) {
    if (p.norm() <= max_range_m) {
      kept.push_back(p);
    }
  }
  return kept;
}

}  // namespace

LoopCloser::LoopCloser(const LoopClosureSettings& settings)
    : settings_(settings), refiner_(settings.refine) {
  if (settings_.min_window_m > settings_.search.linear_search_window_m ||
      settings_.min_window_rad > settings_.search.angular_search_window_rad) {
    throw std::invalid_argument("loop closure: the smallest window exceeds the widest");
  }
}

void LoopCloser::addFinishedSubmap(const std::shared_ptr<const Submap>& submap) {
  const auto id = static_cast<std::size_t>(submap->id);
  if (submaps_.size() <= id) {
    submaps_.resize(id + 1);
  }
  submaps_[id].submap = submap;
  submaps_[id].matcher = std::make_unique<FastCorrelativeMatcher>(submap->grid, settings_.search);
}

bool LoopCloser::isSearchable(int submap) const {
  return submap >= 0 && static_cast<std::size_t>(submap) < submaps_.size() &&
         submaps_[static_cast<std::size_t>(submap)].matcher != nullptr;
}

double LoopCloser::saturatingDrift() const {
  const auto reach = [](double widest, double narrowest, double growth) {
    return growth > 0.0 ? std::max(0.0, widest - narrowest) / growth : 0.0;
  };
  return std::max(reach(settings_.search.linear_search_window_m, settings_.min_window_m,
                        settings_.window_growth_per_m),
                  reach(settings_.search.angular_search_window_rad, settings_.min_window_rad,
                        settings_.window_growth_rad_per_m));
}

std::optional<LoopClosure> LoopCloser::search(int submap, const SE2& T_submap_node_guess,
                                              const std::vector<Eigen::Vector2d>& points,
                                              double drift_m) {
  if (!isSearchable(submap)) {
    return std::nullopt;
  }
  Searchable& target = submaps_[static_cast<std::size_t>(submap)];
  target.sampled += settings_.sampling_ratio;
  if (target.sampled < 1.0) {
    return std::nullopt;
  }
  target.sampled -= 1.0;
  const std::vector<Eigen::Vector2d> near = withinRange(points, settings_.max_range_m);
  if (near.empty()) {
    return std::nullopt;
  }
  ++counters_.searches;
  const double window_m =
      std::min(settings_.search.linear_search_window_m,
               settings_.min_window_m + settings_.window_growth_per_m * drift_m);
  const double window_rad =
      std::min(settings_.search.angular_search_window_rad,
               settings_.min_window_rad + settings_.window_growth_rad_per_m * drift_m);
  const std::optional<FastMatch> found =
      target.matcher->match(T_submap_node_guess, near, settings_.min_score, window_m, window_rad);
  if (!found) {
    return std::nullopt;
  }
  const std::optional<CeresMatch> refined =
      refiner_.match(target.submap->grid, found->T_submap_robot, near);
  if (!refined) {
    return std::nullopt;
  }
  ++counters_.found;
  return LoopClosure{submap, refined->T_submap_robot, found->score};
}

}  // namespace mrslam::robot::slam
