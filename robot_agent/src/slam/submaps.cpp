#include "mrslam/robot/slam/submaps.hpp"

#include <stdexcept>

namespace mrslam::robot::slam {

ActiveSubmaps::ActiveSubmaps(const SubmapSettings& settings) : settings_(settings) {
  if (settings_.num_range_data < 1) {
    throw std::invalid_argument("submaps: num_range_data must be at least 1");
  }
  ProbabilityGrid check(settings_.grid);  // throws on bad grid settings here, not at first scan
}

void ActiveSubmaps::startSubmap(const Eigen::Vector2d& origin_local) {
  active_.push_back(std::make_shared<Submap>(next_id_++, SE2(origin_local.x(), origin_local.y(), 0),
                                             settings_.grid));
}

std::vector<std::shared_ptr<Submap>> ActiveSubmaps::insert(const RangeData& data_local) {
  finished_.reset();
  if (active_.empty()) {
    startSubmap(data_local.origin);
  }
  for (const auto& submap : active_) {
    const SE2 T_submap_local = submap->T_local_submap.inverse();
    const RangeData data_submap = transformed(data_local, T_submap_local);
    submap->grid.insertScan(data_submap.origin, data_submap.hits, data_submap.misses);
    ++submap->insertions;
  }
  std::vector<std::shared_ptr<Submap>> inserted = active_;
  if (active_.back()->insertions >= settings_.num_range_data) {
    if (active_.size() == 2) {
      active_.front()->finished = true;
      active_.front()->grid.shrinkToKnown();  // it never changes again
      finished_ = active_.front();
      active_.erase(active_.begin());
    }
    startSubmap(data_local.origin);
  }
  return inserted;
}

}  // namespace mrslam::robot::slam
