#include "mrslam/robot/device_source.hpp"

#include <spdlog/spdlog.h>

#include "device_sensors.hpp"
#include "mrslam/drivers/device_host_clock.hpp"

namespace mrslam::robot {

namespace {

constexpr std::chrono::milliseconds kWaitSlice{100};  // next(): how often shutdown is looked at
constexpr std::size_t kMaxQueued = 4096;  // a pipeline this far behind: the oldest are dropped

constexpr std::size_t kLaserKind = 0;  // index in the Sample variant
constexpr std::size_t kTicksKind = 1;
constexpr std::size_t kImuKind = 3;
static_assert(std::is_same_v<std::variant_alternative_t<kLaserKind, Sample>, LaserScan>);
static_assert(std::is_same_v<std::variant_alternative_t<kTicksKind, Sample>, WheelTicks>);
static_assert(std::is_same_v<std::variant_alternative_t<kImuKind, Sample>, ImuSample>);

std::unique_ptr<ReplayFeed> fallbackOf(const DeviceSourceSettings& settings,
                                       DeviceFallback fallback, std::size_t kind) {
  if (fallback == DeviceFallback::kNone || settings.replay_log.empty()) {
    return nullptr;
  }
  return std::make_unique<ReplayFeed>(settings.replay_log, kind);
}

SensorThread::Device laserDevice(const drivers::HokuyoSettings& settings) {
  auto driver = std::make_shared<drivers::HokuyoDriver>(settings);
  return {[driver](std::chrono::milliseconds timeout) -> std::optional<Sample> {
            if (auto scan = driver->poll(timeout)) {
              return Sample(std::move(*scan));
            }
            return std::nullopt;
          },
          [driver] { return driver->health().state == drivers::HokuyoState::kConnected; },
          [driver] { return driver->health().last_error; }};
}

SensorThread::Device imuDevice(const drivers::Gx1Settings& settings) {
  auto driver = std::make_shared<drivers::Gx1Driver>(settings);
  return {[driver](std::chrono::milliseconds timeout) -> std::optional<Sample> {
            if (auto sample = driver->poll(timeout)) {
              return Sample(*sample);
            }
            return std::nullopt;
          },
          [driver] { return driver->state() == drivers::Gx1State::kRunning; },
          [driver] { return driver->health().last_error; }};
}

// The Phidget library or device may be missing: opened again every reopen_period_s.
struct EncoderLink {
  drivers::PhidgetEncoderSettings settings;
  double reopen_period_s = 2.0;
  std::unique_ptr<drivers::PhidgetEncoders> encoders;
  std::chrono::steady_clock::time_point next_open{};
  std::string error;

