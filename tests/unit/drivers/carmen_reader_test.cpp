#include "mrslam/drivers/carmen_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "test_data.hpp"

namespace mrslam::drivers {
namespace {

using ::testing::HasSubstr;

std::string writeFile(const std::filesystem::path& path, const std::string& content) {
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

CarmenSettings settingsFor(const std::string& path,
                           CarmenOdometry odometry = CarmenOdometry::kFlaserOdom,
                           MalformedPolicy policy = MalformedPolicy::kSkip) {
  CarmenSettings settings;
  settings.path = path;
  settings.odometry = odometry;
  settings.malformed_policy = policy;
  return settings;
}

std::vector<Sample> readAll(SampleSource& source) {
  std::vector<Sample> samples;
  while (std::optional<Sample> sample = source.next()) {
    samples.push_back(std::move(*sample));
  }
  return samples;
}

template <typename T>
std::vector<T> only(const std::vector<Sample>& samples) {
  std::vector<T> result;
  for (const Sample& sample : samples) {
    if (const T* value = std::get_if<T>(&sample)) {
      result.push_back(*value);
    }
  }
  return result;
}

Stamp seconds(const char* text) {
  return *Stamp::parseSeconds(text);
}

void expectPose(const SE2& pose, double x, double y, double theta) {
  EXPECT_DOUBLE_EQ(pose.x(), x);
  EXPECT_DOUBLE_EQ(pose.y(), y);
  EXPECT_DOUBLE_EQ(pose.theta(), theta);
}

std::size_t countNoReturn(const std::vector<LaserScan>& scans) {
  std::size_t count = 0;
  for (const LaserScan& scan : scans) {
    count += static_cast<std::size_t>(
        std::count(scan.ranges_m.begin(), scan.ranges_m.end(), LaserScan::kNoReturn));
  }
  return count;
}

/// Largest hit, and checks every range is a hit in [range_min, max_range) or kNoReturn.
float longestHit(const std::vector<LaserScan>& scans, const CarmenSettings& settings) {
  float longest = 0.0f;
  for (const LaserScan& scan : scans) {
    for (const float range : scan.ranges_m) {
      EXPECT_FALSE(std::isnan(range));
      if (std::isfinite(range)) {
        EXPECT_GE(range, settings.range_min_m);
        EXPECT_LT(range, settings.max_range_m);
        longest = std::max(longest, range);
      }
    }
  }
  return longest;
}

/// In the default mode every scan comes right after the odometry of its own line.
void expectOdometryBeforeEachScan(const std::vector<Sample>& samples) {
  ASSERT_EQ(samples.size() % 2, 0u);
  for (std::size_t i = 0; i < samples.size(); i += 2) {
    const auto* odometry = std::get_if<OdometryPose>(&samples[i]);
    const auto* scan = std::get_if<LaserScan>(&samples[i + 1]);
    ASSERT_TRUE(odometry != nullptr && scan != nullptr) << "sample " << i;
    EXPECT_EQ(odometry->stamp, scan->stamp);
    ASSERT_TRUE(scan->logged_pose.has_value());
    // The corrected logs write the corrected pose into the odom fields too.
    EXPECT_EQ(odometry->T_odom_robot.x(), scan->logged_pose->x());
    EXPECT_EQ(odometry->T_odom_robot.y(), scan->logged_pose->y());
    EXPECT_EQ(odometry->T_odom_robot.theta(), scan->logged_pose->theta());
  }
}

// ---------------------------------------------------------------------------------------------
// The real logs (values read by hand from `zcat ... | grep -m1 FLASER`)

TEST(CarmenReaderTest, IntelLog) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/carmen-intel-corrected.log.gz");
  CarmenReader reader(settingsFor(test::sharedDataPath("logs/carmen-intel-corrected.log.gz")));
  const std::vector<Sample> samples = readAll(reader);
  expectOdometryBeforeEachScan(samples);
  const std::vector<LaserScan> scans = only<LaserScan>(samples);
  ASSERT_EQ(scans.size(), 910u);
  EXPECT_EQ(only<OdometryPose>(samples).size(), 910u);

  const LaserScan& first = scans.front();
  EXPECT_EQ(first.stamp, seconds("32.9068"));
  ASSERT_EQ(first.ranges_m.size(), 180u);
  EXPECT_DOUBLE_EQ(first.angle_min_rad, -M_PI / 2);
  EXPECT_DOUBLE_EQ(first.angle_increment_rad, M_PI / 180);
  EXPECT_FLOAT_EQ(first.ranges_m[0], 1.09f);
  EXPECT_FLOAT_EQ(first.ranges_m[1], 1.08f);
  EXPECT_FLOAT_EQ(first.ranges_m[89], 2.53f);
  EXPECT_FLOAT_EQ(first.ranges_m[179], 1.23f);
  expectPose(*first.logged_pose, 0.600266, -0.0320327, -0.354665);
  EXPECT_EQ(countNoReturn({first}), 15u);
  EXPECT_EQ(scans.back().stamp, seconds("2683.77"));
  expectPose(*scans.back().logged_pose, -0.596494, -0.101202, 0.0119294);

  // 81.83 m is the sentinel of this log: 4172 readings; the longest real one is 25.38 m.
  EXPECT_EQ(countNoReturn(scans), 4172u);
  EXPECT_FLOAT_EQ(longestHit(scans, reader.settings()), 25.38f);

  // Four scans are stamped before the one above them (e.g. 940.54 after 940.654).
  const SourceCounters counters = reader.counters();
  EXPECT_EQ(counters.out_of_order_stamps, 4u);
  EXPECT_EQ(counters.malformed_records, 0u);
  EXPECT_EQ(counters.samples, samples.size());
  EXPECT_EQ(reader.skipped_records(), 0u);
  EXPECT_EQ(reader.reanchor_odom_records(), 910u);
}

TEST(CarmenReaderTest, AcesLog) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/carmen-aces-corrected.log.gz");
  CarmenReader reader(settingsFor(test::sharedDataPath("logs/carmen-aces-corrected.log.gz")));
  const std::vector<Sample> samples = readAll(reader);
  expectOdometryBeforeEachScan(samples);
  const std::vector<LaserScan> scans = only<LaserScan>(samples);
  ASSERT_EQ(scans.size(), 440u);

