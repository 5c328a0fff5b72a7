// mrslam_imu end to end against mrslam_gx1_emulator, both as separate processes.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_data.hpp"

#if defined(MRSLAM_IMU_PROGRAM) && defined(MRSLAM_GX1_EMULATOR_PROGRAM)
#include "gx1_test_fixture.hpp"
#include "mrslam/tools/child_process.hpp"

namespace mrslam::drivers {
namespace {

using gx1_test::waitUntil;
using tools::ChildProcess;
namespace fs = std::filesystem;

constexpr double kRadiansPerDegree = M_PI / 180.0;

std::vector<std::string> linesOf(const std::string& path) {
  std::ifstream file(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(file, line);) {
    if (!line.empty()) {
      lines.push_back(line);
    }
  }
  return lines;
}

std::vector<nlohmann::json> jsonLinesOf(const std::string& path) {
  std::vector<nlohmann::json> objects;
  for (const std::string& line : linesOf(path)) {
    if (line.front() == '{') {
      objects.push_back(nlohmann::json::parse(line));
    }
  }
  return objects;
}

struct Gx1ToolTest : ::testing::Test {
  fs::path folder = test::scratchFolder("tool");
  std::string link = (folder / "ttyGX1").string();

  std::unique_ptr<ChildProcess> startEmulator(std::vector<std::string> options) {
    options.insert(options.begin(), {MRSLAM_GX1_EMULATOR_PROGRAM, link});
    auto emulator = std::make_unique<ChildProcess>(options, (folder / "emulator.log").string());
    EXPECT_TRUE(waitUntil([&] { return fs::exists(link); }, 500)) << "no " << link;
    return emulator;
  }

  std::unique_ptr<ChildProcess> startImu(std::vector<std::string> options) {
    options.insert(options.begin(), {MRSLAM_IMU_PROGRAM, link});
    return std::make_unique<ChildProcess>(options, (folder / "imu.log").string());
  }

  // The tool's whole output must be one line with the reason.
  void expectOneLineFailure(ChildProcess& imu, const std::string& reason) {
    const std::optional<int> code = imu.waitFor(30.0);
    ASSERT_TRUE(code) << "mrslam_imu did not end";
    EXPECT_EQ(*code, 2);
    const auto lines = linesOf(imu.logPath());
    ASSERT_EQ(lines.size(), 1u) << tools::tailOfFile(imu.logPath(), 10);
    EXPECT_EQ(lines[0].rfind("mrslam_imu: " + link + ": ", 0), 0u) << lines[0];
    EXPECT_NE(lines[0].find(reason), std::string::npos) << lines[0];
  }
};

TEST_F(Gx1ToolTest, PrintsGainsAndJsonSamplesInRobotUnits) {
  auto emulator = startEmulator({"--roll", "10", "--pitch", "-5", "--yaw", "30", "--rate-z", "20"});
  auto imu = startImu({"--json", "--count", "3", "--mode", "continuous"});
  const std::optional<int> code = imu->waitFor(30.0);
  ASSERT_TRUE(code) << "mrslam_imu did not end";
  ASSERT_EQ(*code, 0) << tools::tailOfFile(imu->logPath(), 10);

  const auto objects = jsonLinesOf(imu->logPath());
  ASSERT_EQ(objects.size(), 4u) << tools::tailOfFile(imu->logPath(), 10);
  EXPECT_EQ(objects[0]["gains"]["gyro"], 10000);
  EXPECT_EQ(objects[0]["gains"]["accel"], 8500);
  EXPECT_EQ(objects[0]["gains"]["mag"], 2000);
  std::uint64_t previous_ticks = 0;
  for (std::size_t i = 1; i < objects.size(); ++i) {
    const nlohmann::json& sample = objects[i];
    // Device axes z down → robot axes z up: pitch and yaw change sign, as do y and z.
    EXPECT_NEAR(sample["roll"].get<double>(), 10.0 * kRadiansPerDegree, 1e-4);
    EXPECT_NEAR(sample["pitch"].get<double>(), 5.0 * kRadiansPerDegree, 1e-4);
    EXPECT_NEAR(sample["yaw"].get<double>(), -30.0 * kRadiansPerDegree, 1e-4);
    ASSERT_EQ(sample["accel"].size(), 3u);
    EXPECT_NEAR(sample["accel"][0].get<double>(), 0.0, 1e-9);
    EXPECT_NEAR(sample["accel"][2].get<double>(), 9.80665, 0.01);  // m/s², level at rest
    ASSERT_EQ(sample["rate"].size(), 3u);
    EXPECT_NEAR(sample["rate"][2].get<double>(), -20.0 * kRadiansPerDegree, 1e-3);  // rad/s
    const auto ticks = sample["ticks"].get<std::uint64_t>();
    EXPECT_GE(ticks, previous_ticks);  // the device timer, unwrapped: never back
    previous_ticks = ticks;
  }
  EXPECT_EQ(emulator->stop(5.0), 0);  // the emulator ends cleanly on SIGINT
}

TEST_F(Gx1ToolTest, ADeviceThatDoesNotAnswerGivesOneLineAndANonZeroExit) {
  auto emulator = startEmulator({"--silent"});
  auto imu = startImu({"--count", "3"});
  expectOneLineFailure(*imu, "no answer to the EEPROM read of the gyro gain");
}

TEST_F(Gx1ToolTest, ADeviceThatAnswersGarbageGivesOneLineAndANonZeroExit) {
  auto emulator = startEmulator({"--garbage"});
  auto imu = startImu({"--json", "--count", "3"});
  expectOneLineFailure(*imu, "garbage in reply to the EEPROM read");
}

TEST_F(Gx1ToolTest, AMissingDeviceGivesOneLineAndANonZeroExit) {
  auto imu = startImu({"--count", "1"});
  expectOneLineFailure(*imu, "cannot open");
}

TEST_F(Gx1ToolTest, ADeviceThatVanishesGivesANonZeroExitWithTheReason) {
  auto emulator = startEmulator({});
  auto imu = startImu({"--json", "--count", "1000000", "--timeout", "5"});
  ASSERT_TRUE(waitUntil([&] { return jsonLinesOf(imu->logPath()).size() >= 3; }, 1000))
      << tools::tailOfFile(imu->logPath(), 10);
  emulator->stop(5.0);  // the pty goes with the process
  const std::optional<int> code = imu->waitFor(30.0);
  ASSERT_TRUE(code) << "mrslam_imu did not end";
  EXPECT_EQ(*code, 2);
  const auto lines = linesOf(imu->logPath());
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.back().rfind("mrslam_imu: " + link + ": device lost", 0), 0u) << lines.back();
}

}  // namespace
}  // namespace mrslam::drivers

#else

TEST(Gx1ToolTest, NeedsTheImuAndEmulatorPrograms) {
  GTEST_SKIP() << "mrslam_imu or mrslam_gx1_emulator is not part of this build";
}

#endif
