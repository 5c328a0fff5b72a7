#include "mrslam/drivers/emulated_robot.hpp"

#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "mrslam/drivers/device_host_clock.hpp"
#include "mrslam/drivers/gx1_emulator.hpp"
#include "mrslam/drivers/hokuyo_emulator.hpp"

namespace mrslam::drivers {

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kDefaultScanRateHz = 10.0;  // when the source's first two scans do not tell
constexpr std::chrono::milliseconds kStopCheck{50};
constexpr int kBoardInputs = 4;

// What the devices' threads read: the latest scan and IMU state, under a lock.
struct LatestReadings {
  std::mutex mutex;
  std::vector<std::uint32_t> raw_ranges;
  gx1::DeviceState imu;
};

// Wheel travel of a pose change (for logs with odometry poses instead of ticks).
class TicksFromPoses {
 public:
  explicit TicksFromPoses(const DiffDriveParams& drive) : drive_(drive) {}
  std::pair<std::int64_t, std::int64_t> add(const SE2& T_odom_robot) {
    if (previous_) {
      const SE2 step = previous_->inverse() * T_odom_robot;
      const double half_turn_m = 0.5 * step.theta() * drive_.track_width_m;
      const double counts_per_m =
          drive_.ticks_per_revolution / (2.0 * M_PI * drive_.wheel_radius_m);
      left_ += (step.x() - half_turn_m) * counts_per_m;
      right_ += (step.x() + half_turn_m) * counts_per_m;
    }
    previous_ = T_odom_robot;
    return {std::llround(left_), std::llround(right_)};
  }

 private:
  DiffDriveParams drive_;
  std::optional<SE2> previous_;
  double left_ = 0.0;
  double right_ = 0.0;
};

}  // namespace

struct EmulatedRobot::Devices {
  HokuyoModel model;
  std::shared_ptr<LatestReadings> latest = std::make_shared<LatestReadings>();
  std::unique_ptr<HokuyoEmulator> laser;
  std::unique_ptr<Gx1Emulator> imu;
  std::unique_ptr<PhidgetFeedWriter> feed;
  TicksFromPoses ticks_from_poses;
  std::vector<std::int64_t> board_counts = std::vector<std::int64_t>(kBoardInputs, 0);

  explicit Devices(const DiffDriveParams& drive) : ticks_from_poses(drive) {}
};

EmulatedRobot::EmulatedRobot(std::unique_ptr<SampleSource> source, EmulatedDevices devices,
                             EmulatedRobotSettings settings)
    : source_(std::move(source)), devices_(std::move(devices)), settings_(settings) {
  if (!source_) {
    throw std::invalid_argument("emulated robot: no source");
  }
  for (const int channel : {devices_.left_channel, devices_.right_channel}) {
    if (channel < 0 || channel >= kBoardInputs) {
      throw std::invalid_argument("emulated robot: encoder channel " + std::to_string(channel) +
                                  " is not an input of the board (0…3)");
    }
  }
  if (!(settings_.speed > 0.0)) {
    throw std::invalid_argument("emulated robot: speed must be positive");
  }
}

EmulatedRobot::~EmulatedRobot() = default;

const HokuyoModel& EmulatedRobot::laserModel() const {
  if (!live_) {
    throw std::logic_error("emulated robot: laserModel() before start()");
  }
  return live_->model;
}

void EmulatedRobot::start() {
  // The laser's model comes from the source's scans: read up to the second (its rate).
  std::size_t scans_read = 0;
  while (scans_read < 2) {
    std::optional<Sample> sample = source_->next();
    if (!sample) {
      break;
    }
    scans_read += std::holds_alternative<LaserScan>(*sample) ? 1 : 0;
    pending_.push_back(std::move(*sample));
  }
  std::vector<const LaserScan*> scans;
  for (const Sample& sample : pending_) {
    if (const auto* scan = std::get_if<LaserScan>(&sample)) {
      scans.push_back(scan);
    }
  }
  live_ = std::make_unique<Devices>(settings_.drive);
  if (!devices_.laser_path.empty()) {
    if (scans.empty()) {
      throw std::runtime_error("emulated robot: " + source_->describe() + " has no laser scans");
    }
    double rate_hz = kDefaultScanRateHz;
    if (scans.size() == 2) {
      const double period_s = (scans[1]->stamp.ns - scans[0]->stamp.ns) * 1e-9;
      rate_hz = period_s > 0.0 ? 1.0 / period_s : kDefaultScanRateHz;
    }
    Result<HokuyoModel> model = hokuyoModelFor(*scans.front(), rate_hz);
    if (!model) {
      throw std::runtime_error("emulated robot: the laser: " + model.reason());
    }
    live_->model = model.value();
    live_->latest->raw_ranges = rawRangesOf(*scans.front(), live_->model);
    HokuyoEmulatorSettings laser;
    laser.model = live_->model;
    std::weak_ptr<LatestReadings> latest = live_->latest;
    laser.ranges = [latest](std::uint64_t) {
      const auto readings = latest.lock();
      if (!readings) {
        return std::vector<std::uint32_t>{};
      }
      std::lock_guard<std::mutex> lock(readings->mutex);
      return readings->raw_ranges;
    };
    live_->laser = std::make_unique<HokuyoEmulator>(laser, devices_.laser_path);
    live_->laser->start();
  }
  // The IMU and the encoders appear when the source has their samples (a CARMEN log has no
  // IMU): an agent then runs without them, as with a robot that lacks the device.
  for (const Sample& sample : pending_) {
    if (const auto* imu = std::get_if<ImuSample>(&sample)) {
      bringUpImu(*imu);
    } else if (!std::holds_alternative<LaserScan>(sample)) {
      bringUpEncoders();
    }
  }
}