  const LaserScan& first = scans.front();
  EXPECT_EQ(first.stamp, seconds("21.0199"));
  ASSERT_EQ(first.ranges_m.size(), 180u);
  EXPECT_FLOAT_EQ(first.ranges_m[0], 6.66f);
  EXPECT_FLOAT_EQ(first.ranges_m[2], 7.16f);
  EXPECT_FLOAT_EQ(first.ranges_m[89], 1.79f);
  EXPECT_FLOAT_EQ(first.ranges_m[179], 1.64f);
  expectPose(*first.logged_pose, 0.89706, -0.180771, -0.454003);
  EXPECT_EQ(countNoReturn({first}), 16u);
  EXPECT_EQ(scans.back().stamp, seconds("1339.08"));

  // This log clips at exactly 50 m (620 readings); the longest real reading is 49.91 m.
  EXPECT_EQ(countNoReturn(scans), 620u);
  EXPECT_FLOAT_EQ(longestHit(scans, reader.settings()), 49.91f);
  for (std::size_t i = 1; i < scans.size(); ++i) {
    EXPECT_GT(scans[i].stamp, scans[i - 1].stamp);
  }
  EXPECT_EQ(reader.counters().out_of_order_stamps, 0u);
  EXPECT_EQ(reader.counters().malformed_records, 0u);
  EXPECT_EQ(reader.reanchor_odom_records(), 440u);
}

TEST(CarmenReaderTest, CsailLogKeepsEqualStampsInFileOrder) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/carmen-csail-corrected.log.gz");
  CarmenReader reader(settingsFor(test::sharedDataPath("logs/carmen-csail-corrected.log.gz")));
  const std::vector<Sample> samples = readAll(reader);
  expectOdometryBeforeEachScan(samples);
  const std::vector<LaserScan> scans = only<LaserScan>(samples);
  ASSERT_EQ(scans.size(), 406u);

  // Stamps written as "1.13486e+09": 365 scans share 1134860000 s, 41 share 1134870000 s.
  const Stamp early = seconds("1134860000");
  const Stamp late = seconds("1134870000");
  EXPECT_EQ(std::count_if(scans.begin(), scans.end(), [&](auto& s) { return s.stamp == early; }),
            365);
  EXPECT_EQ(std::count_if(scans.begin(), scans.end(), [&](auto& s) { return s.stamp == late; }),
            41);
  EXPECT_EQ(reader.counters().out_of_order_stamps, 0u);

