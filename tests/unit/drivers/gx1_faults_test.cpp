// The 3DM-GX1 driver under faults injected by the emulator over real ptys: every fault is
// counted, no corrupt sample comes out, and a lost device is found again.

#include <gtest/gtest.h>

#include <climits>
#include <tuple>

#include "gx1_test_fixture.hpp"
#include "test_data.hpp"

namespace mrslam::drivers {
namespace {

using namespace gx1_test;

class Gx1FaultTest : public ::testing::TestWithParam<std::tuple<Gx1Mode, Gx1Fault>> {};

// How many of the driver's counters a fault must move.
std::uint64_t faultCount(const Gx1Health& health, Gx1Fault fault, Gx1Mode mode) {
  switch (fault) {
    case Gx1Fault::kBadChecksum:
    case Gx1Fault::kGarbageReply:
      return health.parser.bad_checksums;
    case Gx1Fault::kTruncated:
      // Polled: the reply stays incomplete until the time-out. Streaming: the next frame
      // follows at once and the mixed candidate fails its checksum.
      return mode == Gx1Mode::kPolled ? health.parser.truncated_frames
                                      : health.parser.bad_checksums;
    case Gx1Fault::kStrayBytes:
      return health.parser.garbage_bytes;
  }
  return 0;
}

TEST_P(Gx1FaultTest, FaultsAreCountedAndNoCorruptSampleComesOut) {
  const auto [mode, fault] = GetParam();
  Gx1Emulator emulator(emulatorSettings(), [] { return fixedState(); });
  emulator.start();
  Gx1Driver driver(driverSettings(emulator.devicePath(), mode, gx1::kEulerVectorsCommand));
  ASSERT_EQ(collect(driver, 2).size(), 2u) << driver.health().last_error;
  ASSERT_EQ(faultCount(driver.health(), fault, mode), 0u);

  emulator.injectFault(fault, 3);
  const auto samples = collect(driver, 10);
  ASSERT_EQ(samples.size(), 10u) << driver.health().last_error;
  for (const ImuSample& sample : samples) {
    expectSample(sample, expectedSample(fixedState(), gx1::kEulerVectorsCommand));
  }
  EXPECT_EQ(emulator.counters().faults_applied, 3u);
  const Gx1Health health = driver.health();
  EXPECT_GE(faultCount(health, fault, mode), 3u);
  EXPECT_EQ(health.disconnects, 0u) << health.last_loss;  // bad frames do not lose the device
  if (mode == Gx1Mode::kPolled && fault != Gx1Fault::kStrayBytes) {
    EXPECT_GE(health.timeouts, 3u);  // the spoiled replies were asked for again
  }
}

std::string faultTestName(const ::testing::TestParamInfo<std::tuple<Gx1Mode, Gx1Fault>>& info) {
  static const char* const kFaultNames[] = {"BadChecksum", "Truncated", "StrayBytes",
                                            "GarbageReply"};
  const std::string mode = std::get<0>(info.param) == Gx1Mode::kPolled ? "Polled" : "Continuous";
  return mode + kFaultNames[static_cast<int>(std::get<1>(info.param))];
}

INSTANTIATE_TEST_SUITE_P(
    EveryFault, Gx1FaultTest,
    ::testing::Combine(::testing::Values(Gx1Mode::kPolled, Gx1Mode::kContinuous),
                       ::testing::Values(Gx1Fault::kBadChecksum, Gx1Fault::kTruncated,
                                         Gx1Fault::kStrayBytes, Gx1Fault::kGarbageReply)),
    faultTestName);

TEST(Gx1RecoveryTest, AStalledDeviceIsLostAndFoundAgain) {
  Gx1Emulator emulator(emulatorSettings(), [] { return fixedState(); });
  emulator.start();
  Gx1Settings settings = driverSettings(emulator.devicePath(), Gx1Mode::kContinuous, 0x31);
  settings.read_timeout = 50ms;
  Gx1Driver driver(settings);
  ASSERT_EQ(collect(driver, 3).size(), 3u);

  emulator.setStalled(true);
  EXPECT_TRUE(pollUntil(driver, [&] { return driver.health().disconnects > 0; }));
  EXPECT_GE(driver.health().timeouts, 3u);
  EXPECT_EQ(driver.health().last_loss.rfind("device silent", 0), 0u) << driver.health().last_loss;
  EXPECT_EQ(driver.state(), Gx1State::kDisconnected);

  emulator.setStalled(false);
  const auto samples = collect(driver, 3, 200);
  ASSERT_EQ(samples.size(), 3u) << driver.health().last_error;
  expectSample(samples.back(), expectedSample(fixedState(), 0x31));
  EXPECT_GE(driver.health().startups, 2u);
  EXPECT_EQ(emulator.counters().continuous_starts, driver.health().startups);
}

TEST(Gx1RecoveryTest, ACallerThatPollsLateFindsTheWaitingFramesWithoutATimeout) {
  Gx1Emulator emulator(emulatorSettings(), [] { return fixedState(); });
  emulator.start();
  Gx1Settings settings = driverSettings(emulator.devicePath(), Gx1Mode::kContinuous, 0x31);
  settings.read_timeout = 50ms;
  Gx1Driver driver(settings);
  ASSERT_EQ(collect(driver, 2).size(), 2u);
  std::this_thread::sleep_for(4 * settings.read_timeout);  // the caller is busy elsewhere
  const auto samples = collect(driver, 3);
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_EQ(driver.health().timeouts, 0u);
  EXPECT_EQ(driver.health().disconnects, 0u);
}

TEST(Gx1RecoveryTest, UnplugIsDetectedAndReplugRedoesTheStartUp) {
  const std::string link = (test::scratchFolder("pty") / "ttyGX1").string();
  Gx1Emulator emulator(emulatorSettings(link), [] { return fixedState(); });
  emulator.start();
  Gx1Driver driver(driverSettings(link, Gx1Mode::kPolled, 0x0C));
  ASSERT_EQ(collect(driver, 3).size(), 3u) << driver.health().last_error;
  ASSERT_EQ(emulator.counters().eeprom_reads, 3u);

  emulator.unplug();
  EXPECT_TRUE(pollUntil(driver, [&] { return driver.health().disconnects > 0; }));
  EXPECT_EQ(driver.health().last_loss.rfind("device lost", 0), 0u) << driver.health().last_loss;
  // While unplugged, start-ups fail and are retried.
  EXPECT_TRUE(pollUntil(driver, [&] { return driver.health().failed_startups > 0; }));
  EXPECT_FALSE(driver.poll(30ms));

  emulator.replug();
  const auto samples = collect(driver, 3, 200);
  ASSERT_EQ(samples.size(), 3u) << driver.health().last_error;
  expectSample(samples.back(), expectedSample(fixedState(), 0x0C), 5e-4);
  EXPECT_EQ(emulator.counters().eeprom_reads, 6u);  // the gains were read again
  EXPECT_EQ(driver.health().startups, 2u);
  EXPECT_EQ(driver.state(), Gx1State::kRunning);
}

TEST(Gx1StartUpTest, ADeviceThatDoesNotAnswerFailsWithAClearReason) {
  PtyPair pty;  // nobody on the master side
  Gx1Driver driver(driverSettings(pty.devicePath(), Gx1Mode::kPolled, 0x31));
  EXPECT_FALSE(driver.poll(50ms));
  const Gx1Health health = driver.health();
  EXPECT_EQ(health.failed_startups, 1u);
  EXPECT_EQ(health.startups, 0u);
  EXPECT_NE(health.last_error.find("no answer to the EEPROM read of the gyro gain (address 130)"),
            std::string::npos)
      << health.last_error;
}

TEST(Gx1StartUpTest, ADeviceThatAnswersGarbageFailsWithAClearReason) {
  Gx1Emulator emulator(emulatorSettings(), [] { return fixedState(); });
  emulator.injectFault(Gx1Fault::kGarbageReply, INT_MAX);
  emulator.start();
  Gx1Driver driver(driverSettings(emulator.devicePath(), Gx1Mode::kPolled, 0x31));
  EXPECT_FALSE(driver.poll(50ms));
  const Gx1Health health = driver.health();
  EXPECT_GE(health.failed_startups, 1u);
  EXPECT_NE(health.last_error.find("garbage in reply to the EEPROM read"), std::string::npos)
      << health.last_error;
  EXPECT_GT(health.parser.bad_checksums, 0u);
}

TEST(Gx1StartUpTest, AMissingDeviceFailsWithAClearReason) {
  Gx1Driver driver(driverSettings("/dev/nonexistent-gx1", Gx1Mode::kPolled, 0x31));
  EXPECT_FALSE(driver.poll(10ms));
  EXPECT_NE(driver.health().last_error.find("/dev/nonexistent-gx1: cannot open"), std::string::npos)
      << driver.health().last_error;
}

}  // namespace
}  // namespace mrslam::drivers
