// The robot's devices as one source, on emulated devices behind real pseudo-terminals: samples
// from the devices; a device lost while running → its replay fallback, then the device again
// when it is back; a missing device without fallback → absent, the others go on; no Phidget
// library here → the encoders' ticks come from the replay log, continuous.

#include "mrslam/robot/device_source.hpp"

#include "mrslam/robot/robot_config.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include <fstream>
#include <functional>

#include "mrslam/drivers/device_host_clock.hpp"
#include "mrslam/drivers/gx1_emulator.hpp"
#include "mrslam/drivers/hokuyo_emulator.hpp"
#include "mrslam/drivers/mrslam_log.hpp"
#include "test_data.hpp"

namespace mrslam::robot {
namespace {

using namespace std::chrono_literals;

// Loops wait for what they expect at most this long (a bound, not an assertion on time).
constexpr auto kPatience = std::chrono::seconds(30);

drivers::HokuyoSettings laserSettings(const std::string& device) {
  drivers::HokuyoSettings settings;
  settings.device = device;
  settings.read_timeout = 300ms;
  settings.reconnect_backoff_min = 20ms;
  settings.reconnect_backoff_max = 200ms;
  settings.stall_scan_periods = 3;
  settings.time_sync_round_trips = 1;
  return settings;
}

drivers::Gx1Settings imuSettings(const std::string& device) {
  drivers::Gx1Settings settings;
  settings.device = device;
  settings.mode = drivers::Gx1Mode::kPolled;
  settings.command = drivers::gx1::kEulerVectorsCommand;
  settings.read_timeout = 250ms;
  settings.reconnect_initial = 20ms;
  settings.reconnect_max = 100ms;
  return settings;
}

// A replay log of 30 s: a scan, ticks and an IMU sample every 100 ms.
std::string writeReplayLog(const std::filesystem::path& folder) {
  const std::string path = (folder / "fallback.log").string();
  drivers::MrslamLogWriter writer(path, "robot1");
  for (int i = 0; i < 300; ++i) {
    const Stamp stamp{1'000'000'000LL + i * 100'000'000LL};
    LaserScan scan;
    scan.stamp = stamp;
    scan.angle_min_rad = -1.0;
    scan.angle_increment_rad = 0.01;
    scan.range_min_m = 0.02;
    scan.range_max_m = 5.6;
    scan.ranges_m.assign(201, 2.5f);
    writer.write(scan);
    writer.write(WheelTicks{stamp, 10 * i, 12 * i});
    ImuSample imu;
    imu.stamp = stamp;
    writer.write(imu);
  }
  writer.close();
  return path;
}

SensorHealth healthOf(const DeviceSource& source, const std::string& name) {
  for (const SensorHealth& sensor : source.health()) {
    if (sensor.name == name) {
      return sensor;
    }
  }
  ADD_FAILURE() << "no sensor " << name;
  return {};
}

// Reads samples until `done` holds (or kPatience runs out); counts them by kind.
struct Counts {
  int scans = 0;
  int imu = 0;
  std::vector<WheelTicks> ticks;
};
Counts readUntil(DeviceSource& source, const std::function<bool(const Counts&)>& done) {
  Counts counts;
  const auto give_up = std::chrono::steady_clock::now() + kPatience;
  while (!done(counts) && std::chrono::steady_clock::now() < give_up) {
    std::optional<Sample> sample = source.next();
    if (!sample) {
      continue;
    }
    counts.scans += std::holds_alternative<LaserScan>(*sample);
    counts.imu += std::holds_alternative<ImuSample>(*sample);
    if (const auto* ticks = std::get_if<WheelTicks>(&*sample)) {
      counts.ticks.push_back(*ticks);
    }
  }
  return counts;
}

class DeviceSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = test::scratchFolder("devices");
    laser_ = std::make_unique<drivers::HokuyoEmulator>(drivers::HokuyoEmulatorSettings{},
                                                       (folder_ / "ttyACM0").string());
    laser_->start();
    imu_ = std::make_unique<drivers::Gx1Emulator>(drivers::Gx1EmulatorSettings{},
                                                  [] { return drivers::gx1::DeviceState{}; });
    imu_->start();
  }

