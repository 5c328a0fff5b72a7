// The Hokuyo driver against the emulator over real pseudo-terminals: start-up, streaming
// geometry of both models, single scans, the 24-bit clock, shutdown. Faults: hokuyo_faults_test.

#include "mrslam/drivers/hokuyo_driver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "hokuyo_test_support.hpp"

namespace mrslam::drivers {
namespace {

using namespace test;

std::unique_ptr<HokuyoEmulator> startEmulator(HokuyoEmulatorSettings settings) {
  auto emulator = std::make_unique<HokuyoEmulator>(std::move(settings), linkPath());
  emulator->start();
  return emulator;
}

std::size_t countOf(const std::vector<std::string>& commands, const std::string& command) {
  return static_cast<std::size_t>(std::count(commands.begin(), commands.end(), command));
}

TEST(HokuyoDriverTest, StartUpReadsIdentityGeometryAndSynchronisesTime) {
  auto emulator = startEmulator({});
  HokuyoDriver driver(quickSettings(emulator->devicePath()));
  const auto identity = driver.connect();
  ASSERT_TRUE(identity.ok()) << identity.reason();
  EXPECT_EQ(identity.value().version.at("PROD"), "SOKUIKI Sensor URG-04LX");
  EXPECT_EQ(identity.value().parameters.at("MODL"), "URG-04LX(Hokuyo Automatic Co.,Ltd.)");
  EXPECT_EQ(identity.value().state.at("STAT"), "Sensor works well.");
  EXPECT_EQ(identity.value().geometry.amin, 44);
  EXPECT_EQ(identity.value().geometry.amax, 725);
  EXPECT_EQ(identity.value().baud, 115200);
  EXPECT_FALSE(identity.value().switched_from_scip11);
  EXPECT_TRUE(identity.value().time_synchronised);
  EXPECT_EQ(driver.health().state, HokuyoState::kConnected);
  const std::vector<std::string> expected{"QT",  "VV",  "PP",  "II",  "TM0",
                                          "TM1", "TM1", "TM1", "TM2", "BM"};
  EXPECT_EQ(emulator->receivedCommands(), expected);
}

TEST(HokuyoDriverTest, SwitchesADeviceInScip11ToScip20) {
  HokuyoEmulatorSettings settings;
  settings.protocol.start_in_scip11 = true;
  auto emulator = startEmulator(settings);
  HokuyoDriver driver(quickSettings(emulator->devicePath()));
  const auto identity = driver.connect();
  ASSERT_TRUE(identity.ok()) << identity.reason();
  EXPECT_TRUE(identity.value().switched_from_scip11);
  const auto commands = emulator->receivedCommands();
  ASSERT_GE(commands.size(), 3u);
  EXPECT_EQ(commands[0], "QT");  // answered "E" (SCIP 1.1)
  EXPECT_EQ(commands[1], "SCIP2.0");
  EXPECT_EQ(commands[2], "QT");
}

TEST(HokuyoDriverTest, ProbesBaudRatesUntilTheDeviceAnswers) {
  HokuyoEmulatorSettings settings;
  settings.device_baud = 38400;  // an RS-232 device: every other rate reads noise
  auto emulator = startEmulator(settings);
  HokuyoSettings driver_settings = quickSettings(emulator->devicePath());
  driver_settings.baud = 115200;
  driver_settings.probe_bauds = {19200, 38400, 115200};
  HokuyoDriver driver(driver_settings);
  const auto identity = driver.connect();
  ASSERT_TRUE(identity.ok()) << identity.reason();
  EXPECT_EQ(identity.value().baud, 38400);
  const auto scans = collectScans(driver, 2);
  EXPECT_EQ(scans.size(), 2u);
}

TEST(HokuyoDriverTest, StreamsUrg04lxScansWithTheGeometryOfItsParameters) {
  auto emulator = startEmulator({});
  HokuyoDriver driver(quickSettings(emulator->devicePath()));
  const auto scans = collectScans(driver, 6);
  ASSERT_EQ(scans.size(), 6u) << driver.health().last_error;
  const HokuyoModel model = HokuyoModel::urg04lx();
  const auto expected = expectedRanges(hokuyoRangePattern("ramp", model)(0), model.geometry);
  for (const LaserScan& scan : scans) {
    ASSERT_EQ(scan.ranges_m.size(), 682u);
    EXPECT_NEAR(scan.angle_min_rad, (44 - 384) * 2 * M_PI / 1024, 1e-9);
    EXPECT_NEAR(scan.angle_increment_rad, 2 * M_PI / 1024, 1e-12);
    EXPECT_DOUBLE_EQ(scan.range_min_m, 0.02);
    EXPECT_DOUBLE_EQ(scan.range_max_m, 5.6);
  }
  EXPECT_EQ(scansDifferingFrom(scans, expected), 0);
  expectStampsFollowTheSensorClock(scans, 0.1);
  const HokuyoHealth health = driver.health();
  EXPECT_EQ(health.counters.scans, 6u);
  EXPECT_EQ(health.counters.checksum + health.counters.truncated + health.counters.status +
                health.counters.garbage + health.counters.timeout + health.counters.disconnect,
            0u);
  EXPECT_EQ(driver.scanRequest().text(), "MD0044072501000");
}

TEST(HokuyoDriverTest, StreamsUbg05lnScansOf513BeamsAt036Degrees) {
  HokuyoEmulatorSettings settings;
  settings.model = HokuyoModel::ubg05ln();
  settings.ranges = hokuyoRangePattern("room", settings.model);
  auto emulator = startEmulator(settings);
  HokuyoDriver driver(quickSettings(emulator->devicePath()));
  const auto scans = collectScans(driver, 3);
  ASSERT_EQ(scans.size(), 3u) << driver.health().last_error;
  const auto expected = expectedRanges(settings.ranges(0), settings.model.geometry);
  for (const LaserScan& scan : scans) {
    ASSERT_EQ(scan.ranges_m.size(), 513u);
    EXPECT_NEAR(scan.angle_min_rad, -256 * 0.36 * M_PI / 180, 1e-9);
    EXPECT_NEAR(scan.angle_increment_rad, 0.36 * M_PI / 180, 1e-12);
    EXPECT_DOUBLE_EQ(scan.range_max_m, 4.5);
    EXPECT_FLOAT_EQ(scan.ranges_m[256], 1.5f);  // straight ahead
  }
  EXPECT_EQ(scansDifferingFrom(scans, expected), 0);
}

TEST(HokuyoDriverTest, StepsAndClusterComeFromTheSettings) {
  auto emulator = startEmulator({});
  HokuyoSettings settings = quickSettings(emulator->devicePath());
  settings.start_step = 100;
  settings.end_step = 399;
  settings.cluster = 3;
  HokuyoDriver driver(settings);
  const auto scans = collectScans(driver, 2);
  ASSERT_EQ(scans.size(), 2u) << driver.health().last_error;
  const HokuyoModel model = HokuyoModel::urg04lx();
  const auto ramp = hokuyoRangePattern("ramp", model)(0);
  std::vector<std::uint32_t> cluster_minima;
  for (int step = 100; step <= 399; step += 3) {
    const auto first = ramp.begin() + (step - 44);
    cluster_minima.push_back(*std::min_element(first, first + 3));
  }
  EXPECT_EQ(scans[0].ranges_m.size(), 100u);
  EXPECT_NEAR(scans[0].angle_min_rad, (101 - 384) * 2 * M_PI / 1024, 1e-9);
  EXPECT_NEAR(scans[0].angle_increment_rad, 3 * 2 * M_PI / 1024, 1e-12);
  EXPECT_EQ(scansDifferingFrom(scans, expectedRanges(cluster_minima, model.geometry)), 0);
}

TEST(HokuyoDriverTest, SingleScansByGdAlsoAfterStreaming) {
  auto emulator = startEmulator({});
  HokuyoDriver driver(quickSettings(emulator->devicePath()));
  const HokuyoModel model = HokuyoModel::urg04lx();
  const auto expected = expectedRanges(hokuyoRangePattern("ramp", model)(0), model.geometry);
  const auto first = driver.singleScan();
  ASSERT_TRUE(first.ok()) << first.reason();
  EXPECT_TRUE(sameRanges(first.value().ranges_m, expected));
  ASSERT_EQ(collectScans(driver, 1).size(), 1u);  // MD streaming
  const auto second = driver.singleScan();        // stops MD, laser on again, GD
  ASSERT_TRUE(second.ok()) << second.reason();
  EXPECT_TRUE(sameRanges(second.value().ranges_m, expected));
  EXPECT_GT(second.value().stamp, first.value().stamp);
  EXPECT_EQ(countOf(emulator->receivedCommands(), "GD0044072501"), 2u);
}

TEST(HokuyoDriverTest, UnwrapsTheSensorsTwentyFourBitMillisecondCounter) {
  HokuyoEmulatorSettings settings;
  settings.clock_start_ms = (1u << 24) - 400;  // wraps 0.4 s after the emulator starts
  auto emulator = startEmulator(settings);
  HokuyoDriver driver(quickSettings(emulator->devicePath()));
  const auto scans = collectScans(driver, 10);
  ASSERT_EQ(scans.size(), 10u) << driver.health().last_error;
  EXPECT_LT(emulator->clockMs(), settings.clock_start_ms);  // the counter did wrap
  expectStampsFollowTheSensorClock(scans, 0.1);
}

TEST(HokuyoDriverTest, WithoutTimeSyncStampsStillIncrease) {
  HokuyoEmulatorSettings settings;
  settings.protocol.support_time_sync = false;
  auto emulator = startEmulator(settings);
  HokuyoDriver driver(quickSettings(emulator->devicePath()));
  const auto identity = driver.connect();
  ASSERT_TRUE(identity.ok()) << identity.reason();
  EXPECT_FALSE(identity.value().time_synchronised);
  const auto scans = collectScans(driver, 5);
  ASSERT_EQ(scans.size(), 5u);
  for (std::size_t i = 1; i < scans.size(); ++i) {
    EXPECT_GT(scans[i].stamp, scans[i - 1].stamp);
  }
}

TEST(HokuyoDriverTest, StopsTheLaserWithQtOnShutdownAndResetsWhenAsked) {
  auto emulator = startEmulator({});
  {
    HokuyoDriver driver(quickSettings(emulator->devicePath()));
    ASSERT_EQ(collectScans(driver, 1).size(), 1u);
  }
  EXPECT_EQ(emulator->receivedCommands().back(), "QT");
  {
    HokuyoSettings settings = quickSettings(emulator->devicePath());
    settings.reset_on_stop = true;
    HokuyoDriver driver(settings);
    ASSERT_EQ(collectScans(driver, 1).size(), 1u);
  }
  const auto commands = emulator->receivedCommands();
  ASSERT_GE(commands.size(), 2u);
  EXPECT_EQ(commands[commands.size() - 2], "QT");
  EXPECT_EQ(commands.back(), "RS");
}

TEST(HokuyoDriverTest, ASettingOutsideTheDevicesStepsFailsTheStartUp) {
  auto emulator = startEmulator({});
  HokuyoSettings settings = quickSettings(emulator->devicePath());
  settings.start_step = 10;  // below AMIN 44
  HokuyoDriver driver(settings);
  const auto identity = driver.connect();
  ASSERT_FALSE(identity.ok());
  EXPECT_NE(identity.reason().find("outside AMIN"), std::string::npos) << identity.reason();
}

TEST(HokuyoDriverTest, InvalidSettingsThrow) {
  HokuyoSettings settings = quickSettings("/dev/ttyACM0");
  settings.cluster = 0;
  EXPECT_THROW(HokuyoDriver{settings}, std::invalid_argument);
  settings = quickSettings("");
  EXPECT_THROW(HokuyoDriver{settings}, std::invalid_argument);
  settings = quickSettings("/dev/ttyACM0");
  settings.start_step = 500;
  settings.end_step = 400;
  EXPECT_THROW(HokuyoDriver{settings}, std::invalid_argument);
  settings = quickSettings("/dev/ttyACM0");
  settings.reconnect_backoff_max = 1ms;
  EXPECT_THROW(HokuyoDriver{settings}, std::invalid_argument);
}

TEST(HokuyoDriverTest, SettingsLoadFromConfig) {
  const Config config = Config::loadString(
      "device: /dev/ttyACM1\nbaud: 19200\ncluster: 2\nread_timeout_s: 0.5\n"
      "zero_range: no_return\nprobe_bauds: [38400]\n",
      "hokuyo.yaml");
  const HokuyoSettings settings = loadHokuyoSettings(config);
  config.checkNoUnknownKeys();
  EXPECT_EQ(settings.device, "/dev/ttyACM1");
  EXPECT_EQ(settings.baud, 19200);
  EXPECT_EQ(settings.cluster, 2);
  EXPECT_EQ(settings.read_timeout, 500ms);
  EXPECT_EQ(settings.zero_range, scip::ZeroRange::kNoReturn);
  EXPECT_EQ(settings.probe_bauds, std::vector<int>{38400});
  EXPECT_THROW(loadHokuyoSettings(Config::loadString("device: x\ncluster: 0\n", "h.yaml")),
               ConfigError);
}

}  // namespace
}  // namespace mrslam::drivers
