#pragma once
// Submaps of local SLAM (Hess et al., ICRA 2016, section IV): a submap is a probability grid of
// a few consecutive scans, in the local frame shifted to the first scan's position. Two submaps
// are active: every scan goes into both; scans are matched against the older. When the newer
// holds num_range_data scans a third one starts and the oldest, which then holds
// 2·num_range_data, is finished: it never changes again and can be searched for loop closures.

#include <memory>
#include <vector>

#include "mrslam/robot/slam/probability_grid.hpp"
#include "mrslam/robot/slam/range_data.hpp"

namespace mrslam::robot::slam {

struct Submap {
  Submap(int submap_id, const SE2& T_local_submap_in, const ProbabilityGridSettings& settings)
      : id(submap_id), T_local_submap(T_local_submap_in), grid(settings) {}

  int id;                ///< index in the order submaps were started
  SE2 T_local_submap;    ///< the submap frame in the local SLAM frame (a translation)
  ProbabilityGrid grid;  ///< in the submap frame
  int insertions = 0;
  bool finished = false;
};

struct SubmapSettings {
  int num_range_data = 90;       ///< scans of a submap before the next one starts
  ProbabilityGridSettings grid;  ///< the cells and their update rule
};

class ActiveSubmaps {
 public:
  explicit ActiveSubmaps(const SubmapSettings& settings);

  /// Inserts range data given in the local frame (with its origin); returns the submaps it went
  /// into. A submap that becomes finished is reported by finishedSinceLastInsert().
  std::vector<std::shared_ptr<Submap>> insert(const RangeData& data_local);

  /// The submap scans are matched against (null before the first insertion).
  std::shared_ptr<const Submap> matchingSubmap() const {
    return active_.empty() ? nullptr : active_.front();
  }
  /// The submap the last insert() finished, if any.
  const std::shared_ptr<Submap>& finishedByLastInsert() const { return finished_; }
  const std::vector<std::shared_ptr<Submap>>& active() const { return active_; }
  int submapsStarted() const { return next_id_; }

 private:
  void startSubmap(const Eigen::Vector2d& origin_local);

  const SubmapSettings settings_;
  std::vector<std::shared_ptr<Submap>> active_;
  std::shared_ptr<Submap> finished_;
  int next_id_ = 0;
};

}  // namespace mrslam::robot::slam
