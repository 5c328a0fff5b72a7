// The Hokuyo driver under injected faults: every bad reply is counted by kind and no corrupt
// scan comes out (the emulator sends one known pattern: every scan must equal it); a stalled,
// unplugged, silent or garbage-talking device is reported and, when it comes back, used again.

#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "hokuyo_test_support.hpp"

namespace mrslam::drivers {
namespace {

using namespace test;

class HokuyoFaultsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    emulator_ = std::make_unique<HokuyoEmulator>(HokuyoEmulatorSettings{}, linkPath());
    emulator_->start();
    driver_ = std::make_unique<HokuyoDriver>(quickSettings(emulator_->devicePath()));
    ASSERT_EQ(collectScans(*driver_, 2).size(), 2u) << driver_->health().last_error;
  }

  /// Collects scans until `done` holds for the counters (or the poll bound runs out).
  template <class Done>
  std::vector<LaserScan> scansUntil(Done done, int max_polls = 100) {
    std::vector<LaserScan> scans;
    for (int poll = 0; poll < max_polls && !done(driver_->health().counters); ++poll) {
      if (auto scan = driver_->poll(200ms)) {
        scans.push_back(std::move(*scan));
      }
    }
    return scans;
  }

  std::vector<float> expected() const {
    const HokuyoModel model = HokuyoModel::urg04lx();
    return expectedRanges(hokuyoRangePattern("ramp", model)(0), model.geometry);
  }

  std::unique_ptr<HokuyoEmulator> emulator_;
  std::unique_ptr<HokuyoDriver> driver_;
};

TEST_F(HokuyoFaultsTest, BadChecksumsAreCountedAndDropped) {
  emulator_->corruptChecksums(3);
  const auto scans = scansUntil([](const HokuyoCounters& c) { return c.scans >= 10; });
  const HokuyoCounters counters = driver_->health().counters;
  EXPECT_EQ(counters.checksum, 3u);
  EXPECT_EQ(counters.truncated + counters.status + counters.garbage, 0u);
  EXPECT_EQ(scansDifferingFrom(scans, expected()), 0);
}

TEST_F(HokuyoFaultsTest, TruncatedRepliesAreCountedAndDropped) {
  emulator_->truncateScans(2);
  const auto scans = scansUntil([](const HokuyoCounters& c) { return c.scans >= 8; });
  const HokuyoCounters counters = driver_->health().counters;
  EXPECT_EQ(counters.truncated, 2u);
  EXPECT_EQ(counters.checksum + counters.status + counters.garbage, 0u);
  EXPECT_EQ(scansDifferingFrom(scans, expected()), 0);
}

TEST_F(HokuyoFaultsTest, NoiseBeforeRepliesIsSkippedAndTheScansAfterItKept) {
  std::vector<LaserScan> scans;
  for (int burst = 0; burst < 3; ++burst) {
    emulator_->injectGarbage(60);
    const auto more = collectScans(*driver_, 2);
    scans.insert(scans.end(), more.begin(), more.end());
  }
  const HokuyoCounters counters = driver_->health().counters;
  EXPECT_GE(counters.garbage, 3u);
  EXPECT_EQ(counters.checksum + counters.truncated + counters.status, 0u);
  EXPECT_EQ(scans.size(), 6u);
  EXPECT_EQ(scansDifferingFrom(scans, expected()), 0);
}

TEST_F(HokuyoFaultsTest, ErrorStatusesAreCountedAndDropped) {
  emulator_->injectStatus("50", 2);
  const auto scans = scansUntil([](const HokuyoCounters& c) { return c.scans >= 6; });
  EXPECT_EQ(driver_->health().counters.status, 2u);
  EXPECT_NE(driver_->health().last_error.find("hardware fault"), std::string::npos);
  EXPECT_EQ(scansDifferingFrom(scans, expected()), 0);
}

TEST_F(HokuyoFaultsTest, ASeededMixOfFaultsNeverLetsACorruptScanThrough) {
  std::mt19937 random(42);
  HokuyoCounters injected;
  std::vector<LaserScan> scans;
  for (int round = 0; round < 12; ++round) {
    switch (random() % 4) {
      case 0:
        emulator_->corruptChecksums(1);
        ++injected.checksum;
        break;
      case 1:
        emulator_->truncateScans(1);
        ++injected.truncated;
        break;
      case 2:
        emulator_->injectStatus("62", 1);
        ++injected.status;
        break;
      default:
        emulator_->injectGarbage(1 + random() % 100);
        ++injected.garbage;
        break;
    }
    const auto more = collectScans(*driver_, 1);
    scans.insert(scans.end(), more.begin(), more.end());
  }
  const auto rest = scansUntil([&](const HokuyoCounters& c) {
    return c.checksum >= injected.checksum && c.truncated >= injected.truncated &&
           c.status >= injected.status;
  });
  scans.insert(scans.end(), rest.begin(), rest.end());
  const HokuyoCounters counters = driver_->health().counters;
  EXPECT_EQ(counters.checksum, injected.checksum);
  EXPECT_EQ(counters.truncated, injected.truncated);
  EXPECT_EQ(counters.status, injected.status);
  EXPECT_GE(counters.garbage, injected.garbage);
  EXPECT_GE(scans.size(), 12u);
  EXPECT_EQ(scansDifferingFrom(scans, expected()), 0);
}