void EmulatedRobot::bringUpImu(const ImuSample& first) {
  if (devices_.imu_path.empty() || live_->imu) {
    return;
  }
  {
    std::lock_guard<std::mutex> lock(live_->latest->mutex);
    live_->latest->imu = gx1StateOf(first, devices_.imu_z_down);
  }
  Gx1EmulatorSettings imu;
  imu.link_path = devices_.imu_path;
  // Frames every two timer ticks, the timer stepping two ticks a frame: the device's time stamps
  // then space its frames as they are sent. (A 10 ms interval against 6.5536 ms ticks stamped
  // frames one or two ticks apart, ±35 % of the true spacing, which the yaw rate took for bias.)
  imu.ticks_per_frame = 2;
  imu.continuous_interval = std::chrono::microseconds(std::llround(2.0 * imu.tick_period_s * 1e6));
  std::weak_ptr<LatestReadings> latest = live_->latest;
  live_->imu = std::make_unique<Gx1Emulator>(imu, [latest] {
    const auto readings = latest.lock();
    if (!readings) {
      return gx1::DeviceState{};
    }
    std::lock_guard<std::mutex> lock(readings->mutex);
    return readings->imu;
  });
  live_->imu->start();
}

void EmulatedRobot::bringUpEncoders() {
  if (devices_.encoder_feed_path.empty() || live_->feed) {
    return;
  }
  live_->feed = std::make_unique<PhidgetFeedWriter>(devices_.encoder_feed_path);
  live_->feed->write(live_->board_counts);
}

void EmulatedRobot::route(const Sample& sample, const ScanObserver& observer) {
  Devices& d = *live_;
  std::optional<std::pair<std::int64_t, std::int64_t>> wheel_ticks;
  if (const auto* scan = std::get_if<LaserScan>(&sample)) {
    if (d.laser) {
      std::vector<std::uint32_t> raw = rawRangesOf(*scan, d.model);
      {
        std::lock_guard<std::mutex> lock(d.latest->mutex);
        d.latest->raw_ranges = std::move(raw);
      }
      ++counters_.scans;
      if (observer) {
        observer(device_clock::hostNow().seconds(), *scan);
      }
    }
  } else if (const auto* imu = std::get_if<ImuSample>(&sample)) {
    bringUpImu(*imu);
    if (d.imu) {
      std::lock_guard<std::mutex> lock(d.latest->mutex);
      d.latest->imu = gx1StateOf(*imu, devices_.imu_z_down);
      ++counters_.imu_samples;
    }
  } else if (const auto* ticks = std::get_if<WheelTicks>(&sample)) {
    wheel_ticks = std::make_pair(ticks->left, ticks->right);
  } else if (const auto* odometry = std::get_if<OdometryPose>(&sample)) {
    wheel_ticks = d.ticks_from_poses.add(odometry->T_odom_robot);
  }
  if (wheel_ticks) {
    bringUpEncoders();
  }
  if (wheel_ticks && d.feed) {
    d.board_counts[static_cast<std::size_t>(devices_.left_channel)] =
        devices_.left_direction * wheel_ticks->first;
    d.board_counts[static_cast<std::size_t>(devices_.right_channel)] =
        devices_.right_direction * wheel_ticks->second;
    d.feed->write(d.board_counts);
    ++counters_.tick_readings;
  }
}

EmulatedRobotCounters EmulatedRobot::run(const std::atomic<bool>& stop,
                                         const ScanObserver& observer) {
  if (!live_) {
    start();
  }
  const Clock::time_point wall_start = Clock::now();
  std::optional<std::int64_t> first_ns;
  std::size_t next_pending = 0;
  while (!stop.load()) {
    std::optional<Sample> sample;
    if (next_pending < pending_.size()) {
      sample = std::move(pending_[next_pending++]);
    } else {
      sample = source_->next();
    }
    if (!sample) {
      break;
    }
    const std::int64_t stamp_ns = stampOf(*sample).ns;
    first_ns = first_ns.value_or(stamp_ns);
    const double source_s = (stamp_ns - *first_ns) * 1e-9;
    if (settings_.duration_s && source_s > *settings_.duration_s) {
      break;
    }
    const auto due = wall_start + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(source_s / settings_.speed));
    while (!stop.load() && Clock::now() < due) {
      std::this_thread::sleep_until(std::min(due, Clock::now() + kStopCheck));
    }
    route(*sample, observer);
    counters_.source_time_s = source_s;
  }
  pending_.clear();
  if (live_->laser) {
    counters_.hokuyo_scans_sent = live_->laser->scansSent();
    live_->laser->stop();
  }
  if (live_->imu) {
    counters_.gx1_frames_sent =
        live_->imu->counters().streamed_frames + live_->imu->counters().polled_replies;
    live_->imu->stop();
  }
  live_.reset();  // the links and the feed file go away: the devices are unplugged
  return counters_;
}

}  // namespace mrslam::drivers