  std::optional<Sample> poll(std::chrono::milliseconds timeout) {
    const auto now = std::chrono::steady_clock::now();
    if (!encoders && now >= next_open) {
      auto opened = drivers::PhidgetEncoders::open(settings);
      if (opened) {
        encoders = std::move(opened.value());
        error.clear();
      } else {
        error = opened.reason();
        next_open = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(reopen_period_s));
      }
    }
    if (!encoders) {
      return std::nullopt;  // no waiting here: the fallback (if any) paces itself
    }
    const auto deadline = now + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      if (auto ticks = encoders->poll()) {
        return Sample(*ticks);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return std::nullopt;
  }
};

SensorThread::Device encoderDevice(const drivers::PhidgetEncoderSettings& settings,
                                   double reopen_period_s) {
  auto link = std::make_shared<EncoderLink>();
  link->settings = settings;
  link->reopen_period_s = reopen_period_s;
  return {[link](std::chrono::milliseconds timeout) { return link->poll(timeout); },
          [link] { return link->encoders != nullptr; }, [link] { return link->error; }};
}

}  // namespace

const char* sensorStateName(SensorState state) {
  switch (state) {
    case SensorState::kStarting:
      return "starting";
    case SensorState::kDevice:
      return "device";
    case SensorState::kFallback:
      return "fallback";
    case SensorState::kAbsent:
      return "absent";
  }
  return "unknown";
}

DeviceSource::DeviceSource(const DeviceSourceSettings& settings, const std::atomic<bool>& shutdown)
    : shutdown_(shutdown),
      reorder_window_ns_(static_cast<std::int64_t>(std::llround(settings.reorder_window_s * 1e9))) {
  if (settings.laser) {
    sensors_.push_back(std::make_unique<SensorThread>(
        "laser", laserDevice(*settings.laser),
        fallbackOf(settings, settings.laser_fallback, kLaserKind), *this));
  }
  if (settings.imu) {
    sensors_.push_back(std::make_unique<SensorThread>(
        "imu", imuDevice(*settings.imu), fallbackOf(settings, settings.imu_fallback, kImuKind),
        *this));
  }
  if (settings.encoders) {
    sensors_.push_back(std::make_unique<SensorThread>(
        "encoders", encoderDevice(*settings.encoders, settings.reopen_period_s),
        fallbackOf(settings, settings.encoders_fallback, kTicksKind), *this));
  }
  if (sensors_.empty()) {
    throw std::invalid_argument("source.devices: no device is configured");
  }
}

DeviceSource::~DeviceSource() {
  sensors_.clear();  // joins the threads before the queue goes away
  spdlog::info(
      "devices: {} samples handed out, {} of them later than the {} s reorder window, {} "
      "dropped by a full queue",
      handed_out_, out_of_order_, reorder_window_ns_ * 1e-9, dropped_);
}

void DeviceSource::push(Sample sample) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (queue_.size() >= kMaxQueued) {
      queue_.pop_front();
      if (dropped_++ % 1000 == 0) {
        spdlog::warn("devices: the pipeline falls behind; {} samples dropped so far", dropped_);
      }
    }
    // Mostly in order already: look for its place from the back.
    const Stamp stamp = stampOf(sample);
    auto place = queue_.end();
    while (place != queue_.begin() && stamp < stampOf(*std::prev(place))) {
      --place;
    }
    queue_.insert(place, std::move(sample));
  }
  arrived_.notify_one();
}

std::optional<Sample> DeviceSource::next() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!shutdown_.load()) {
    if (!queue_.empty()) {
      // The oldest sample leaves once the window has passed over it: anything stamped earlier
      // that is still on its way would be later than the window.
      const std::int64_t due_ns = stampOf(queue_.front()).ns + reorder_window_ns_;
      const std::int64_t wait_ns = due_ns - drivers::device_clock::hostNow().ns;
      if (wait_ns <= 0) {
        Sample sample = std::move(queue_.front());
        queue_.pop_front();
        const Stamp stamp = stampOf(sample);
        if (last_handed_out_ && stamp < *last_handed_out_) {
          ++out_of_order_;
        }
        last_handed_out_ = std::max(stamp, last_handed_out_.value_or(stamp));
        ++handed_out_;
        return sample;
      }
      arrived_.wait_for(
          lock, std::min<std::chrono::nanoseconds>(std::chrono::nanoseconds(wait_ns), kWaitSlice));
      continue;
    }
    arrived_.wait_for(lock, kWaitSlice, [this] { return !queue_.empty(); });
  }
  return std::nullopt;
}

std::uint64_t DeviceSource::outOfOrderSamples() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return out_of_order_;
}

std::string DeviceSource::describe() const {
  std::string names;
  for (const SensorHealth& sensor : health()) {
    names += (names.empty() ? "" : ", ") + sensor.name;
  }
  return "devices (" + names + ")";
}

drivers::SourceCounters DeviceSource::counters() const {
  drivers::SourceCounters counters;
  std::lock_guard<std::mutex> lock(mutex_);
  counters.samples = handed_out_;
  return counters;
}

std::vector<drivers::SensorStatus> DeviceSource::sensors() const {
  std::vector<drivers::SensorStatus> sensors;
  for (const SensorHealth& sensor : health()) {
    sensors.push_back({sensor.name, sensorStateName(sensor.state),
                       sensor.state == SensorState::kDevice,
                       sensor.device_samples + sensor.fallback_samples, sensor.losses});
  }
  return sensors;
}

std::uint64_t DeviceSource::droppedSamples() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return dropped_;
}

std::vector<SensorHealth> DeviceSource::health() const {
  std::vector<SensorHealth> health;
  for (const auto& sensor : sensors_) {
    health.push_back(sensor->health());
  }
  return health;
}

}  // namespace mrslam::robot