  // File order, read by hand: the first two scans and the last one.
  expectPose(*scans[0].logged_pose, 0.154, 0.068, 0.562729);
  expectPose(*scans[1].logged_pose, 0.348, 0.217, 1.34445);
  expectPose(*scans.back().logged_pose, -0.53, -0.093, 0.874611);

  const LaserScan& first = scans.front();
  ASSERT_EQ(first.ranges_m.size(), 361u);
  EXPECT_DOUBLE_EQ(first.angle_increment_rad, M_PI / 360);
  EXPECT_NEAR(first.beamAngle(360), M_PI / 2, 1e-12);
  EXPECT_EQ(first.ranges_m[0], LaserScan::kNoReturn);  // 81.91
  EXPECT_FLOAT_EQ(first.ranges_m[89], 6.21f);
  EXPECT_FLOAT_EQ(first.ranges_m[179], 6.05f);
  EXPECT_FLOAT_EQ(first.ranges_m[360], 2.12f);
  EXPECT_EQ(countNoReturn({first}), 39u);
  EXPECT_EQ(countNoReturn(scans), 3907u);  // 81.91 m is this log's sentinel
  EXPECT_FLOAT_EQ(longestHit(scans, reader.settings()), 35.12f);
  EXPECT_EQ(reader.counters().malformed_records, 0u);
}

TEST(CarmenReaderTest, IntelOdomLinesJumpBackInTime) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/carmen-intel-corrected.log.gz");
  const std::string path = test::sharedDataPath("logs/carmen-intel-corrected.log.gz");

  CarmenReader odom_lines(settingsFor(path, CarmenOdometry::kOdomLines));
  const std::vector<Sample> samples = readAll(odom_lines);
  EXPECT_EQ(only<LaserScan>(samples).size(), 910u);
  // 14541 ODOM lines, 910 of which re-anchor to a scan's pose and are left out.
  EXPECT_EQ(only<OdometryPose>(samples).size(), 13631u);
  EXPECT_EQ(odom_lines.reanchor_odom_records(), 910u);
  EXPECT_EQ(odom_lines.counters().out_of_order_stamps, 629u);

  CarmenReader both(settingsFor(path, CarmenOdometry::kBoth));
  const std::vector<Sample> all = readAll(both);
  EXPECT_EQ(only<LaserScan>(all).size(), 910u);
  EXPECT_EQ(only<OdometryPose>(all).size(), 13631u + 910u);
  EXPECT_EQ(both.counters().out_of_order_stamps, 629u);

  CarmenSettings with_reanchor = settingsFor(path, CarmenOdometry::kOdomLines);
  with_reanchor.emit_reanchor_odom = true;
  CarmenReader every_odom(with_reanchor);
  EXPECT_EQ(only<OdometryPose>(readAll(every_odom)).size(), 14541u);
}

// The 180-beam logs hold 1° steps from -90° to +89° (pi/n), not 180° / 179 (pi/(n-1)): with the
// corrected poses, consecutive scans taken during turns agree better so. (A sweep of the span
// over 178°..181° puts the best fit at 179°..179.5° for both logs.)
class CarmenReaderBeamAngleTest : public ::testing::TestWithParam<const char*> {};