TEST_F(HokuyoFaultsTest, AStalledDeviceIsReopenedAndScansResume) {
  emulator_->stall(1500ms);  // 15 scan periods; the driver gives up after 3
  const auto scans =
      scansUntil([](const HokuyoCounters& c) { return c.reconnects >= 1 && c.scans >= 4; }, 150);
  const HokuyoHealth health = driver_->health();
  EXPECT_GE(health.counters.timeout, 1u);
  EXPECT_GE(health.counters.reconnects, 1u);
  EXPECT_EQ(health.state, HokuyoState::kConnected);
  EXPECT_GE(scans.size(), 2u);
  EXPECT_EQ(scansDifferingFrom(scans, expected()), 0);
}

TEST_F(HokuyoFaultsTest, ADeviceSendingOnlyBadRepliesIsReopened) {
  // 3 periods × 10 = 3 s of bad replies make the driver reopen it; 45 bad ones last 4.5 s.
  emulator_->corruptChecksums(45);
  const auto scans =
      scansUntil([](const HokuyoCounters& c) { return c.reconnects >= 1 && c.scans >= 4; }, 150);
  const HokuyoCounters counters = driver_->health().counters;
  EXPECT_GE(counters.timeout, 1u);
  EXPECT_GE(counters.reconnects, 1u);
  EXPECT_GE(counters.checksum, 25u);
  EXPECT_EQ(scansDifferingFrom(scans, expected()), 0);
}

TEST_F(HokuyoFaultsTest, UnplugIsNoticedAndReplugRecoversWithinTwoAttempts) {
  emulator_->unplug();
  for (int poll = 0; poll < 50 && driver_->health().state != HokuyoState::kReconnecting; ++poll) {
    EXPECT_FALSE(driver_->poll(100ms).has_value());
  }
  ASSERT_EQ(driver_->health().state, HokuyoState::kReconnecting);
  EXPECT_GE(driver_->health().counters.disconnect, 1u);
  for (int poll = 0; poll < 3; ++poll) {  // still gone: attempts fail, nothing comes out
    EXPECT_FALSE(driver_->poll(100ms).has_value());
  }
  const std::uint64_t attempts_before = driver_->health().counters.connect_attempts;
  emulator_->replug();
  const auto scans = scansUntil([](const HokuyoCounters& c) { return c.scans >= 5; });
  const HokuyoHealth health = driver_->health();
  EXPECT_EQ(health.state, HokuyoState::kConnected);
  EXPECT_EQ(health.counters.reconnects, 1u);
  EXPECT_LE(health.counters.connect_attempts - attempts_before, 2u);
  EXPECT_EQ(scans.size(), 3u);
  EXPECT_EQ(scansDifferingFrom(scans, expected()), 0);
}

TEST(HokuyoDeadDeviceTest, ASilentDeviceFailsTheStartUpWithAClearReason) {
  PtyPair pty;  // nobody answers on the master side
  HokuyoDriver driver(quickSettings(pty.devicePath()));
  const auto identity = driver.connect();
  ASSERT_FALSE(identity.ok());
  EXPECT_NE(identity.reason().find("does not answer"), std::string::npos) << identity.reason();
  EXPECT_EQ(driver.health().counters.timeout, 1u);
  EXPECT_EQ(driver.health().state, HokuyoState::kReconnecting);
}

TEST(HokuyoDeadDeviceTest, ADeviceTalkingGarbageFailsTheStartUpWithAClearReason) {
  HokuyoEmulatorSettings settings;
  settings.device_baud = 9600;  // a rate the driver does not probe: every answer is noise
  HokuyoEmulator emulator(settings, linkPath());
  emulator.start();
  HokuyoDriver driver(quickSettings(emulator.devicePath()));
  const auto identity = driver.connect();
  ASSERT_FALSE(identity.ok());
  EXPECT_NE(identity.reason().find("garbage"), std::string::npos) << identity.reason();
  EXPECT_EQ(driver.health().counters.garbage, 1u);
}

TEST(HokuyoDeadDeviceTest, AMissingDeviceIsADisconnectNotACrash) {
  HokuyoDriver driver(quickSettings("/dev/nonexistent-mrslam-hokuyo"));
  const auto identity = driver.connect();
  ASSERT_FALSE(identity.ok());
  EXPECT_NE(identity.reason().find("cannot open"), std::string::npos) << identity.reason();
  EXPECT_FALSE(driver.poll(50ms).has_value());
  EXPECT_GE(driver.health().counters.disconnect, 1u);
  EXPECT_EQ(driver.health().state, HokuyoState::kReconnecting);
}

}  // namespace
}  // namespace mrslam::drivers
