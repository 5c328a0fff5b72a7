#include "mrslam/fusion/map_composer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/Geometry>

namespace mrslam::fusion {

namespace {

// The box of cells [min, max) that holds every known cell of a map; nothing when none is known.
std::optional<Eigen::AlignedBox2i> knownCellBox(const GridMap& map) {
  Eigen::AlignedBox2i box;
  const GridGeometry& g = map.geometry;
  for (int cy = 0; cy < g.height; ++cy) {
    for (int cx = 0; cx < g.width; ++cx) {
      if (map.at(cx, cy) != GridMap::kUnknown) {
        box.extend(Eigen::Vector2i(cx, cy));
      }
    }
  }
  if (box.isEmpty()) {
    return std::nullopt;
  }
  return Eigen::AlignedBox2i(box.min(), box.max() + Eigen::Vector2i::Ones());
}

}  // namespace

bool placedBounds(const std::vector<PlacedMap>& maps, Eigen::Vector2d& min_m,
                  Eigen::Vector2d& max_m) {
  min_m = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  max_m = -min_m;
  bool any = false;
  for (const PlacedMap& placed : maps) {
    const std::optional<Eigen::AlignedBox2i> box = knownCellBox(*placed.map);
    if (!box) {
      continue;
    }
    any = true;
    const GridGeometry& g = placed.map->geometry;
    for (const auto corner : {Eigen::AlignedBox2i::BottomLeft, Eigen::AlignedBox2i::BottomRight,
                              Eigen::AlignedBox2i::TopLeft, Eigen::AlignedBox2i::TopRight}) {
      const Eigen::Vector2d p_robot =
          g.origin_m + box->corner(corner).cast<double>() * g.resolution_m;
      const Eigen::Vector2d p = placed.T_reference_robot * p_robot;
      min_m = min_m.cwiseMin(p);
      max_m = max_m.cwiseMax(p);
    }
  }
  return any;
}

namespace {

// The global grid's geometry: the placed maps' bounds, origin on the resolution lattice.
GridGeometry globalGeometry(const std::vector<PlacedMap>& maps, double resolution) {
  Eigen::Vector2d min_m;
  Eigen::Vector2d max_m;
  GridGeometry geometry;
  geometry.resolution_m = resolution;
  if (!placedBounds(maps, min_m, max_m)) {
    return geometry;  // nothing known: an empty map
  }
  const double min_cx = std::floor(min_m.x() / resolution + 1e-9);
  const double min_cy = std::floor(min_m.y() / resolution + 1e-9);
  geometry.origin_m = Eigen::Vector2d(min_cx * resolution, min_cy * resolution);
  geometry.width = static_cast<int>(std::ceil(max_m.x() / resolution - 1e-9) - min_cx);
  geometry.height = static_cast<int>(std::ceil(max_m.y() / resolution - 1e-9) - min_cy);
  return geometry;
}

// Log-odds of an occupancy value, with 0 and 100 taken as 0.4 % and 99.6 %: finite, and they
// round back to 0 and 100.
float valueLogOdds(std::int8_t value) {
  const double p = std::clamp(value / 100.0, 0.004, 0.996);
  return static_cast<float>(std::log(p / (1.0 - p)));
}

// Looks up, for every global cell, the cell of a placed map it falls in.
class PlacedLookup {
 public:
  PlacedLookup(const PlacedMap& placed, const GridGeometry& global)
      : placed_(placed), global_(global) {
    const GridGeometry& local = placed.map->geometry;
    const SE2 T_robot_reference = placed.T_reference_robot.inverse();
    rotation_ = T_robot_reference.rotation() / local.resolution_m;
    offset_ = (T_robot_reference.translation() - local.origin_m) / local.resolution_m;
  }

  /// The placed map's value at the centre of global cell (gx, gy); unknown outside it.
  std::int8_t valueAt(int gx, int gy) const {
    const Eigen::Vector2d q = rotation_ * global_.cellCenter(gx, gy) + offset_;
    const int cx = static_cast<int>(std::floor(q.x()));
    const int cy = static_cast<int>(std::floor(q.y()));
    return placed_.map->geometry.contains(cx, cy) ? placed_.map->at(cx, cy) : GridMap::kUnknown;
  }

 private:
  const PlacedMap& placed_;
  const GridGeometry& global_;
  Eigen::Matrix2d rotation_;
  Eigen::Vector2d offset_;
};

// Adds the evidence of one placed map to the global log-odds sums.
void accumulate(const PlacedMap& placed, const GridGeometry& global, std::vector<float>& sum,
                std::vector<std::uint8_t>& known) {
  const PlacedLookup lookup(placed, global);
  for (int gy = 0; gy < global.height; ++gy) {
    for (int gx = 0; gx < global.width; ++gx) {
      const std::int8_t value = lookup.valueAt(gx, gy);
      if (value == GridMap::kUnknown) {
        continue;
      }
      const std::size_t index = global.index(gx, gy);
      sum[index] += valueLogOdds(value);
      known[index] = 1;
    }
  }
}

}  // namespace

GridMap composeGlobalMap(const std::vector<PlacedMap>& maps, const ComposerSettings& settings) {
  if (maps.empty()) {
    return GridMap();
  }
  const double resolution =
      settings.resolution_m > 0.0 ? settings.resolution_m : maps.front().map->geometry.resolution_m;
  const GridGeometry geometry = globalGeometry(maps, resolution);
  std::vector<float> sum(geometry.cellCount(), 0.0f);
  std::vector<std::uint8_t> known(geometry.cellCount(), 0);
  for (const PlacedMap& placed : maps) {
    accumulate(placed, geometry, sum, known);
  }
  GridMap global(geometry, GridMap::kUnknown);
  for (std::size_t i = 0; i < sum.size(); ++i) {
    if (known[i] != 0) {
      const float clamped =
          std::clamp(sum[i], -settings.max_abs_log_odds, settings.max_abs_log_odds);
      global.cells[i] =
          static_cast<std::int8_t>(std::lround(100.0 * logOddsToProbability(clamped)));
    }
  }
  return global;
}

}  // namespace mrslam::fusion

namespace mrslam::fusion {

std::vector<Eigen::Vector2i> occupiedCellsOf(const PlacedMap& placed, const GridMap& global) {
  std::vector<Eigen::Vector2i> cells;
  const PlacedLookup lookup(placed, global.geometry);
  for (int gy = 0; gy < global.geometry.height; ++gy) {
    for (int gx = 0; gx < global.geometry.width; ++gx) {
      if (global.at(gx, gy) > 50 && lookup.valueAt(gx, gy) > 50) {
        cells.emplace_back(gx, gy);
      }
    }
  }
  return cells;
}

}  // namespace mrslam::fusion