TEST_P(CarmenReaderBeamAngleTest, ScansAgreeBestWithOneDegreeSteps) {
  const std::string relative = std::string("logs/") + GetParam();
  MRSLAM_REQUIRE_SHARED_DATA(relative);
  CarmenReader reader(settingsFor(test::sharedDataPath(relative)));
  const std::vector<LaserScan> scans = only<LaserScan>(readAll(reader));
  const auto points = [](const LaserScan& scan, double increment) {
    std::vector<Eigen::Vector2d> world;
    for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
      const double range = scan.ranges_m[i];
      if (std::isfinite(range) && range < 20.0) {
        const double angle = scan.angle_min_rad + static_cast<double>(i) * increment;
        world.push_back(*scan.logged_pose *
                        Eigen::Vector2d(range * std::cos(angle), range * std::sin(angle)));
      }
    }
    return world;
  };
  const auto median_gap = [](const std::vector<Eigen::Vector2d>& from,
                             const std::vector<Eigen::Vector2d>& to) {
    std::vector<double> gaps;
    for (const Eigen::Vector2d& p : from) {
      double best = INFINITY;
      for (const Eigen::Vector2d& q : to) {
        best = std::min(best, (p - q).squaredNorm());
      }
      gaps.push_back(std::sqrt(best));
    }
    std::nth_element(gaps.begin(), gaps.begin() + static_cast<long>(gaps.size() / 2), gaps.end());
    return gaps[gaps.size() / 2];
  };
  int pairs = 0;
  int one_degree_better = 0;
  double sum_one_degree = 0.0;
  double sum_other = 0.0;
  for (std::size_t i = 0; i + 1 < scans.size(); ++i) {
    const double turn =
        std::abs(wrapAngle(scans[i + 1].logged_pose->theta() - scans[i].logged_pose->theta()));
    if (turn < 10.0 * M_PI / 180.0) {
      continue;
    }
    const double a = median_gap(points(scans[i + 1], M_PI / 180), points(scans[i], M_PI / 180));
    const double b = median_gap(points(scans[i + 1], M_PI / 179), points(scans[i], M_PI / 179));
    ++pairs;
    one_degree_better += a < b ? 1 : 0;
    sum_one_degree += a;
    sum_other += b;
  }
  ASSERT_GE(pairs, 100);
  EXPECT_GT(one_degree_better, pairs / 2) << one_degree_better << " of " << pairs;
  EXPECT_LT(sum_one_degree, sum_other);
  EXPECT_DOUBLE_EQ(scans.front().angle_increment_rad, M_PI / 180);
}

INSTANTIATE_TEST_SUITE_P(Logs, CarmenReaderBeamAngleTest,
                         ::testing::Values("carmen-intel-corrected.log.gz",
                                           "carmen-aces-corrected.log.gz"),
                         [](const ::testing::TestParamInfo<const char*>& param_info) {
                           return std::string(param_info.param).substr(7, 4);
                         });

// ---------------------------------------------------------------------------------------------
// Small files

// FLASER with three beams: ranges, laser pose, odom pose, timestamp, host, logger timestamp.
std::string flaser(const std::string& ranges, const std::string& pose, const std::string& stamp) {
  return "FLASER 3 " + ranges + " " + pose + " 9.5 8.5 0.25 " + stamp + " host " + stamp + "\n";
}

std::string odom(const std::string& pose, const std::string& stamp) {
  return "ODOM " + pose + " 0.1 0 0 " + stamp + " host " + stamp + "\n";
}

TEST(CarmenReaderTest, ReadsFlaserAndOdomAndSkipsOtherRecords) {
  const auto folder = test::scratchFolder("log");
  const std::string path = writeFile(
      folder / "a.log",
      "# message formats defined: PARAM SYNC ODOM FLASER\n"
      "\n"
      "PARAM robot_frontlaser_offset 0.0 nohost 0\n" +
          odom("1 2 0.5", "10.0") + "RAWLASER1 0 -1.57 3.14 0.01 81.9 0.01 0 3 1 2 3 0 10 h 10\n" +
          flaser("1.5 2.5 3.5", "4 5 0.75", "10.25") + "NEFF 15\n" +
          "ROBOTLASER1 0 -1.5 3.1 0.01 80 0.1 0 0 0 0 0 0 0 0 0 0 0 10.3 h 10.3\n" +
          "SYNC 10.4 h 10.4\n" + odom("1.5 2 0.5", "10.5"));
  CarmenReader reader(settingsFor(path, CarmenOdometry::kBoth));
  const std::vector<Sample> samples = readAll(reader);
  ASSERT_EQ(samples.size(), 4u);
  const auto& first = std::get<OdometryPose>(samples[0]);
  EXPECT_EQ(first.stamp, seconds("10"));
  expectPose(first.T_odom_robot, 1, 2, 0.5);
  const auto& flaser_odom = std::get<OdometryPose>(samples[1]);
  EXPECT_EQ(flaser_odom.stamp, seconds("10.25"));
  expectPose(flaser_odom.T_odom_robot, 9.5, 8.5, 0.25);
  const auto& scan = std::get<LaserScan>(samples[2]);
  EXPECT_EQ(scan.stamp, seconds("10.25"));
  EXPECT_EQ(scan.ranges_m, (std::vector<float>{1.5f, 2.5f, 3.5f}));
  EXPECT_DOUBLE_EQ(scan.angle_increment_rad, M_PI / 2);  // 3 beams over 180°, both ends
  expectPose(*scan.logged_pose, 4, 5, 0.75);
  EXPECT_EQ(std::get<OdometryPose>(samples[3]).stamp, seconds("10.5"));

  EXPECT_EQ(reader.skipped_records(), 3u);  // RAWLASER1, ROBOTLASER1, SYNC
  EXPECT_EQ(reader.counters().malformed_records, 0u);
  EXPECT_EQ(reader.counters().samples, 4u);
  EXPECT_EQ(reader.describe(), "carmen log " + path);
}