  std::filesystem::path folder_;
  std::unique_ptr<drivers::HokuyoEmulator> laser_;
  std::unique_ptr<drivers::Gx1Emulator> imu_;
  std::atomic<bool> shutdown_{false};
};

TEST_F(DeviceSourceTest, ScansAndImuSamplesComeFromTheDevices) {
  DeviceSourceSettings settings;
  settings.laser = laserSettings(laser_->devicePath());
  settings.imu = imuSettings(imu_->devicePath());
  DeviceSource source(settings, shutdown_);
  const Counts counts =
      readUntil(source, [](const Counts& c) { return c.scans >= 5 && c.imu >= 5; });
  EXPECT_GE(counts.scans, 5);
  EXPECT_GE(counts.imu, 5);
  EXPECT_EQ(healthOf(source, "laser").state, SensorState::kDevice);
  EXPECT_EQ(healthOf(source, "imu").state, SensorState::kDevice);
  EXPECT_EQ(healthOf(source, "laser").fallback_samples, 0u);
  EXPECT_EQ(source.counters().samples, static_cast<std::uint64_t>(counts.scans + counts.imu));
  shutdown_ = true;
  EXPECT_FALSE(source.next().has_value());  // shutdown ends the stream
}

TEST_F(DeviceSourceTest, ALostLaserFallsBackToReplayAndIsUsedAgainWhenBack) {
  DeviceSourceSettings settings;
  settings.laser = laserSettings(laser_->devicePath());
  settings.replay_log = writeReplayLog(folder_);
  DeviceSource source(settings, shutdown_);
  readUntil(source, [](const Counts& c) { return c.scans >= 3; });
  ASSERT_EQ(healthOf(source, "laser").state, SensorState::kDevice);

  laser_->unplug();
  readUntil(source, [&](const Counts&) { return healthOf(source, "laser").fallback_samples >= 3; });
  SensorHealth laser = healthOf(source, "laser");
  EXPECT_EQ(laser.state, SensorState::kFallback);
  EXPECT_GE(laser.fallback_samples, 3u);
  EXPECT_EQ(laser.losses, 1u);
  EXPECT_FALSE(laser.last_error.empty());
  // What the robot status carries.
  const std::vector<drivers::SensorStatus> status = source.sensors();
  ASSERT_EQ(status.size(), 1u);
  EXPECT_EQ(status[0].name, "laser");
  EXPECT_EQ(status[0].source, "fallback");
  EXPECT_FALSE(status[0].healthy);
  EXPECT_EQ(status[0].errors, 1u);

  const std::uint64_t device_before = laser.device_samples;
  laser_->replug();
  readUntil(source, [&](const Counts&) {
    const SensorHealth now = healthOf(source, "laser");
    return now.state == SensorState::kDevice && now.device_samples >= device_before + 3;
  });
  laser = healthOf(source, "laser");
  EXPECT_EQ(laser.state, SensorState::kDevice);
  EXPECT_GE(laser.device_samples, device_before + 3);
}

TEST_F(DeviceSourceTest, AMissingDeviceWithoutFallbackIsAbsentAndTheOthersGoOn) {
  DeviceSourceSettings settings;
  settings.laser = laserSettings((folder_ / "no-such-device").string());
  settings.laser_fallback = DeviceFallback::kNone;
  settings.imu = imuSettings(imu_->devicePath());
  DeviceSource source(settings, shutdown_);
  const Counts counts = readUntil(source, [&](const Counts& c) {
    return c.imu >= 5 && healthOf(source, "laser").state == SensorState::kAbsent;
  });
  EXPECT_GE(counts.imu, 5);
  EXPECT_EQ(counts.scans, 0);
  const SensorHealth laser = healthOf(source, "laser");
  EXPECT_EQ(laser.state, SensorState::kAbsent);
  EXPECT_FALSE(laser.last_error.empty());
}

TEST_F(DeviceSourceTest, WithoutThePhidgetLibraryTheTicksComeFromReplayContinuous) {
  DeviceSourceSettings settings;
  settings.encoders = drivers::PhidgetEncoderSettings{};
  settings.replay_log = writeReplayLog(folder_);
  DeviceSource source(settings, shutdown_);
  const Counts counts = readUntil(source, [](const Counts& c) { return c.ticks.size() >= 5; });
  ASSERT_GE(counts.ticks.size(), 5u);
  for (std::size_t i = 1; i < counts.ticks.size(); ++i) {
    EXPECT_EQ(counts.ticks[i].left - counts.ticks[i - 1].left, 10) << i;
    EXPECT_EQ(counts.ticks[i].right - counts.ticks[i - 1].right, 12) << i;
    EXPECT_EQ(counts.ticks[i].stamp.ns - counts.ticks[i - 1].stamp.ns, 100'000'000) << i;
  }
  const SensorHealth encoders = healthOf(source, "encoders");
  EXPECT_EQ(encoders.state, SensorState::kFallback);
  EXPECT_NE(encoders.last_error.find("hidget"), std::string::npos) << encoders.last_error;
}

TEST_F(DeviceSourceTest, SamplesFromDifferentDevicesLeaveInTimeStampOrder) {
  DeviceSourceSettings settings;
  settings.laser = laserSettings((folder_ / "no-such-device").string());
  settings.laser_fallback = DeviceFallback::kNone;
  settings.reorder_window_s = 0.2;
  DeviceSource source(settings, shutdown_);
  const std::int64_t now_ns = drivers::device_clock::hostNow().ns;
  const auto imuAt = [&](std::int64_t ago_ms) {
    ImuSample sample;
    sample.stamp = Stamp::fromNanoseconds(now_ns - ago_ms * 1'000'000);
    return Sample(sample);
  };
  // A scan arrives first; IMU samples stamped before it arrive after it, within the window.
  LaserScan scan;
  scan.stamp = Stamp::fromNanoseconds(now_ns - 50'000'000);
  source.push(scan);
  source.push(imuAt(80));
  source.push(imuAt(60));
  source.push(imuAt(40));
  std::vector<std::int64_t> stamps;
  for (int i = 0; i < 4; ++i) {
    const std::optional<Sample> sample = source.next();
    ASSERT_TRUE(sample);
    stamps.push_back(stampOf(*sample).ns);
  }
  EXPECT_TRUE(std::is_sorted(stamps.begin(), stamps.end()));
  EXPECT_EQ(stamps[2], now_ns - 50'000'000);  // the scan after the two IMU samples before it
  // The window had passed over each sample when it left.
  EXPECT_GE(drivers::device_clock::hostNow().ns, stamps.back() + 200'000'000);
  // One stamped before what already left is handed out, and counted.
  source.push(imuAt(500));
  ASSERT_TRUE(source.next());
  EXPECT_EQ(source.outOfOrderSamples(), 1u);
}

TEST(DeviceSourceConfigTest, NoDeviceConfiguredIsAnError) {
  std::atomic<bool> shutdown{false};
  EXPECT_THROW(DeviceSource(DeviceSourceSettings{}, shutdown), std::invalid_argument);
}

}  // namespace
}  // namespace mrslam::robot

