// The emulated robot: samples become what its devices send, and the real drivers (Hokuyo and
// 3DM-GX1 over pseudo-terminals, the Phidget adapter loading the emulated board) read back the
// samples it played.

#include "mrslam/drivers/emulated_robot.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "hokuyo_test_support.hpp"
#include "mrslam/drivers/gx1_driver.hpp"
#include "mrslam/drivers/hokuyo_driver.hpp"
#include "mrslam/drivers/phidget_encoders.hpp"
#include "mrslam/drivers/simulator.hpp"
#include "test_data.hpp"

namespace mrslam::drivers {
namespace {

using namespace std::chrono_literals;

LaserScan scanOf(std::size_t beams, double angle_min, double increment, float fill) {
  LaserScan scan;
  scan.angle_min_rad = angle_min;
  scan.angle_increment_rad = increment;
  scan.range_min_m = 0.02;
  scan.range_max_m = 4.5;
  scan.ranges_m.assign(beams, fill);
  return scan;
}

TEST(EmulatedDevicesTest, TheSimulatorsLaserIsTheUbg05ln) {
  const double increment = 0.36 * M_PI / 180.0;
  const auto model = hokuyoModelFor(scanOf(513, -256 * increment, increment, 1.0f), 10.0);
  ASSERT_TRUE(model) << model.reason();
  EXPECT_EQ(model.value().product, HokuyoModel::ubg05ln().product);
  EXPECT_EQ(model.value().geometry.scan_rpm, 600);
}

TEST(EmulatedDevicesTest, ALogsOneDegreeScansGetAModelOfTheirOwn) {
  const double increment = M_PI / 180.0;
  const auto model = hokuyoModelFor(scanOf(180, -M_PI / 2.0, increment, 1.0f), 5.0);
  ASSERT_TRUE(model) << model.reason();
  const scip::ScanGeometry& g = model.value().geometry;
  EXPECT_EQ(g.ares, 360);
  EXPECT_EQ(g.afrt, 90);
  EXPECT_EQ(g.measuredSteps(), 180);
  EXPECT_EQ(g.scan_rpm, 300);
  EXPECT_EQ(g.dmax_mm, 4500);
  EXPECT_NEAR(g.stepAngleRad(g.amin), -M_PI / 2.0, 1e-12);
  // A start between two steps fits no Hokuyo.
  EXPECT_FALSE(hokuyoModelFor(scanOf(180, -M_PI / 2.0 + 0.3 * increment, increment, 1.0f), 5.0));
  EXPECT_FALSE(hokuyoModelFor(scanOf(0, -1.0, increment, 1.0f), 5.0));
}

TEST(EmulatedDevicesTest, RawValuesCarryHitsNoReturnsAndErrors) {
  const HokuyoModel model = HokuyoModel::ubg05ln();
  LaserScan scan = scanOf(513, 0.0, 0.0, 1.2344f);
  scan.ranges_m[1] = LaserScan::kNoReturn;
  scan.ranges_m[2] = LaserScan::kInvalid;
  scan.ranges_m[3] = 0.005f;  // closer than DMIN
  scan.ranges_m[4] = 9.0f;    // beyond DMAX
  const std::vector<std::uint32_t> raw = rawRangesOf(scan, model);
  ASSERT_EQ(raw.size(), 513u);
  EXPECT_EQ(raw[0], 1234u);
  EXPECT_EQ(raw[1], 4501u);
  EXPECT_EQ(raw[2], 1u);
  EXPECT_EQ(raw[3], 1u);
  EXPECT_EQ(raw[4], 4501u);
  // The driver's reading of them (hokuyo_test_support: written out independently).
  const std::vector<float> read = test::expectedRanges(raw, model.geometry);
  EXPECT_FLOAT_EQ(read[0], 1.234f);
  EXPECT_TRUE(std::isinf(read[1]));
  EXPECT_TRUE(std::isnan(read[2]));
}

TEST(EmulatedDevicesTest, TheGx1ReadsInItsOwnAxes) {
  ImuSample sample;
  sample.roll_rad = 0.1;
  sample.pitch_rad = 0.2;
  sample.yaw_rad = 0.3;
  sample.angular_rate_rad_s = {0.01, 0.02, 0.03};
  sample.acceleration_g = {0.1, 0.0, 1.0};
  const gx1::DeviceState z_down = gx1StateOf(sample, true);
  EXPECT_DOUBLE_EQ(z_down.roll_rad, 0.1);
  EXPECT_DOUBLE_EQ(z_down.pitch_rad, -0.2);
  EXPECT_DOUBLE_EQ(z_down.yaw_rad, -0.3);  // heading clockwise
  EXPECT_DOUBLE_EQ(z_down.angular_rate_rad_s.z(), -0.03);
  EXPECT_DOUBLE_EQ(z_down.acceleration_g.z(), -1.0);  // level at rest: -1 g on z
  const gx1::DeviceState z_up = gx1StateOf(sample, false);
  EXPECT_DOUBLE_EQ(z_up.yaw_rad, 0.3);
  // Unknown vectors (0x0E readings) are sent as zero, not NaN.
  sample.angular_rate_rad_s.setConstant(std::nan(""));
  EXPECT_TRUE(gx1StateOf(sample, true).angular_rate_rad_s.isZero());
}

TEST(EmulatedDevicesTest, TheFeedFileIsReplacedWholeAndRemovedAtTheEnd) {
  const std::string path = (mrslam::test::scratchFolder("feed") / "encoders.feed").string();
  {
    PhidgetFeedWriter feed(path);
    feed.write({1, -2, 3, 4});
    std::ifstream file(path);
    std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text, "mrslam-phidget-feed 1\n1 -2 3 4\n");
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

// One simulated robot played through its emulated devices, read by the real drivers.
class EmulatedRobotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = mrslam::test::scratchFolder("emulated_robot");
    devices_.laser_path = (folder_ / "laser").string();
    devices_.imu_path = (folder_ / "imu").string();
    devices_.encoder_feed_path = (folder_ / "encoders.feed").string();
    devices_.left_channel = 2;
    devices_.right_channel = 3;
    devices_.right_direction = -1;
    ::setenv("MRSLAM_PHIDGET_EMULATOR_FEED", devices_.encoder_feed_path.c_str(), 1);
  }
  void TearDown() override { ::unsetenv("MRSLAM_PHIDGET_EMULATOR_FEED"); }

