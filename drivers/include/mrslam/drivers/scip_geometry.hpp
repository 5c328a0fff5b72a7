#pragma once
// Scan geometry of a Hokuyo ranger, read from its PP reply (never hard-coded), and the
// conversion of raw scan values to a LaserScan.
//
//   angle of step s = (s − AFRT) · 2π / ARES   (counter-clockwise positive, 0 = straight ahead)
//   scan period     = 60 s / SCAN (rpm)
//   raw value v mm:  v < DMIN → error code → LaserScan::kInvalid (0 too, unless the settings say
//                    the firmware uses 0 for "no echo"); v > DMAX → LaserScan::kNoReturn;
//                    otherwise v / 1000 m.
// A cluster of c steps gives one value, placed at the middle step of the cluster.

#include <cstdint>
#include <vector>

#include "mrslam/common/samples.hpp"
#include "mrslam/drivers/scip_protocol.hpp"

namespace mrslam::drivers::scip {

struct ScanGeometry {
  int dmin_mm = 0;   ///< DMIN: smallest valid distance; smaller values are error codes
  int dmax_mm = 0;   ///< DMAX: largest valid distance
  int ares = 0;      ///< ARES: steps in a full turn
  int amin = 0;      ///< AMIN: first measured step
  int amax = 0;      ///< AMAX: last measured step
  int afrt = 0;      ///< AFRT: the step straight ahead
  int scan_rpm = 0;  ///< SCAN: turns per minute

  /// Reads DMIN, DMAX, ARES, AMIN, AMAX, AFRT and SCAN from a PP reply and checks them.
  static Parsed<ScanGeometry> fromParameters(const KeyValues& parameters);

  double stepAngleRad(double step) const;
  double scanPeriodS() const { return 60.0 / scan_rpm; }
  /// Time the mirror takes from one step to the next.
  double stepDurationS() const { return scanPeriodS() / ares; }
  /// Steps AMIN … AMAX.
  int measuredSteps() const { return amax - amin + 1; }
};

/// What a raw value of 0 means (firmware dependent; *unsure*, hence a setting).
enum class ZeroRange {
  kInvalid,   ///< an error code like the others below DMIN (safe: says nothing)
  kNoReturn,  ///< "no echo": free space up to the maximum range
};

/// One raw value in metres, kInvalid or kNoReturn (see the header comment).
float rangeToMetres(std::uint32_t value_mm, const ScanGeometry& geometry, ZeroRange zero);

/// A LaserScan (angles, limits, ranges; no stamp) from the raw values of `request`.
LaserScan toLaserScan(const std::vector<std::uint32_t>& ranges_mm, const ScanGeometry& geometry,
                      const ScanRequest& request, ZeroRange zero);

}  // namespace mrslam::drivers::scip
