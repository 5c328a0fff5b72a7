#include "mrslam/common/grid_map.hpp"

namespace mrslam {

bool GridMap::isValid() const {
  if (geometry.width < 0 || geometry.height < 0 || !(geometry.resolution_m > 0.0) ||
      !geometry.origin_m.allFinite() || cells.size() != geometry.cellCount()) {
    return false;
  }
  // kUnknown (-1) and kFree..kOccupied (0..100) are the values 0..101 once one is added (as a
  // byte): one comparison a cell, or-ed without a branch so that the loop is vectorised.
  static_assert(kUnknown == kFree - 1, "kUnknown lies just below kFree");
  constexpr auto kValidRange = static_cast<std::uint8_t>(kOccupied - kUnknown);
  std::uint8_t invalid = 0;
  for (const std::int8_t value : cells) {
    const auto shifted = static_cast<std::uint8_t>(static_cast<std::uint8_t>(value) + 1u);
    invalid |= static_cast<std::uint8_t>(shifted > kValidRange);
  }
  return invalid == 0;
}

}  // namespace mrslam