// ODOM with its own translational velocity tv.
std::string odomMoving(const std::string& pose, const std::string& tv, const std::string& stamp) {
  return "ODOM " + pose + " " + tv + " 0 0 " + stamp + " host " + stamp + "\n";
}

TEST(CarmenReaderTest, AStepAheadWhileReversingIsMirroredAndCarriedOn) {
  const auto folder = test::scratchFolder("log");
  // Heading +90°: ahead is +y. Reversing at -0.3 m/s, the second step still runs 0.1 m ahead
  // (a robot that integrated |v|); the third, driving ahead again, is kept as it is.
  const std::string path = writeFile(
      folder / "a.log",
      odomMoving("1 2 1.5707963267948966", "0.3", "10.0") +
          odomMoving("1 2.1 1.5707963267948966", "-0.3", "10.5") +
          "FLASER 3 1 2 3 1 2.1 1.5707963267948966 1 2.1 1.5707963267948966 10.6 host 10.6\n" +
          odomMoving("1 2.3 1.5707963267948966", "0.3", "11.0"));
  CarmenReader reader(settingsFor(path, CarmenOdometry::kBoth));
  const std::vector<OdometryPose> poses = only<OdometryPose>(readAll(reader));
  ASSERT_EQ(poses.size(), 4u);
  EXPECT_NEAR(poses[0].T_odom_robot.y(), 2.0, 1e-9);
  EXPECT_NEAR(poses[1].T_odom_robot.x(), 1.0, 1e-9);
  EXPECT_NEAR(poses[1].T_odom_robot.y(), 1.9, 1e-9);  // 0.1 m back, not ahead
  EXPECT_NEAR(poses[2].T_odom_robot.y(), 1.9, 1e-9);  // the FLASER's odometry, carried along
  EXPECT_NEAR(poses[3].T_odom_robot.y(), 2.1, 1e-9);  // 0.2 m ahead of the corrected pose
  EXPECT_NEAR(poses[3].T_odom_robot.theta(), M_PI / 2, 1e-9);
  EXPECT_EQ(reader.reversed_odometry_steps(), 1u);
}

TEST(CarmenReaderTest, RawFr079ReversesWithoutEverMovingBack) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/freiburg-fr079.clf.gz");
  CarmenReader reader(
      settingsFor(test::sharedDataPath("logs/freiburg-fr079.clf.gz"), CarmenOdometry::kOdomLines));
  const std::vector<OdometryPose> poses = only<OdometryPose>(readAll(reader));
  // As logged, 315 steps run ahead while tv is below -0.05 m/s, and none moves back.
  EXPECT_EQ(reader.reversed_odometry_steps(), 315u);
  std::size_t backward_steps = 0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    const SE2 step = poses[i - 1].T_odom_robot.inverse() * poses[i].T_odom_robot;
    backward_steps += step.x() < -CarmenReader::kReversingStepM ? 1 : 0;
  }
  EXPECT_EQ(backward_steps, 315u);
}

TEST(CarmenReaderTest, RawIntelAndAcesNeverReverse) {
  for (const char* log : {"logs/freiburg-intel.clf.gz", "logs/freiburg-aces.clf.gz"}) {
    MRSLAM_REQUIRE_SHARED_DATA(log);
    CarmenReader reader(settingsFor(test::sharedDataPath(log), CarmenOdometry::kOdomLines));
    readAll(reader);
    EXPECT_EQ(reader.reversed_odometry_steps(), 0u) << log;
  }
}

