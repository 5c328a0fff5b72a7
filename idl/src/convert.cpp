#include "mrslam/dds/convert.hpp"

#include <cmath>
#include <string>

namespace mrslam::dds {

msg::Time toMsg(Stamp stamp) {
  msg::Time time;
  std::int64_t seconds = stamp.ns / 1000000000;
  std::int64_t nanoseconds = stamp.ns % 1000000000;
  if (nanoseconds < 0) {
    nanoseconds += 1000000000;
    --seconds;
  }
  time.sec(static_cast<std::int32_t>(seconds));
  time.nanosec(static_cast<std::uint32_t>(nanoseconds));
  return time;
}

Stamp fromMsg(const msg::Time& time) {
  return Stamp{static_cast<std::int64_t>(time.sec()) * 1000000000 +
               static_cast<std::int64_t>(time.nanosec())};
}

msg::Pose2D toMsg(const SE2& pose) {
  msg::Pose2D out;
  out.x(pose.x());
  out.y(pose.y());
  out.theta(pose.theta());
  return out;
}

SE2 fromMsg(const msg::Pose2D& pose) {
  return SE2(pose.x(), pose.y(), pose.theta());
}

void gridToMsg(const GridMap& map, msg::GridInfo& info, std::vector<std::uint8_t>& data) {
  info.resolution(map.geometry.resolution_m);
  info.width(static_cast<std::uint32_t>(map.geometry.width));
  info.height(static_cast<std::uint32_t>(map.geometry.height));
  info.origin(toMsg(SE2(map.geometry.origin_m.x(), map.geometry.origin_m.y(), 0.0)));
  data.resize(map.cells.size());
  for (std::size_t i = 0; i < map.cells.size(); ++i) {
    data[i] = static_cast<std::uint8_t>(map.cells[i]);
  }
}

Result<GridMap> gridFromMsg(const msg::GridInfo& info, const std::vector<std::uint8_t>& data,
                            std::size_t max_cells) {
  const double resolution = info.resolution();
  if (!std::isfinite(resolution) || resolution <= 0.0) {
    return Result<GridMap>::failure("resolution " + std::to_string(resolution) +
                                    " is not a positive number");
  }
  const msg::Pose2D& origin = info.origin();
  if (!std::isfinite(origin.x()) || !std::isfinite(origin.y()) || !std::isfinite(origin.theta())) {
    return Result<GridMap>::failure("the origin is not finite");
  }
  if (origin.theta() != 0.0) {
    return Result<GridMap>::failure("the origin is rotated (theta " +
                                    std::to_string(origin.theta()) +
                                    "); grids must be axis-aligned");
  }
  const std::uint64_t cells = static_cast<std::uint64_t>(info.width()) * info.height();
  if (cells > max_cells || info.width() > 1u << 20 || info.height() > 1u << 20) {
    return Result<GridMap>::failure(std::to_string(info.width()) + " x " +
                                    std::to_string(info.height()) + " cells exceed the limit of " +
                                    std::to_string(max_cells));
  }
  if (data.size() != cells) {
    return Result<GridMap>::failure("header says " + std::to_string(info.width()) + " x " +
                                    std::to_string(info.height()) + " cells, data holds " +
                                    std::to_string(data.size()));
  }
  GridMap map;
  map.geometry.resolution_m = resolution;
  map.geometry.width = static_cast<int>(info.width());
  map.geometry.height = static_cast<int>(info.height());
  map.geometry.origin_m = Eigen::Vector2d(origin.x(), origin.y());
  map.cells.resize(data.size());
  for (std::size_t i = 0; i < data.size(); ++i) {
    const auto value = static_cast<std::int8_t>(data[i]);
    if (value < GridMap::kUnknown || value > GridMap::kOccupied) {
      return Result<GridMap>::failure("cell " + std::to_string(i) + " holds " +
                                      std::to_string(value) + ", outside -1..100");
    }
    map.cells[i] = value;
  }
  return Result<GridMap>::success(std::move(map));
}

}  // namespace mrslam::dds
