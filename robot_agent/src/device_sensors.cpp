#include "device_sensors.hpp"

#include <spdlog/spdlog.h>

#include <thread>

#include "mrslam/drivers/device_host_clock.hpp"
#include "mrslam/drivers/log_format.hpp"

namespace mrslam::robot {

namespace {

constexpr std::chrono::milliseconds kPollSlice{100};  // a device poll, and the longest sleep

void restamp(Sample& sample, Stamp stamp) {
  std::visit([stamp](auto& typed) { typed.stamp = stamp; }, sample);
}

}  // namespace

ReplayFeed::ReplayFeed(const std::string& log_path, std::size_t sample_kind)
    : log_(drivers::openLogReader(log_path, drivers::MalformedPolicy::kSkip)), kind_(sample_kind) {}

std::optional<Sample> ReplayFeed::next(const std::function<bool()>& keep_going) {
  std::optional<Sample> sample;
  while ((sample = log_->next()) && sample->index() != kind_) {
  }
  if (!sample) {
    return std::nullopt;
  }
  const Stamp log_stamp = stampOf(*sample);
  if (!anchored_) {
    anchored_ = true;
    host_anchor = drivers::device_clock::hostNow();
    log_anchor = log_stamp;
  }
  const Stamp due{host_anchor.ns + (log_stamp.ns - log_anchor.ns)};
  while (keep_going()) {
    const std::int64_t wait_ns = due.ns - drivers::device_clock::hostNow().ns;
    if (wait_ns <= 0) {
      restamp(*sample, due);
      return sample;
    }
    std::this_thread::sleep_for(
        std::min<std::chrono::nanoseconds>(std::chrono::nanoseconds(wait_ns), kPollSlice));
  }
  return std::nullopt;
}

SensorThread::SensorThread(std::string name, Device device, std::unique_ptr<ReplayFeed> fallback,
                           DeviceSource& sink)
    : device_(std::move(device)), fallback_(std::move(fallback)), sink_(sink) {
  health_.name = std::move(name);
  thread_ = std::thread([this] { run(); });
}

SensorThread::~SensorThread() {
  running_ = false;
  thread_.join();
}

SensorHealth SensorThread::health() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return health_;
}

void SensorThread::run() {
  while (running_) {
    step();
  }
}

void SensorThread::step() {
  std::optional<Sample> sample = device_.poll(kPollSlice);
  {
    const std::string error = device_.error();  // read on this thread, the driver's own
    std::lock_guard<std::mutex> lock(mutex_);
    health_.last_error = error;
  }
  if (sample) {
    if (fallback_) {
      fallback_->pause();
    }
    emit(std::move(*sample), SensorState::kDevice);
    return;
  }
  if (device_.up()) {
    return;  // the device works and had nothing to say in this slice
  }
  if (!fallback_ || fallback_ended_) {
    setState(SensorState::kAbsent);
    return;
  }
  sample = fallback_->next([this] { return running_.load(); });
  if (sample) {
    emit(std::move(*sample), SensorState::kFallback);
  } else if (running_) {
    fallback_ended_ = true;
    spdlog::warn("{}: the replay fallback's log ended", health_.name);
    setState(SensorState::kAbsent);
  }
}

void SensorThread::emit(Sample sample, SensorState from) {
  if (auto* ticks = std::get_if<WheelTicks>(&sample)) {
    // Cumulative counts: the first of a new source continues from the last one handed out.
    if (last_ticks_ && from != ticks_from_) {
      offset_left_ = last_ticks_->left - ticks->left;
      offset_right_ = last_ticks_->right - ticks->right;
    }
    ticks_from_ = from;
    ticks->left += offset_left_;
    ticks->right += offset_right_;
    last_ticks_ = *ticks;
  }
  setState(from);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++(from == SensorState::kDevice ? health_.device_samples : health_.fallback_samples);
  }
  sink_.push(std::move(sample));
}

void SensorThread::setState(SensorState state) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (state == health_.state) {
    return;
  }
  if (health_.state == SensorState::kDevice) {
    ++health_.losses;
  }
  // Logged once per change, not per sample.
  if (state == SensorState::kDevice) {
    spdlog::info("{}: reading its device", health_.name);
  } else if (state == SensorState::kFallback) {
    spdlog::warn("{}: device unavailable ({}); using the replay fallback", health_.name,
                 health_.last_error);
  } else if (state == SensorState::kAbsent) {
    spdlog::warn("{}: device unavailable ({}); running without it", health_.name,
                 health_.last_error);
  }
  health_.state = state;
}

}  // namespace mrslam::robot
