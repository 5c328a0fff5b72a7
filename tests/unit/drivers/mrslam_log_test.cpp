#include "mrslam/drivers/mrslam_log.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <limits>

#include "mrslam/drivers/simulator.hpp"
#include "test_data.hpp"

namespace mrslam::drivers {
namespace {

using ::testing::HasSubstr;

bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof(a)) == 0;
}
bool sameBits(float a, float b) {
  return std::memcmp(&a, &b, sizeof(a)) == 0;
}

std::vector<Sample> awkwardSamples() {
  LaserScan scan;
  scan.stamp = Stamp{-1234567890123};
  scan.angle_min_rad = -M_PI / 3;
  scan.angle_increment_rad = 0.1 / 3.0;
  scan.range_min_m = 0.02;
  scan.range_max_m = 5.6;
  scan.ranges_m = {1.0f / 3.0f, LaserScan::kNoReturn, LaserScan::kInvalid,
                   std::numeric_limits<float>::denorm_min(), 123456.789f};
  scan.logged_pose = SE2(1e-300, -7.25, 3.0);
  ImuSample imu;
  imu.stamp = Stamp{42};
  imu.yaw_rad = -0.1;
  imu.has_orientation = false;
  imu.angular_rate_rad_s = Eigen::Vector3d(1e-9, -2.5, 0.3);
  imu.acceleration_g = Eigen::Vector3d(0.0, -0.0, 1.0000000000000002);
  return {WheelTicks{Stamp{1}, -9223372036854775807LL, 12345}, imu,
          OdometryPose{Stamp{2}, SE2(0.1, 0.2, -3.14159)}, scan};
}

void expectSameSample(const Sample& a, const Sample& b) {
  ASSERT_EQ(a.index(), b.index());
  EXPECT_EQ(stampOf(a), stampOf(b));
  EXPECT_EQ(formatSampleLine(a), formatSampleLine(b));
  if (const auto* scan_a = std::get_if<LaserScan>(&a)) {
    const auto& scan_b = std::get<LaserScan>(b);
    ASSERT_EQ(scan_a->ranges_m.size(), scan_b.ranges_m.size());
    for (std::size_t i = 0; i < scan_a->ranges_m.size(); ++i) {
      EXPECT_TRUE(sameBits(scan_a->ranges_m[i], scan_b.ranges_m[i])) << i;
    }
    EXPECT_TRUE(sameBits(scan_a->angle_increment_rad, scan_b.angle_increment_rad));
    ASSERT_EQ(scan_a->logged_pose.has_value(), scan_b.logged_pose.has_value());
    if (scan_a->logged_pose) {
      EXPECT_TRUE(sameBits(scan_a->logged_pose->x(), scan_b.logged_pose->x()));
    }
  }
}

class MrslamLogTest : public ::testing::TestWithParam<const char*> {};

TEST_P(MrslamLogTest, EverySampleReadsBackBitForBit) {
  const std::string path = (test::scratchFolder("log") / GetParam()).string();
  const std::vector<Sample> samples = awkwardSamples();
  {
    MrslamLogWriter writer(path, "robot7");
    for (const Sample& sample : samples) {
      writer.write(sample);
    }
    writer.close();
  }
  EXPECT_EQ(detectLogFormat(path), LogFormat::kMrslam);
  MrslamLogReader reader({path, MalformedPolicy::kStop});
  for (const Sample& expected : samples) {
    const std::optional<Sample> sample = reader.next();
    ASSERT_TRUE(sample.has_value());
    expectSameSample(expected, *sample);
  }
  EXPECT_FALSE(reader.next().has_value());
  EXPECT_EQ(reader.robotId(), "robot7");
  EXPECT_EQ(reader.counters().samples, samples.size());
  EXPECT_EQ(reader.counters().out_of_order_stamps, 2u);  // 42 → 1, and 2 → -1234567890123
}

INSTANTIATE_TEST_SUITE_P(PlainAndGzip, MrslamLogTest, ::testing::Values("run.log", "run.log.gz"));

TEST(MrslamLogReaderTest, RecordedSimulatorRunReplaysIdentically) {
  drivers::SimulatorSettings settings;
  settings.duration_s = 5.0;
  const std::string path = (test::scratchFolder("sim") / "sim.log").string();
  std::vector<std::string> original;
  {
    RecordingSource source(
        std::make_unique<Simulator>(settings, DiffDriveParams{}, SensorMounting{}), path, "robot1");
    while (auto sample = source.next()) {
      original.push_back(formatSampleLine(*sample));
    }
  }
  MrslamLogReader reader({path, MalformedPolicy::kStop});
  std::vector<std::string> replayed;
  while (auto sample = reader.next()) {
    replayed.push_back(formatSampleLine(*sample));
  }
  EXPECT_EQ(replayed, original);
  EXPECT_GT(original.size(), 500u);
}

std::string writeLog(const std::string& body) {
  const std::string path = (test::scratchFolder("bad") / "bad.log").string();
  std::ofstream(path) << kMrslamLogMagic << "\n" << body;
  return path;
}

TEST(MrslamLogReaderTest, MalformedLinesAreCountedOrStopTheRun) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"TICKS 1 2\n", "the line ends before the right count"},
      {"TICKS 1 2 x\n", "the right count is not an integer: 'x'"},
      {"ODOM 1 0 nan 0\n", "y is not finite"},
      {"LASER 1 0 0.1 0.02 4 3 1 2\n", "the beam count 3 disagrees"},
      {"LASER 1 0 0.1 0.02 4 2 1 2 7\n", "unexpected fields at the end"},
      {"LASER 1 0 0.1 0.02 4 1 1 POSE 1 2\n", "unexpected fields at the end"},
      {"GPS 1 2 3\n", "unknown record type 'GPS'"},
      {"IMU 1 0 0 0 1 0 0 0 0 0\n", "the line ends before an acceleration"},
  };
  for (const auto& [line, message] : cases) {
    const std::string path = writeLog("TICKS 0 0 0\n" + line + "TICKS 5 1 1\n");
    MrslamLogReader skipping({path, MalformedPolicy::kSkip});
    int good = 0;
    while (skipping.next()) {
      ++good;
    }
    EXPECT_EQ(good, 2) << line;
    EXPECT_EQ(skipping.counters().malformed_records, 1u) << line;
    MrslamLogReader stopping({path, MalformedPolicy::kStop});
    ASSERT_TRUE(stopping.next().has_value());
    try {
      stopping.next();
      ADD_FAILURE() << "no error for " << line;
    } catch (const LogFormatError& error) {
      EXPECT_THAT(error.what(), HasSubstr("bad.log:3: " + message)) << line;
    }
  }
}

// Found by the fuzz target: a line of only white space once read past an empty field list.
TEST(MrslamLogReaderTest, LinesOfOnlyWhiteSpaceAreBlank) {
  const std::string path = writeLog("TICKS 0 0 0\n \n\t\t\n \r\nTICKS 5 1 1\n");
  MrslamLogReader reader({path, MalformedPolicy::kStop});
  int good = 0;
  while (reader.next()) {
    ++good;
  }
  EXPECT_EQ(good, 2);
  EXPECT_EQ(reader.counters().malformed_records, 0u);
}

TEST(MrslamLogReaderTest, AFileWithoutTheHeaderIsRefused) {
  const std::string path = (test::scratchFolder("nohead") / "x.log").string();
  std::ofstream(path) << "TICKS 0 0 0\n";
  EXPECT_THROW(MrslamLogReader({path, MalformedPolicy::kSkip}), std::runtime_error);
}

}  // namespace
}  // namespace mrslam::drivers
