#pragma once
// The robot's own devices as one sample source: the Hokuyo laser, the 3DM-GX1 IMU and the Phidget
// encoders, each read by its driver on a thread of its own. A device that is absent at start or
// lost while running is logged once; its sensor then takes its samples from the configured replay
// log (fallback: replay, re-stamped to the host clock and paced in real time) or goes without
// (fallback: none); when the device is back it is used again. Samples are handed out in the
// order they arrive (the EKF orders late ones). The source ends when shutdown is requested.

#include <atomic>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "mrslam/drivers/gx1_driver.hpp"
#include "mrslam/drivers/hokuyo_driver.hpp"
#include "mrslam/drivers/phidget_encoders.hpp"
#include "mrslam/drivers/sample_source.hpp"

namespace mrslam::robot {

enum class DeviceFallback { kNone, kReplay };

struct DeviceSourceSettings {
  std::optional<drivers::HokuyoSettings> laser;             ///< absent: no laser
  std::optional<drivers::Gx1Settings> imu;                  ///< absent: no IMU
  std::optional<drivers::PhidgetEncoderSettings> encoders;  ///< absent: no encoders
  DeviceFallback laser_fallback = DeviceFallback::kReplay;
  DeviceFallback imu_fallback = DeviceFallback::kReplay;
  DeviceFallback encoders_fallback = DeviceFallback::kReplay;
  std::string replay_log;        ///< the fallback's log (any format replay reads); empty: no replay
  double reopen_period_s = 2.0;  ///< how often an absent Phidget library/device is tried again
  /// Samples are held this long (host clock) and handed out in time-stamp order: a sample from
  /// one device that arrives after a later-stamped one from another is still in order.
  double reorder_window_s = 0.05;
};

/// Where a sensor's samples come from now.
enum class SensorState {
  kStarting,  ///< no sample yet
  kDevice,    ///< its device
  kFallback,  ///< the replay log (the device is absent or lost)
  kAbsent,    ///< nothing (no device, no fallback, or the fallback log ended)
};
const char* sensorStateName(SensorState state);

struct SensorHealth {
  std::string name;  ///< laser, imu, encoders
  SensorState state = SensorState::kStarting;
  std::uint64_t device_samples = 0;
  std::uint64_t fallback_samples = 0;
  std::uint64_t losses = 0;  ///< times the device went away while the agent ran
  std::string last_error;    ///< the device's latest problem (empty if none)
};

class SensorThread;

class DeviceSource final : public drivers::SampleSource {
 public:
  /// Starts one thread per configured sensor. `shutdown` ends the stream (next() → nothing).
  DeviceSource(const DeviceSourceSettings& settings, const std::atomic<bool>& shutdown);
  ~DeviceSource() override;
  DeviceSource(const DeviceSource&) = delete;
  DeviceSource& operator=(const DeviceSource&) = delete;

  std::optional<Sample> next() override;
  std::string describe() const override;
  drivers::SourceCounters counters() const override;
  std::vector<drivers::SensorStatus> sensors() const override;

  std::vector<SensorHealth> health() const;
  /// Samples dropped because the pipeline fell 4096 samples behind (oldest first).
  std::uint64_t droppedSamples() const;
  /// Samples stamped before one already handed out (they arrived later than the reorder window).
  std::uint64_t outOfOrderSamples() const;

  /// A sample from a sensor thread (thread-safe).
  void push(Sample sample);

 private:
  const std::atomic<bool>& shutdown_;
  std::vector<std::unique_ptr<SensorThread>> sensors_;
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::deque<Sample> queue_;  ///< in time-stamp order
  std::int64_t reorder_window_ns_ = 0;
  std::uint64_t handed_out_ = 0;
  std::uint64_t out_of_order_ = 0;
  std::optional<Stamp> last_handed_out_;
  std::uint64_t dropped_ = 0;
};

}  // namespace mrslam::robot