TEST(CarmenReaderTest, OdometrySettingChoosesTheSource) {
  const auto folder = test::scratchFolder("log");
  const std::string path =
      writeFile(folder / "a.log", odom("1 2 0.5", "10.0") + flaser("1 2 3", "4 5 0.75", "10.25") +
                                      odom("1.5 2 0.5", "10.5"));
  const auto kinds = [&](CarmenOdometry odometry) {
    CarmenReader reader(settingsFor(path, odometry));
    std::string result;
    for (const Sample& sample : readAll(reader)) {
      result += std::holds_alternative<LaserScan>(sample) ? "S" : "O";
    }
    return result;
  };
  EXPECT_EQ(kinds(CarmenOdometry::kFlaserOdom), "OS");
  EXPECT_EQ(kinds(CarmenOdometry::kOdomLines), "OSO");
  EXPECT_EQ(kinds(CarmenOdometry::kBoth), "OOSO");
}

TEST(CarmenReaderTest, ReanchorOdomLineIsLeftOutUnlessAsked) {
  const auto folder = test::scratchFolder("log");
  const std::string path =
      writeFile(folder / "a.log", flaser("1 2 3", "4 5 0.75", "10.25") + odom("4 5 0.75", "0") +
                                      odom("4.1 5 0.75", "10.5") + odom("4 5 0.75", "10.75"));
  CarmenReader reader(settingsFor(path, CarmenOdometry::kBoth));
  std::vector<OdometryPose> poses = only<OdometryPose>(readAll(reader));
  ASSERT_EQ(poses.size(), 3u);  // the FLASER's, then the last two ODOM lines
  EXPECT_EQ(poses[1].stamp, seconds("10.5"));
  EXPECT_EQ(poses[2].stamp, seconds("10.75"));  // same pose, but not right after the FLASER
  EXPECT_EQ(reader.reanchor_odom_records(), 1u);
  EXPECT_EQ(reader.counters().out_of_order_stamps, 0u);

  CarmenSettings settings = settingsFor(path, CarmenOdometry::kBoth);
  settings.emit_reanchor_odom = true;
  CarmenReader emitting(settings);
  poses = only<OdometryPose>(readAll(emitting));
  ASSERT_EQ(poses.size(), 4u);
  EXPECT_EQ(poses[1].stamp, Stamp{0});
  EXPECT_EQ(emitting.counters().out_of_order_stamps, 1u);  // 0 after 10.25
}

TEST(CarmenReaderTest, CountsBackwardStampsAndKeepsFileOrder) {
  const auto folder = test::scratchFolder("log");
  const std::string path = writeFile(
      folder / "a.log", flaser("1 1 1", "1 0 0", "10") + flaser("2 2 2", "2 0 0", "12") +
                            flaser("3 3 3", "3 0 0", "11") + flaser("4 4 4", "4 0 0", "11") +
                            flaser("5 5 5", "5 0 0", "13"));
  CarmenReader reader(settingsFor(path));
  const std::vector<LaserScan> scans = only<LaserScan>(readAll(reader));
  ASSERT_EQ(scans.size(), 5u);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    EXPECT_EQ(scans[i].logged_pose->x(), static_cast<double>(i + 1));
  }
  EXPECT_EQ(scans[2].stamp, seconds("11"));
  EXPECT_EQ(scans[3].stamp, seconds("11"));
  EXPECT_EQ(reader.counters().out_of_order_stamps, 1u);  // 11 after 12; equal stamps are fine
}

TEST(CarmenReaderTest, ReadsStampsExactlyInDecimalAndExponentForm) {
  const auto folder = test::scratchFolder("log");
  const std::string path = writeFile(
      folder / "a.log", odom("0 0 0", "1.13486e+09") + odom("0 0 0", "1134863807.658747") +
                            odom("0 0 0", "2.5E1") + odom("0 0 0", "1.65576e-153"));
  CarmenReader reader(settingsFor(path, CarmenOdometry::kOdomLines));
  const std::vector<OdometryPose> poses = only<OdometryPose>(readAll(reader));
  ASSERT_EQ(poses.size(), 4u);
  EXPECT_EQ(poses[0].stamp.ns, 1134860000000000000);
  EXPECT_EQ(poses[1].stamp.ns, 1134863807658747000);
  EXPECT_EQ(poses[2].stamp.ns, 25000000000);
  EXPECT_EQ(poses[3].stamp.ns, 0);
}

