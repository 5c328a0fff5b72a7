#include "mrslam/drivers/sensor_clock.hpp"

#include <algorithm>

namespace mrslam::drivers {
namespace {

constexpr std::int64_t kNsPerMs = 1'000'000;
constexpr std::int64_t kMinStampStepNs = 1'000;

}  // namespace

void SensorClock::reset() {
  unwrapped_ms_.reset();
  offset_ns_.reset();
  best_round_trip_ns_.reset();
  latency_ns_.reset();
  learning_scans_left_ = 0;
  last_host_.reset();
}

std::int64_t SensorClock::unwrap(std::uint32_t raw_ms) {
  raw_ms %= kCounterModulus;
  if (!unwrapped_ms_) {
    unwrapped_ms_ = raw_ms;
  } else {
    const std::uint32_t advance = (raw_ms - last_raw_ms_) % kCounterModulus;
    if (advance < kCounterModulus / 2) {
      *unwrapped_ms_ += advance;
    } else {
      *unwrapped_ms_ -= static_cast<std::int64_t>(kCounterModulus - advance);
    }
  }
  last_raw_ms_ = raw_ms;
  return *unwrapped_ms_;
}

void SensorClock::addRoundTrip(std::uint32_t raw_ms, Stamp host_send, Stamp host_receive) {
  const std::int64_t sensor_ns = unwrap(raw_ms) * kNsPerMs;
  const std::int64_t round_trip_ns = host_receive.ns - host_send.ns;
  if (round_trip_ns < 0 || (best_round_trip_ns_ && round_trip_ns >= *best_round_trip_ns_)) {
    return;
  }
  best_round_trip_ns_ = round_trip_ns;
  offset_ns_ = host_send.ns + round_trip_ns / 2 - sensor_ns;
  latency_ns_.reset();
  learning_scans_left_ = settings_.latency_learning_scans;
  last_host_ = host_receive;
}

void SensorClock::updateOffset(std::int64_t bound_ns, Stamp host_receive) {
  if (!offset_ns_) {  // no round trip: the first scan starts the filter, no latency known
    offset_ns_ = bound_ns;
    latency_ns_ = 0;
  } else if (learning_scans_left_ > 0) {  // after a round trip: learn the scan latency first
    --learning_scans_left_;
    const std::int64_t latency = bound_ns - *offset_ns_;
    latency_ns_ = latency_ns_ ? std::min(*latency_ns_, latency) : latency;
  } else {
    const double host_step_ns =
        last_host_
            ? static_cast<double>(std::max<std::int64_t>(0, host_receive.ns - last_host_->ns))
            : 0.0;
    const auto allowed_growth = static_cast<std::int64_t>(settings_.max_drift * host_step_ns);
    offset_ns_ = std::min(*offset_ns_ + allowed_growth, bound_ns - latency_ns_.value_or(0));
  }
  last_host_ = host_receive;
}

Stamp SensorClock::stampScan(std::uint32_t raw_ms, Stamp host_receive, std::int64_t first_beam_ns,
                             std::int64_t last_beam_ns) {
  const std::int64_t sensor_ns = unwrap(raw_ms) * kNsPerMs;
  updateOffset(host_receive.ns - (sensor_ns + last_beam_ns), host_receive);
  Stamp stamp{sensor_ns + first_beam_ns + *offset_ns_};
  if (last_stamp_ && stamp.ns < last_stamp_->ns + kMinStampStepNs) {
    stamp.ns = last_stamp_->ns + kMinStampStepNs;
  }
  last_stamp_ = stamp;
  return stamp;
}

}  // namespace mrslam::drivers
