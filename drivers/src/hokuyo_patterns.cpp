// Named range patterns for the Hokuyo emulator (tests, demos).

#include <cmath>
#include <stdexcept>

#include "mrslam/drivers/scip_responder.hpp"

namespace mrslam::drivers {
namespace {

constexpr std::uint32_t kErrorCode = 7;

std::vector<std::uint32_t> rampScan(const scip::ScanGeometry& g) {
  std::vector<std::uint32_t> ranges(static_cast<std::size_t>(g.measuredSteps()));
  const auto span = static_cast<std::uint32_t>(g.dmax_mm - g.dmin_mm);
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    ranges[i] = static_cast<std::uint32_t>(g.dmin_mm) + static_cast<std::uint32_t>(i * 37) % span;
    if (i % 50 == 0) {
      ranges[i] = kErrorCode;
    } else if (i % 61 == 0) {
      ranges[i] = static_cast<std::uint32_t>(g.dmax_mm) + 500;
    }
  }
  return ranges;
}

/// Distance along a ray from (x, y) at `angle` to the walls of the room [−3, 3] × [−2, 2] m.
double distanceToRoomWalls(double x, double y, double angle) {
  const double dx = std::cos(angle);
  const double dy = std::sin(angle);
  double distance = 1e9;
  if (std::abs(dx) > 1e-9) {
    distance = std::min(distance, ((dx > 0 ? 3.0 : -3.0) - x) / dx);
  }
  if (std::abs(dy) > 1e-9) {
    distance = std::min(distance, ((dy > 0 ? 2.0 : -2.0) - y) / dy);
  }
  return distance;
}

std::vector<std::uint32_t> roomScan(const scip::ScanGeometry& g) {
  std::vector<std::uint32_t> ranges(static_cast<std::size_t>(g.measuredSteps()));
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const double angle = g.stepAngleRad(g.amin + static_cast<double>(i));
    const double mm = 1000.0 * distanceToRoomWalls(1.5, 0.0, angle);
    ranges[i] = mm > g.dmax_mm ? static_cast<std::uint32_t>(g.dmax_mm + 1)
                               : static_cast<std::uint32_t>(std::lround(mm));
  }
  return ranges;
}

}  // namespace

RangeSource hokuyoRangePattern(const std::string& name, const HokuyoModel& model) {
  std::vector<std::uint32_t> scan;
  if (name == "ramp") {
    scan = rampScan(model.geometry);
  } else if (name == "room") {
    scan = roomScan(model.geometry);
  } else if (name == "constant") {
    scan.assign(static_cast<std::size_t>(model.geometry.measuredSteps()), 1000);
  } else {
    throw std::invalid_argument("unknown Hokuyo range pattern '" + name +
                                "' (ramp, room, constant)");
  }
  return [scan](std::uint64_t) { return scan; };
}

}  // namespace mrslam::drivers
