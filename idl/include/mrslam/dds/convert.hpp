#pragma once
// Conversions between the wire types (mrslam_msgs.idl) and the project's own types. Anything
// coming from the network is checked: a grid whose header disagrees with its data is refused.

#include <cstdint>
#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/common/result.hpp"
#include "mrslam/common/se2.hpp"
#include "mrslam/common/stamp.hpp"
#include "mrslam_msgs.h"

namespace mrslam::dds {

msg::Time toMsg(Stamp stamp);
Stamp fromMsg(const msg::Time& time);
msg::Pose2D toMsg(const SE2& pose);
SE2 fromMsg(const msg::Pose2D& pose);

/// Fills a message's grid header and cells.
void gridToMsg(const GridMap& map, msg::GridInfo& info, std::vector<std::uint8_t>& data);

/// A grid received from the network, or why it is refused (resolution not positive or not
/// finite, a non-finite or rotated origin, more than `max_cells` cells, a cell count that
/// disagrees with width × height, a value outside -1..100).
Result<GridMap> gridFromMsg(const msg::GridInfo& info, const std::vector<std::uint8_t>& data,
                            std::size_t max_cells);

}  // namespace mrslam::dds
