// The 3DM-GX1 driver against the emulator over real pseudo-terminals: start-up, polled and
// continuous modes for every command, timer wrap, the stop command on shutdown.

#include <gtest/gtest.h>

#include <stdexcept>
#include <tuple>

#include "gx1_test_fixture.hpp"
#include "mrslam/common/config.hpp"

namespace mrslam::drivers {
namespace {

using namespace gx1_test;

struct Gx1DriverTest : ::testing::Test {
  Gx1Emulator emulator{emulatorSettings(), [] { return fixedState(); }};
  void SetUp() override { emulator.start(); }
};

TEST_F(Gx1DriverTest, StartUpReadsTheThreeGainsFromEeprom) {
  Gx1Driver driver(driverSettings(emulator.devicePath(), Gx1Mode::kPolled, 0x31));
  EXPECT_EQ(driver.state(), Gx1State::kDisconnected);  // nothing opened before poll()
  ASSERT_EQ(collect(driver, 1).size(), 1u) << driver.health().last_error;
  EXPECT_EQ(driver.state(), Gx1State::kRunning);
  EXPECT_EQ(driver.gains().gyro, kGyroGain);
  EXPECT_EQ(driver.gains().accel, kAccelGain);
  EXPECT_EQ(driver.gains().mag, kMagGain);
  EXPECT_EQ(emulator.counters().eeprom_reads, 3u);
  EXPECT_EQ(driver.health().startups, 1u);
  EXPECT_EQ(driver.health().failed_startups, 0u);
}

class Gx1ModeTest : public ::testing::TestWithParam<std::tuple<Gx1Mode, std::uint8_t>> {};

TEST_P(Gx1ModeTest, SamplesCarryTheDeviceValuesInRobotAxes) {
  const auto [mode, command] = GetParam();
  Gx1Emulator emulator(emulatorSettings(), [] { return fixedState(); });
  emulator.start();
  Gx1Driver driver(driverSettings(emulator.devicePath(), mode, command));
  const auto samples = collect(driver, 5);
  ASSERT_EQ(samples.size(), 5u) << driver.health().last_error;
  const double angle_tolerance = command == gx1::kQuaternionVectorsCommand ? 5e-4 : 1e-12;
  for (const ImuSample& sample : samples) {
    expectSample(sample, expectedSample(fixedState(), command), angle_tolerance);
  }
  for (std::size_t i = 1; i < samples.size(); ++i) {
    EXPECT_GT(samples[i].stamp, samples[i - 1].stamp);
  }
  const Gx1EmulatorCounters counters = emulator.counters();
  if (mode == Gx1Mode::kPolled) {
    EXPECT_GE(counters.polled_replies, 5u);
    EXPECT_EQ(counters.continuous_starts, 0u);
    EXPECT_FALSE(emulator.streaming());
  } else {
    EXPECT_EQ(counters.polled_replies, 0u);
    EXPECT_GE(counters.continuous_starts, 1u);
    EXPECT_EQ(emulator.streamingCommand(), command);
  }
  const Gx1Health health = driver.health();
  EXPECT_EQ(health.samples, 5u);
  EXPECT_EQ(health.parser.bad_checksums + health.parser.garbage_bytes, 0u);
}

std::string modeTestName(const ::testing::TestParamInfo<std::tuple<Gx1Mode, std::uint8_t>>& info) {
  const std::uint8_t command = std::get<1>(info.param);
  const std::string mode = std::get<0>(info.param) == Gx1Mode::kPolled ? "Polled" : "Continuous";
  if (command == gx1::kEulerCommand) {
    return mode + "Euler0x0E";
  }
  return mode + (command == gx1::kEulerVectorsCommand ? "EulerVectors0x31" : "Quaternion0x0C");
}

INSTANTIATE_TEST_SUITE_P(
    AllCommands, Gx1ModeTest,
    ::testing::Combine(::testing::Values(Gx1Mode::kPolled, Gx1Mode::kContinuous),
                       ::testing::Values(gx1::kEulerCommand, gx1::kEulerVectorsCommand,
                                         gx1::kQuaternionVectorsCommand)),
    modeTestName);

TEST_F(Gx1DriverTest, DeviceAxesAreKeptWhenZDownIsOff) {
  Gx1Settings settings = driverSettings(emulator.devicePath(), Gx1Mode::kPolled, 0x31);
  settings.device_z_down = false;
  Gx1Driver driver(settings);
  const auto samples = collect(driver, 1);
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_DOUBLE_EQ(samples[0].pitch_rad, fixedState().pitch_rad);
  EXPECT_DOUBLE_EQ(samples[0].yaw_rad, fixedState().yaw_rad);
  EXPECT_DOUBLE_EQ(samples[0].acceleration_g.z(), fixedState().acceleration_g.z());
}

TEST(Gx1DriverWrapTest, TimerTicksAreUnwrappedAcrossThe16BitWrap) {
  Gx1EmulatorSettings settings = emulatorSettings();
  settings.initial_ticks = 65500;  // start-up takes a few frames, then samples cross the wrap
  Gx1Emulator emulator(settings, [] { return fixedState(); });
  emulator.start();
  Gx1Driver driver(driverSettings(emulator.devicePath(), Gx1Mode::kPolled, 0x0E));
  std::vector<std::uint64_t> unwrapped;
  std::vector<std::uint16_t> raw;
  for (int poll = 0; poll < 200 && unwrapped.size() < 30; ++poll) {
    if (driver.poll(50ms)) {
      unwrapped.push_back(driver.lastUnwrappedTicks());
      raw.push_back(driver.lastRawTicks());
    }
  }
  ASSERT_EQ(unwrapped.size(), 30u);
  EXPECT_GT(raw.front(), 65400);  // before the wrap ...
  EXPECT_LT(raw.back(), 100);     // ... and after it
  for (std::size_t i = 1; i < unwrapped.size(); ++i) {
    EXPECT_EQ(unwrapped[i] - unwrapped[i - 1], 3u) << "sample " << i;  // 3 ticks per frame
  }
  EXPECT_EQ(unwrapped.back(), 65536u + raw.back());
}

TEST_F(Gx1DriverTest, CloseStopsContinuousMode) {
  Gx1Driver driver(driverSettings(emulator.devicePath(), Gx1Mode::kContinuous, 0x31));
  ASSERT_EQ(collect(driver, 3).size(), 3u);
  ASSERT_TRUE(emulator.streaming());
  const std::uint64_t stops_before = emulator.counters().continuous_stops;
  driver.close();
  EXPECT_TRUE(waitUntil([&] { return !emulator.streaming(); }));
  EXPECT_EQ(emulator.counters().continuous_stops, stops_before + 1);
  EXPECT_EQ(driver.state(), Gx1State::kClosed);
  EXPECT_FALSE(driver.poll(20ms));
}

TEST_F(Gx1DriverTest, DestructionStopsContinuousMode) {
  {
    Gx1Driver driver(driverSettings(emulator.devicePath(), Gx1Mode::kContinuous, 0x0C));
    ASSERT_EQ(collect(driver, 2).size(), 2u);
    ASSERT_EQ(emulator.streamingCommand(), 0x0C);
  }
  EXPECT_TRUE(waitUntil([&] { return !emulator.streaming(); }));
}

TEST_F(Gx1DriverTest, StartUpStopsADeviceLeftStreaming) {
  {
    // Like a program that crashed in continuous mode: streaming started, never stopped.
    SerialPort port;
    ASSERT_TRUE(port.open(emulator.devicePath(), 38400)) << port.error();
    const auto start = gx1::continuousRequest(0x31);
    ASSERT_EQ(port.writeAll(start.data(), start.size(), 100ms), SerialPort::Status::kOk);
    ASSERT_TRUE(waitUntil([&] { return emulator.streaming(); }));
  }
  Gx1Driver driver(driverSettings(emulator.devicePath(), Gx1Mode::kPolled, 0x0E));
  const auto samples = collect(driver, 3);
  ASSERT_EQ(samples.size(), 3u) << driver.health().last_error;
  EXPECT_FALSE(emulator.streaming());
  for (const ImuSample& sample : samples) {
    expectSample(sample, expectedSample(fixedState(), 0x0E));
  }
}

TEST(Gx1SettingsTest, UnusableSettingsAreRefused) {
  Gx1Settings settings = driverSettings("/dev/null", Gx1Mode::kPolled, 0x31);
  EXPECT_TRUE(settings.check().empty());
  settings.command = 0x01;
  EXPECT_THROW(Gx1Driver{settings}, std::invalid_argument);
  settings.command = 0x31;
  settings.tick_period_s = 0.0;
  EXPECT_NE(settings.check().find("tick_period_s"), std::string::npos);
  settings.tick_period_s = 0.01;
  settings.device.clear();
  EXPECT_NE(settings.check().find("device"), std::string::npos);
}

TEST(Gx1SettingsTest, ReadsAConfigSection) {
  const Config config = Config::loadString(
      "imu:\n  device: /dev/ttyS1\n  mode: continuous\n  command: 0x0C\n"
      "  tick_period_s: 0.01\n  read_timeout_s: 0.5\n  device_z_down: false\n"
      "  quaternion: earth_to_sensor\n",
      "robot.yaml");
  const Gx1Settings settings = Gx1Settings::fromConfig(config.section("imu"));
  config.checkNoUnknownKeys();
  EXPECT_EQ(settings.device, "/dev/ttyS1");
  EXPECT_EQ(settings.mode, Gx1Mode::kContinuous);
  EXPECT_EQ(settings.command, gx1::kQuaternionVectorsCommand);
  EXPECT_DOUBLE_EQ(settings.tick_period_s, 0.01);
  EXPECT_EQ(settings.read_timeout, 500ms);
  EXPECT_FALSE(settings.device_z_down);
  EXPECT_EQ(settings.quaternion, gx1::QuaternionConvention::kEarthToSensor);
  EXPECT_EQ(settings.baud, 38400);  // defaults stay
}

TEST(Gx1SettingsTest, AConfigWithABadCommandNamesFileLineAndKey) {
  const Config config = Config::loadString("device: /dev/ttyS1\ncommand: 0x01\n", "robot.yaml");
  try {
    Gx1Settings::fromConfig(config);
    FAIL() << "no error";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("robot.yaml:2"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("command"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace mrslam::drivers
