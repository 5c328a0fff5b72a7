#include "mrslam/common/grid_map.hpp"

namespace mrslam {

bool GridMap::isValid() const {
  if (geometry.width < 0 || geometry.height < 0 || !(geometry.resolution_m > 0.0) ||
      !geometry.origin_m.allFinite() || cells.size() != geometry.cellCount()) {
    return false;
  }
  for (const std::int8_t value : cells) {
    if (value != kUnknown && (value < kFree || value > kOccupied)) {
      return false;
    }
  }
  return true;
}

}  // namespace mrslam
