#include "mrslam/robot/trajectory_io.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "test_data.hpp"

namespace mrslam::robot {
namespace {

TEST(TrajectoryIoTest, WrittenTrajectoriesReadBackToTheNanosecond) {
  const std::string path = (test::scratchFolder("tum") / "t.tum").string();
  std::vector<TrajectoryPoint> points(2);
  points[0].stamp = Stamp::fromNanoseconds(1700000000123456789);
  points[0].T_map_robot = SE2(1.5, -2.25, 3.0);
  points[1].stamp = Stamp::fromNanoseconds(1700000000223456789);
  points[1].T_map_robot = SE2(-0.5, 0.25, -2.0);
  writeTumTrajectory(points, path);
  const std::vector<StampedPose> read = readTumTrajectory(path);
  ASSERT_EQ(read.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(read[i].stamp.ns, points[i].stamp.ns);
    EXPECT_NEAR(read[i].pose.x(), points[i].T_map_robot.x(), 1e-9);
    EXPECT_NEAR(read[i].pose.y(), points[i].T_map_robot.y(), 1e-9);
    EXPECT_NEAR(read[i].pose.theta(), points[i].T_map_robot.theta(), 1e-8);
  }
}

TEST(TrajectoryIoTest, ALineThatIsNoPoseIsNamedByFileAndLine) {
  const std::string path = (test::scratchFolder("tum") / "bad.tum").string();
  std::ofstream(path) << "# comment\n1.0 0 0 0 0 0 0 1\n2.0 0 0 0 nan-ish\n";
  try {
    readTumTrajectory(path);
    FAIL() << "no error";
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()), path + ":3: not a TUM pose (timestamp x y z qx qy qz qw)");
  }
  EXPECT_THROW(readTumTrajectory(path + ".missing"), std::runtime_error);
}

}  // namespace
}  // namespace mrslam::robot
