#pragma once
// Shared by the Hokuyo driver tests: quick settings, the scan a pattern must give, and polling.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "mrslam/drivers/hokuyo_driver.hpp"
#include "mrslam/drivers/hokuyo_emulator.hpp"
#include "test_data.hpp"

namespace mrslam::drivers::test {

using namespace std::chrono_literals;

/// Settings with short time-outs so failures show quickly (upper bounds only).
inline HokuyoSettings quickSettings(const std::string& device) {
  HokuyoSettings settings;
  settings.device = device;
  settings.read_timeout = 300ms;
  settings.reconnect_backoff_min = 20ms;
  settings.reconnect_backoff_max = 200ms;
  settings.stall_scan_periods = 3;
  settings.time_sync_round_trips = 3;
  return settings;
}

/// A stable link path for an emulated device of this test.
inline std::string linkPath() {
  return (mrslam::test::scratchFolder("hokuyo") / "ttyACM-hokuyo").string();
}

/// The ranges a driver must give for raw values (written out here, not taken from the driver):
/// below DMIN → NaN, above DMAX → +inf, else metres.
inline std::vector<float> expectedRanges(const std::vector<std::uint32_t>& raw_mm,
                                         const scip::ScanGeometry& geometry) {
  std::vector<float> ranges;
  for (const std::uint32_t mm : raw_mm) {
    if (mm < static_cast<std::uint32_t>(geometry.dmin_mm)) {
      ranges.push_back(std::nanf(""));
    } else if (mm > static_cast<std::uint32_t>(geometry.dmax_mm)) {
      ranges.push_back(INFINITY);
    } else {
      ranges.push_back(static_cast<float>(mm) / 1000.0f);
    }
  }
  return ranges;
}

/// Equal element by element, NaN matching NaN.
inline bool sameRanges(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) {
    return false;
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))) {
      return false;
    }
  }
  return true;
}

/// Polls until `count` scans came or `max_polls` polls of 200 ms passed.
inline std::vector<LaserScan> collectScans(HokuyoDriver& driver, std::size_t count,
                                           int max_polls = 50) {
  std::vector<LaserScan> scans;
  for (int poll = 0; poll < max_polls && scans.size() < count; ++poll) {
    if (auto scan = driver.poll(200ms)) {
      scans.push_back(std::move(*scan));
    }
  }
  return scans;
}

/// Every scan carries exactly `expected`; counts those that do not.
inline int scansDifferingFrom(const std::vector<LaserScan>& scans,
                              const std::vector<float>& expected) {
  int differing = 0;
  for (const LaserScan& scan : scans) {
    differing += sameRanges(scan.ranges_m, expected) ? 0 : 1;
  }
  return differing;
}

/// Stamps strictly increase and each step is a whole number of scan periods (±2 ms: the
/// sensor's stamps are whole milliseconds).
inline void expectStampsFollowTheSensorClock(const std::vector<LaserScan>& scans, double period_s) {
  for (std::size_t i = 1; i < scans.size(); ++i) {
    const double step_s = secondsBetween(scans[i - 1].stamp, scans[i].stamp);
    EXPECT_GT(step_s, 0.0) << "scan " << i;
    const double periods = step_s / period_s;
    EXPECT_NEAR(periods, std::round(periods), 0.002 / period_s) << "scan " << i;
    EXPECT_GE(std::round(periods), 1.0) << "scan " << i;
  }
}

}  // namespace mrslam::drivers::test