TEST(CarmenReaderTest, RangeLimits) {
  const auto folder = test::scratchFolder("log");
  const std::string path =
      writeFile(folder / "a.log", "FLASER 6 0 0.005 0.01 49.99 50 81.83 1 2 3 1 2 3 7 h 7\n");
  CarmenReader reader(settingsFor(path));
  const LaserScan scan = only<LaserScan>(readAll(reader)).at(0);
  ASSERT_EQ(scan.ranges_m.size(), 6u);
  EXPECT_TRUE(std::isnan(scan.ranges_m[0]));  // below range_min: an error reading
  EXPECT_TRUE(std::isnan(scan.ranges_m[1]));
  EXPECT_FLOAT_EQ(scan.ranges_m[2], 0.01f);
  EXPECT_FLOAT_EQ(scan.ranges_m[3], 49.99f);
  EXPECT_EQ(scan.ranges_m[4], LaserScan::kNoReturn);
  EXPECT_EQ(scan.ranges_m[5], LaserScan::kNoReturn);
  EXPECT_DOUBLE_EQ(scan.range_max_m, 50.0);
  EXPECT_DOUBLE_EQ(scan.angle_increment_rad, M_PI / 6);  // an even count lacks the +90° beam

  CarmenSettings settings = settingsFor(path);
  settings.max_range_m = 3.0;
  settings.range_min_m = 0.001;
  CarmenReader short_range(settings);
  const LaserScan limited = only<LaserScan>(readAll(short_range)).at(0);
  EXPECT_TRUE(std::isnan(limited.ranges_m[0]));
  EXPECT_FLOAT_EQ(limited.ranges_m[1], 0.005f);
  EXPECT_EQ(limited.ranges_m[3], LaserScan::kNoReturn);
}

TEST(CarmenReaderTest, BeamIncrementFollowsCarmen) {
  EXPECT_DOUBLE_EQ(CarmenReader::beamIncrementRad(180), M_PI / 180);
  EXPECT_DOUBLE_EQ(CarmenReader::beamIncrementRad(181), M_PI / 180);
  EXPECT_DOUBLE_EQ(CarmenReader::beamIncrementRad(360), M_PI / 360);
  EXPECT_DOUBLE_EQ(CarmenReader::beamIncrementRad(361), M_PI / 360);
  EXPECT_DOUBLE_EQ(CarmenReader::beamIncrementRad(1), 0.0);
}

TEST(CarmenReaderTest, RejectsBadSettingsAndMissingFiles) {
  const auto folder = test::scratchFolder("log");
  const std::string path = writeFile(folder / "a.log", odom("0 0 0", "1"));
  CarmenSettings settings = settingsFor(path);
  settings.max_range_m = 0.005;
  EXPECT_THROW(CarmenReader{settings}, std::invalid_argument);
  settings = settingsFor(path);
  settings.range_min_m = -1.0;
  EXPECT_THROW(CarmenReader{settings}, std::invalid_argument);

  const std::string missing = (folder / "missing.log.gz").string();
  try {
    CarmenReader reader(settingsFor(missing));
    FAIL() << "opened a missing file";
  } catch (const std::runtime_error& error) {
    EXPECT_THAT(error.what(), HasSubstr(missing + ": cannot open"));
  }
}

// ---------------------------------------------------------------------------------------------
// Malformed lines: each kind, under both policies

struct Corruption {
  const char* name;
  const char* line;
  const char* kind;
  const char* message;
};

void PrintTo(const Corruption& corruption, std::ostream* out) {
  *out << corruption.name;
}

class CarmenReaderMalformedTest : public ::testing::TestWithParam<Corruption> {
 protected:
  /// Line 1 (FLASER) and line 3 (ODOM) are good, line 2 is corrupted.
  std::string writeLog() {
    const auto folder = test::scratchFolder("log");
    return writeFile(folder / "bad.log", flaser("1 2 3", "4 5 0.75", "10") + GetParam().line +
                                             "\n" + odom("1 2 0.5", "11"));
  }
};

TEST_P(CarmenReaderMalformedTest, SkipCountsTheLineAndReadsTheGoodOnes) {
  CarmenReader reader(settingsFor(writeLog(), CarmenOdometry::kBoth, MalformedPolicy::kSkip));
  const std::vector<Sample> samples = readAll(reader);
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_TRUE(std::holds_alternative<LaserScan>(samples[1]));
  EXPECT_EQ(stampOf(samples[2]), seconds("11"));
  EXPECT_EQ(reader.counters().malformed_records, 1u);
  EXPECT_EQ(reader.counters().samples, 3u);
  EXPECT_EQ(reader.skipped_records(), 0u);
  EXPECT_EQ(reader.malformedByKind(), (std::map<std::string, std::uint64_t>{{GetParam().kind, 1}}));
}

