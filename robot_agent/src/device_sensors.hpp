#pragma once
// Private to DeviceSource: one thread per sensor that reads its device and, while the device is
// away, its replay fallback.

#include <chrono>
#include <functional>
#include <memory>
#include <optional>

#include "mrslam/robot/device_source.hpp"

namespace mrslam::robot {

/// Samples of one kind from a log, re-stamped to the host clock and paced in real time: the
/// sample after a pause is due at once, the ones after it keep the log's spacing.
class ReplayFeed {
 public:
  ReplayFeed(const std::string& log_path, std::size_t sample_kind);
  /// The next sample of the kind once it is due (waits in short steps while `keep_going`);
  /// nothing at the end of the log or when `keep_going` turns false.
  std::optional<Sample> next(const std::function<bool()>& keep_going);
  /// The feed was not used for a while: its next sample is due at once.
  void pause() { anchored_ = false; }

 private:
  std::unique_ptr<drivers::SampleSource> log_;
  std::size_t kind_;
  bool anchored_ = false;
  Stamp host_anchor;  ///< host time of the anchor sample
  Stamp log_anchor;   ///< its log time
};

/// A sensor: its device behind `poll_device` (nothing when no sample came in the time given),
/// `device_up` (the driver has a working device) and `device_error`; the optional fallback.
class SensorThread {
 public:
  struct Device {
    std::function<std::optional<Sample>(std::chrono::milliseconds)> poll;
    std::function<bool()> up;
    std::function<std::string()> error;
  };

  SensorThread(std::string name, Device device, std::unique_ptr<ReplayFeed> fallback,
               DeviceSource& sink);
  ~SensorThread();
  SensorThread(const SensorThread&) = delete;
  SensorThread& operator=(const SensorThread&) = delete;

  SensorHealth health() const;

 private:
  void run();
  void step();
  void emit(Sample sample, SensorState from);
  void setState(SensorState state);

  Device device_;
  std::unique_ptr<ReplayFeed> fallback_;
  DeviceSource& sink_;
  std::atomic<bool> running_{true};
  mutable std::mutex mutex_;
  SensorHealth health_;
  bool fallback_ended_ = false;
  std::optional<WheelTicks> last_ticks_;  ///< encoder counts continue across a switch of source
  SensorState ticks_from_ = SensorState::kStarting;
  std::int64_t offset_left_ = 0;
  std::int64_t offset_right_ = 0;
  std::thread thread_;
};

}  // namespace mrslam::robot