  std::filesystem::path folder_;
  EmulatedDevices devices_;
};

TEST_F(EmulatedRobotTest, TheDriversReadWhatTheSimulatorSensed) {
  SimulatorSettings sim;
  sim.duration_s = 3.0;
  sim.seed = 5;
  DiffDriveParams drive;
  EmulatedRobotSettings settings;
  settings.drive = drive;
  EmulatedRobot robot(std::make_unique<Simulator>(sim, drive, SensorMounting{}), devices_,
                      settings);
  robot.start();
  ASSERT_TRUE(std::filesystem::exists(devices_.laser_path));
  ASSERT_TRUE(std::filesystem::exists(devices_.imu_path));
  ASSERT_TRUE(std::filesystem::exists(devices_.encoder_feed_path));
  EXPECT_EQ(robot.laserModel().product, HokuyoModel::ubg05ln().product);

  PhidgetEncoderSettings encoder_settings;
  encoder_settings.library_names = {MRSLAM_PHIDGET_EMULATOR};
  encoder_settings.left = {-1, -1, 2, 1};
  encoder_settings.right = {-1, -1, 3, -1};
  auto encoders = PhidgetEncoders::open(encoder_settings);
  ASSERT_TRUE(encoders) << encoders.reason();
  // What the robot played, recorded by its observer; then the drivers, as an agent opens them.
  std::mutex played_mutex;
  std::vector<std::vector<std::uint32_t>> played;
  std::atomic<bool> stop{false};
  EmulatedRobotCounters counters;
  const HokuyoModel model = robot.laserModel();
  std::thread player([&] {
    counters = robot.run(stop, [&](double, const LaserScan& scan) {
      std::lock_guard<std::mutex> lock(played_mutex);
      played.push_back(rawRangesOf(scan, model));
    });
  });
  HokuyoDriver laser(test::quickSettings(devices_.laser_path));
  Gx1Settings imu_settings;
  imu_settings.device = devices_.imu_path;
  imu_settings.mode = Gx1Mode::kContinuous;
  Gx1Driver imu(imu_settings);

  const std::vector<LaserScan> scans = test::collectScans(laser, 10);
  std::vector<ImuSample> imu_samples;
  for (int poll = 0; poll < 50 && imu_samples.size() < 20; ++poll) {
    if (auto sample = imu.poll(100ms)) {
      imu_samples.push_back(*sample);
    }
  }
  player.join();
  // The encoders' readings as the simulator produced them (directions undone by the board).
  Simulator twin(sim, drive, SensorMounting{});
  std::vector<WheelTicks> produced;
  while (auto sample = twin.next()) {
    if (const auto* reading = std::get_if<WheelTicks>(&*sample)) {
      produced.push_back(*reading);
    }
  }
  ASSERT_FALSE(produced.empty());
  std::optional<WheelTicks> ticks;
  for (int poll = 0; poll < 20; ++poll) {  // the board's thread reads the last feed it saw
    if (auto latest = encoders.value()->poll()) {
      ticks = latest;
    }
    std::this_thread::sleep_for(20ms);
  }

  EXPECT_GT(counters.source_time_s, 2.9);
  EXPECT_GE(counters.scans, 29u);
  // Every scan the driver read is one the robot played (to the millimetre).
  ASSERT_GE(scans.size(), 10u);
  for (const LaserScan& scan : scans) {
    bool found = false;
    std::lock_guard<std::mutex> lock(played_mutex);
    for (const auto& raw : played) {
      found = found || test::sameRanges(scan.ranges_m, test::expectedRanges(raw, model.geometry));
    }
    EXPECT_TRUE(found) << "a scan the robot never played";
  }
  // The IMU: the simulator's robot starts facing east (route 0) and turns little in 3 s.
  ASSERT_GE(imu_samples.size(), 20u);
  for (const ImuSample& sample : imu_samples) {
    EXPECT_LT(std::abs(sample.yaw_rad - builtInStartPose(0).theta()), 0.5);
    EXPECT_NEAR(sample.acceleration_g.z(), 1.0, 0.1);  // z up after the driver's flip
  }
  // The encoders: the board's counts are a reading the simulator produced, from the run's last
  // second. The board samples its feed every data interval and the robot unplugs it at the end,
  // so a reading written after the board's last sample never reaches it (as on a real board).
  ASSERT_TRUE(ticks);
  EXPECT_GT(produced.back().left, 100);
  const auto same = std::find_if(produced.begin(), produced.end(), [&](const WheelTicks& reading) {
    return reading.left == ticks->left && reading.right == ticks->right;
  });
  ASSERT_NE(same, produced.end()) << "counts the simulator never produced: " << ticks->left << ", "
                                  << ticks->right;
  EXPECT_GE(same->stamp.ns, produced.back().stamp.ns - 1'000'000'000);
  EXPECT_FALSE(std::filesystem::exists(devices_.laser_path));  // unplugged at the end
  EXPECT_FALSE(std::filesystem::exists(devices_.encoder_feed_path));
}

// A log's samples: one-degree scans and odometry poses, no IMU.
class ListSource : public SampleSource {
 public:
  explicit ListSource(std::vector<Sample> samples) : samples_(std::move(samples)) {}
  std::optional<Sample> next() override {
    if (next_ == samples_.size()) {
      return std::nullopt;
    }
    return samples_[next_++];
  }
  std::string describe() const override { return "a list"; }
  SourceCounters counters() const override { return {}; }

 private:
  std::vector<Sample> samples_;
  std::size_t next_ = 0;
};

TEST_F(EmulatedRobotTest, OdometryPosesBecomeTheWheelTravelAndNoImuAppears) {
  std::vector<Sample> samples;
  for (int k = 0; k <= 5; ++k) {
    LaserScan scan = scanOf(180, -M_PI / 2.0, M_PI / 180.0, 2.0f);
    scan.stamp = Stamp::fromSeconds(100.0 + 0.1 * k);
    samples.emplace_back(std::in_place_type<LaserScan>, std::move(scan));
    if (k == 5) {
      break;
    }
    // 0.25 m forward per step, then a quarter turn on the spot in the last step.
    const SE2 pose = k < 4 ? SE2(0.25 * k, 0.0, 0.0) : SE2(0.75, 0.0, M_PI / 2.0);
    samples.emplace_back(std::in_place_type<OdometryPose>,
                         OdometryPose{Stamp::fromSeconds(100.0 + 0.1 * k + 0.05), pose});
  }
  EmulatedRobotSettings settings;
  settings.drive.wheel_radius_m = 0.1;
  settings.drive.track_width_m = 0.4;
  settings.drive.ticks_per_revolution = 1000;
  EmulatedRobot robot(std::make_unique<ListSource>(samples), devices_, settings);
  robot.start();
  EXPECT_EQ(robot.laserModel().geometry.ares, 360);
  EXPECT_FALSE(std::filesystem::exists(devices_.imu_path));  // the log has no IMU
  std::vector<std::int64_t> last_feed;
  std::atomic<bool> stop{false};
  const EmulatedRobotCounters counters = robot.run(stop, [&](double, const LaserScan&) {
    std::ifstream feed(devices_.encoder_feed_path);
    std::string magic;
    int version = 0;
    last_feed.assign(4, 0);
    feed >> magic >> version >> last_feed[0] >> last_feed[1] >> last_feed[2] >> last_feed[3];
  });
  EXPECT_EQ(counters.scans, 6u);
  EXPECT_EQ(counters.imu_samples, 0u);
  EXPECT_EQ(counters.tick_readings, 5u);
  // Seen at the last scan: 0.75 m forward = 0.75 / (2π · 0.1) · 1000 counts on each wheel, then
  // a quarter turn: each wheel ± π/2 · 0.2 m = ± 0.314 m = ± 500 counts (inputs 2 and 3; the right
  // one counts down, its direction being -1).
  const double forward = 0.75 / (2.0 * M_PI * 0.1) * 1000.0;
  ASSERT_EQ(last_feed.size(), 4u);
  EXPECT_EQ(last_feed[2], std::llround(forward - 500.0));
  EXPECT_EQ(last_feed[3], -std::llround(forward + 500.0));
  EXPECT_EQ(last_feed[0], 0);
}

}  // namespace
}  // namespace mrslam::drivers
