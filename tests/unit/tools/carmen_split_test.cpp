#include "mrslam/tools/carmen_split.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "mrslam/drivers/carmen_reader.hpp"
#include "test_data.hpp"

namespace mrslam::tools {
namespace {

int countScans(const std::string& path, std::optional<SE2>& first_pose) {
  drivers::CarmenSettings settings;
  settings.path = path;
  settings.malformed_policy = drivers::MalformedPolicy::kStop;
  drivers::CarmenReader reader(settings);
  int scans = 0;
  while (auto sample = reader.next()) {
    if (const auto* scan = std::get_if<LaserScan>(&*sample)) {
      if (scans++ == 0) {
        first_pose = scan->logged_pose;
      }
    }
  }
  return scans;
}

TEST(CarmenSplitTest, IntelLogSplitsIntoReplayableSegmentsWithTheirTruth) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/carmen-intel-corrected.log.gz");
  const auto folder = test::scratchFolder("split");
  SplitSettings settings;
  settings.segments = 3;
  const auto segments = splitCarmenLog(test::sharedDataPath("logs/carmen-intel-corrected.log.gz"),
                                       folder.string(), settings);
  ASSERT_EQ(segments.size(), 3u);
  int total = 0;
  for (const LogSegment& segment : segments) {
    std::optional<SE2> first_pose;
    const int scans = countScans(segment.path, first_pose);
    EXPECT_EQ(scans, segment.scan_count);
    ASSERT_TRUE(first_pose.has_value());
    EXPECT_DOUBLE_EQ(first_pose->x(), segment.T_log_origin.x());
    EXPECT_DOUBLE_EQ(first_pose->theta(), segment.T_log_origin.theta());
    total += scans;
  }
  EXPECT_EQ(total, 910);
  EXPECT_EQ(segments[1].first_scan, 303);
  EXPECT_EQ(segments[2].first_scan, 606);

  const std::string truth_path = (folder / "truth.json").string();
  writeSplitTruth(segments, {"a", "b", "c"}, truth_path);
  std::ifstream file(truth_path);
  const nlohmann::json truth = nlohmann::json::parse(file);
  EXPECT_EQ(truth["reference"], "a");
  EXPECT_DOUBLE_EQ(truth["robots"][0]["x"].get<double>(), 0.0);
  const SE2 expected = segments[0].T_log_origin.inverse() * segments[2].T_log_origin;
  EXPECT_NEAR(truth["robots"][2]["x"].get<double>(), expected.x(), 1e-12);
  EXPECT_NEAR(truth["robots"][2]["theta"].get<double>(), expected.theta(), 1e-12);
}

TEST(CarmenSplitTest, OverlapRepeatsScansAndTooFewScansIsAnError) {
  const auto folder = test::scratchFolder("small");
  const std::string log = (folder / "small.log").string();
  {
    std::ofstream file(log);
    file << "PARAM robot_front_laser_max 50.0 nohost 0\n";
    for (int i = 0; i < 6; ++i) {
      file << "FLASER 2 1.0 2.0 " << i << " 0 0 " << i << " 0 0 " << 10 + i << " nohost 0\n";
      file << "ODOM " << i << ".5 0 0 0 0 0 " << 10.5 + i << " nohost 0\n";
    }
  }
  SplitSettings settings;
  settings.segments = 2;
  settings.overlap_scans = 1;
  const auto segments = splitCarmenLog(log, (folder / "out").string(), settings);
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_EQ(segments[0].scan_count, 3);
  EXPECT_EQ(segments[1].first_scan, 2);
  EXPECT_EQ(segments[1].scan_count, 4);
  EXPECT_DOUBLE_EQ(segments[1].T_log_origin.x(), 2.0);
  std::ifstream second(segments[1].path);
  std::string first_line;
  std::getline(second, first_line);
  EXPECT_EQ(first_line, "PARAM robot_front_laser_max 50.0 nohost 0");
  settings.segments = 7;
  EXPECT_THROW(splitCarmenLog(log, (folder / "out2").string(), settings), std::runtime_error);
}

}  // namespace
}  // namespace mrslam::tools
