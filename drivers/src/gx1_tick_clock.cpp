// Host time stamps from the 3DM-GX1's 16-bit timer ticks (method in gx1_driver.hpp).

#include <algorithm>
#include <cmath>

#include "mrslam/drivers/gx1_driver.hpp"

namespace mrslam::drivers {

namespace {

constexpr double kTicksPerWrap = 65536.0;
constexpr int kResyncAfterFrames = 8;  // frames in a row lagging more than max_error_s

}  // namespace

void TickClock::reset() {
  started_ = false;
  unwrapped_ = 0;
  lagging_frames_ = 0;
}

std::uint64_t TickClock::unwrap(std::uint16_t ticks, Stamp host) const {
  const auto delta = static_cast<std::uint16_t>(ticks - last_ticks_);
  // Whole wraps the host clock says passed beyond `delta` (frames over ~7 minutes apart).
  const double elapsed_ticks = secondsBetween(last_host_, host) / settings_.tick_period_s;
  const double wraps = std::round((elapsed_ticks - static_cast<double>(delta)) / kTicksPerWrap);
  const std::uint64_t extra = wraps > 0.0 ? static_cast<std::uint64_t>(wraps) * 65536u : 0u;
  return unwrapped_ + delta + extra;
}

Stamp TickClock::stamp(std::uint16_t ticks, Stamp host) {
  if (!started_) {
    started_ = true;
    first_unwrapped_ = ticks;
    unwrapped_ = ticks;
    last_ticks_ = ticks;
    last_host_ = host;
    offset_ns_ = host.ns;  // device time is counted from this first frame
    last_stamp_ = std::max(host, Stamp{last_stamp_.ns + 1});
    return last_stamp_;
  }
  const std::uint64_t next = unwrap(ticks, host);
  const double period_ns = settings_.tick_period_s * 1e9;
  const auto step_ns = static_cast<double>(next - unwrapped_) * period_ns;
  unwrapped_ = next;
  last_ticks_ = ticks;
  last_host_ = host;

  const auto device_ns = static_cast<std::int64_t>(
      std::llround(static_cast<double>(next - first_unwrapped_) * period_ns));
  const std::int64_t candidate = host.ns - device_ns;
  const bool lagging = static_cast<double>(candidate - offset_ns_) > settings_.max_error_s * 1e9;
  lagging_frames_ = lagging ? lagging_frames_ + 1 : 0;
  lagging_min_ns_ = lagging_frames_ == 1 ? candidate : std::min(lagging_min_ns_, candidate);
  if (candidate < offset_ns_) {
    offset_ns_ = candidate;  // a less delayed frame
  } else if (lagging_frames_ >= kResyncAfterFrames) {
    // Even the least delayed of these frames lags: the clocks disagree (wrong tick period,
    // device reset). Start again from the least delayed one.
    offset_ns_ = lagging_min_ns_;
    lagging_frames_ = 0;
    ++resyncs_;
  } else {
    const auto drift_ns =
        static_cast<std::int64_t>(std::llround(settings_.drift_allowance * step_ns));
    offset_ns_ = std::min(candidate, offset_ns_ + drift_ns);
  }
  const std::int64_t aligned = std::min(device_ns + offset_ns_, host.ns);
  last_stamp_ = Stamp{std::max(aligned, last_stamp_.ns + 1)};
  return last_stamp_;
}

}  // namespace mrslam::drivers