namespace mrslam::robot {
namespace {

TEST(DeviceSourceConfigTest, TheExampleRobotConfigNamesEveryDeviceAndItsFallback) {
  const RobotConfig config = loadRobotConfig(test::sourcePath("config/devices_robot.yaml"));
  ASSERT_EQ(config.source.type, SourceType::kDevices);
  const DeviceSourceSettings& devices = config.source.devices;
  ASSERT_TRUE(devices.laser && devices.imu && devices.encoders);
  EXPECT_EQ(devices.laser->device, "/dev/ttyACM0");
  EXPECT_EQ(devices.imu->device, "/dev/ttyS0");
  EXPECT_EQ(devices.imu->mode, drivers::Gx1Mode::kContinuous);
  EXPECT_EQ(devices.encoders->right.direction, -1);
  EXPECT_EQ(devices.laser_fallback, DeviceFallback::kReplay);
  EXPECT_NE(devices.replay_log.find("coroware1.log"), std::string::npos);
}

TEST(DeviceSourceConfigTest, ADevicesSourceWithoutDevicesOrWithABadFallbackIsRefused) {
  const auto folder = test::scratchFolder("config");
  const auto load = [&folder](const std::string& text) -> std::string {
    const std::string path = (folder / "robot.yaml").string();
    std::ofstream(path) << "robot_id: r1\nsource:\n  type: devices\n" << text;
    try {
      loadRobotConfig(path);
    } catch (const ConfigError& error) {
      return error.what();
    }
    return "no error";
  };
  EXPECT_NE(load("").find("needs at least one of laser, imu, encoders"), std::string::npos);
  EXPECT_NE(load("  devices:\n    laser:\n      device: /dev/x\n      fallback: maybe\n")
                .find("robot.yaml:7: source.devices.laser.fallback: 'maybe' is not one of"),
            std::string::npos)
      << load("  devices:\n    laser:\n      device: /dev/x\n      fallback: maybe\n");
}

}  // namespace
}  // namespace mrslam::robot
