// Loading HokuyoSettings from a config section.

#include <string>
#include <vector>

#include "mrslam/drivers/hokuyo_driver.hpp"

namespace mrslam::drivers {
namespace {

std::chrono::milliseconds secondsSetting(const Config& section, const std::string& key,
                                         std::chrono::milliseconds default_value, Range range) {
  const double seconds = section.getDouble(key, default_value.count() * 1e-3, range);
  return std::chrono::milliseconds(static_cast<long long>(seconds * 1e3 + 0.5));
}

}  // namespace

HokuyoSettings loadHokuyoSettings(const Config& section) {
  HokuyoSettings s;
  s.device = section.requirePath("device");
  s.baud = static_cast<int>(section.getInt("baud", s.baud, {1200, 1e7}));
  std::vector<double> default_bauds(s.probe_bauds.begin(), s.probe_bauds.end());
  s.probe_bauds.clear();
  for (const double baud : section.getDoubles("probe_bauds", default_bauds, 0, {1200, 1e7})) {
    s.probe_bauds.push_back(static_cast<int>(baud));
  }
  s.start_step = static_cast<int>(section.getInt("start_step", s.start_step, {-1, 9999}));
  s.end_step = static_cast<int>(section.getInt("end_step", s.end_step, {-1, 9999}));
  s.cluster = static_cast<int>(section.getInt("cluster", s.cluster, {1, 99}));
  s.skip_scans = static_cast<int>(section.getInt("skip_scans", s.skip_scans, {0, 9}));
  s.read_timeout = secondsSetting(section, "read_timeout_s", s.read_timeout, {0.01, 60.0});
  s.stall_scan_periods =
      static_cast<int>(section.getInt("stall_scan_periods", s.stall_scan_periods, {1, 1000}));
  s.reconnect_backoff_min =
      secondsSetting(section, "reconnect_backoff_min_s", s.reconnect_backoff_min, {0.001, 60.0});
  s.reconnect_backoff_max =
      secondsSetting(section, "reconnect_backoff_max_s", s.reconnect_backoff_max, {0.001, 600.0});
  if (s.reconnect_backoff_max < s.reconnect_backoff_min) {
    section.fail("reconnect_backoff_max_s", "must not be below reconnect_backoff_min_s");
  }
  s.time_sync_round_trips =
      static_cast<int>(section.getInt("time_sync_round_trips", s.time_sync_round_trips, {0, 100}));
  const std::string zero = section.getChoice("zero_range", "invalid", {"invalid", "no_return"});
  s.zero_range = zero == "no_return" ? scip::ZeroRange::kNoReturn : scip::ZeroRange::kInvalid;
  s.reset_on_stop = section.getBool("reset_on_stop", s.reset_on_stop);
  return s;
}

}  // namespace mrslam::drivers