TEST_P(CarmenReaderMalformedTest, StopThrowsTheFileLineAndProblem) {
  const std::string path = writeLog();
  CarmenReader reader(settingsFor(path, CarmenOdometry::kBoth, MalformedPolicy::kStop));
  ASSERT_TRUE(reader.next().has_value());  // line 1: odometry
  ASSERT_TRUE(reader.next().has_value());  // line 1: scan
  try {
    reader.next();
    FAIL() << "no error for line 2";
  } catch (const LogFormatError& error) {
    EXPECT_EQ(std::string(error.what()), path + ":2: " + GetParam().message);
    EXPECT_EQ(error.line(), 2u);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Kinds, CarmenReaderMalformedTest,
    ::testing::Values(
        Corruption{"FlaserAlone", "FLASER", "field count",
                   "FLASER needs at least 2 fields, found 1"},
        Corruption{"CountDisagrees", "FLASER 3 1 2 4 5 0.7 4 5 0.7 10 h 10", "field count",
                   "FLASER with 3 beams needs 14 fields, found 13"},
        Corruption{"CountTooLarge", "FLASER 180 1 2 3 4 5 0.7 4 5 0.7 10 h 10", "field count",
                   "FLASER with 180 beams needs 191 fields, found 14"},
        Corruption{"CountNotInteger", "FLASER 3.0 1 2 3 4 5 0.7 4 5 0.7 10 h 10", "beam count",
                   "field 2: '3.0' is not a beam count (a positive integer)"},
        Corruption{"CountNegative", "FLASER -3 1 2 3 4 5 0.7 4 5 0.7 10 h 10", "beam count",
                   "field 2: '-3' is not a beam count (a positive integer)"},
        Corruption{"CountZero", "FLASER 0 4 5 0.7 4 5 0.7 10 h 10", "beam count",
                   "field 2: '0' is not a beam count (a positive integer)"},
        Corruption{"RangeNotNumber", "FLASER 3 1 2x 3 4 5 0.7 4 5 0.7 10 h 10", "not a number",
                   "field 4: '2x' is not a number"},
        Corruption{"RangeNan", "FLASER 3 nan 2 3 4 5 0.7 4 5 0.7 10 h 10", "not finite",
                   "field 3: 'nan' is not finite"},
        Corruption{"PoseInf", "FLASER 3 1 2 3 4 inf 0.7 4 5 0.7 10 h 10", "not finite",
                   "field 7: 'inf' is not finite"},
        Corruption{"RangeNegative", "FLASER 3 1 -2.5 3 4 5 0.7 4 5 0.7 10 h 10", "negative",
                   "field 4: '-2.5' is a negative range"},
        Corruption{"FlaserBadStamp", "FLASER 3 1 2 3 4 5 0.7 4 5 0.7 10.5.1 h 10", "bad stamp",
                   "field 12: '10.5.1' is not a time stamp"},
        Corruption{"FlaserBadLoggerStamp", "FLASER 3 1 2 3 4 5 0.7 4 5 0.7 10 h later",
                   "not a number", "field 14: 'later' is not a number"},
        Corruption{"OdomTooFewFields", "ODOM 1 2 0.5 0 0 10.5", "field count",
                   "ODOM needs 10 fields, found 7"},
        Corruption{"OdomNotNumber", "ODOM 1 two 0.5 0 0 0 10.5 h 10.5", "not a number",
                   "field 3: 'two' is not a number"},
        Corruption{"OdomNan", "ODOM 1 2 NaN 0 0 0 10.5 h 10.5", "not finite",
                   "field 4: 'NaN' is not finite"},
        Corruption{"OdomBadStamp", "ODOM 1 2 0.5 0 0 0 inf h 10.5", "bad stamp",
                   "field 8: 'inf' is not a time stamp"},
        Corruption{"NotAMessage", "3.25 1 2 3", "not a message",
                   "field 1: '3.25' is not a message name"}),
    [](const ::testing::TestParamInfo<Corruption>& param_info) {
      return std::string(param_info.param.name);
    });

}  // namespace
}  // namespace mrslam::drivers
