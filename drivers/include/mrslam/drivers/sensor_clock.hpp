#pragma once
// Host time stamps for a sensor that stamps its data with its own 24-bit millisecond counter
// (Hokuyo SCIP: the counter at step 0 of each scan, wrapping every 2^24 ms ≈ 4.66 h).
//
// Method:
//  1. Unwrap: each raw value advances the sensor time by (raw − previous raw) mod 2^24 ms; an
//     advance above 2^23 ms is a step back (a stale or reset counter) and is taken as one.
//  2. Offset = host − sensor. Every message gives an upper bound: the host receives it after the
//     sensor stamped it, so host_receive − sensor_time − (known delays) ≥ offset; transfer and
//     scheduling only add to it. Hence:
//     a. start: TM round trips (time-sync mode) give offset ≈ (send + receive) / 2 − sensor, the
//        round trip of the shortest duration kept (error ≤ its half);
//     b. the first `latency_learning_scans` scans learn the fixed part of the scan latency
//        L = min(bound − offset) (the transfer time of a scan: ~1 ms on USB, up to ~200 ms on a
//        115200 baud line), the offset staying at the TM value;
//     c. then every scan updates the offset by a one-sided minimum filter that may grow only at
//        the clock drift rate: offset = min(offset + max_drift · Δt_host, bound − L).
//     Without TM the first scan's bound starts the filter with L = 0: stamps then lag by the
//     smallest transfer time of a scan (a constant bias).
//  3. Monotonic: a stamp is never earlier than 1 µs after the one before, across reset() too.

#include <cstdint>
#include <optional>

#include "mrslam/common/stamp.hpp"

namespace mrslam::drivers {

struct SensorClockSettings {
  double max_drift = 1e-4;          ///< largest relative rate error of the two clocks (100 ppm)
  int latency_learning_scans = 20;  ///< scans that learn the fixed scan latency after a TM sync
};

class SensorClock {
 public:
  using Settings = SensorClockSettings;
  static constexpr std::uint32_t kCounterModulus = 1u << 24;

  explicit SensorClock(Settings settings = {}) : settings_(settings) {}

  /// A new session (the sensor may have restarted its counter): forgets the unwrapping and the
  /// offset; keeps the monotonic floor.
  void reset();

  /// A time-sync round trip: the sensor answered `raw_ms` between host_send and host_receive.
  void addRoundTrip(std::uint32_t raw_ms, Stamp host_send, Stamp host_receive);

  /// The host stamp of a scan whose counter read `raw_ms` at step 0, received at host_receive.
  /// `first_beam_ns`: from step 0 to the first beam (the stamp returned is that beam's time);
  /// `last_beam_ns`: from step 0 to the last beam (after which the scan is sent).
  Stamp stampScan(std::uint32_t raw_ms, Stamp host_receive, std::int64_t first_beam_ns,
                  std::int64_t last_beam_ns);

  /// The unwrapped sensor time of the last raw value, in ms since the session's first one
  /// (plus that first raw value).
  std::int64_t sensorTimeMs() const { return unwrapped_ms_.value_or(0); }
  /// host − sensor in ns, once known.
  std::optional<std::int64_t> offsetNs() const { return offset_ns_; }
  bool synchronisedByRoundTrip() const { return best_round_trip_ns_.has_value(); }

 private:
  std::int64_t unwrap(std::uint32_t raw_ms);
  void updateOffset(std::int64_t bound_ns, Stamp host_receive);

  Settings settings_;
  std::optional<std::int64_t> unwrapped_ms_;
  std::uint32_t last_raw_ms_ = 0;
  std::optional<std::int64_t> offset_ns_;
  std::optional<std::int64_t> best_round_trip_ns_;
  std::optional<std::int64_t> latency_ns_;
  int learning_scans_left_ = 0;
  std::optional<Stamp> last_host_;
  std::optional<Stamp> last_stamp_;
};

}  // namespace mrslam::drivers
