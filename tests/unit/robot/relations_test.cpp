#include "mrslam/robot/relations.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "test_data.hpp"

namespace mrslam::robot {
namespace {

Stamp at(double seconds) {
  return Stamp::fromSeconds(seconds);
}

// A robot driving a circle: a pose every second.
std::vector<StampedPose> circle(std::size_t count) {
  std::vector<StampedPose> poses;
  for (std::size_t i = 0; i < count; ++i) {
    const double angle = 0.1 * static_cast<double>(i);
    poses.push_back({at(1000.0 + static_cast<double>(i)),
                     SE2(5.0 * std::cos(angle), 5.0 * std::sin(angle), angle + M_PI / 2)});
  }
  return poses;
}

Relation relationOf(const std::vector<StampedPose>& truth, std::size_t from, std::size_t to) {
  return {truth[from].stamp, truth[to].stamp, truth[from].pose.inverse() * truth[to].pose};
}

TEST(RelationsTest, AFileReadsToItsRelationsAndABadLineIsNamed) {
  const std::string path = (test::scratchFolder("relations") / "r.relations").string();
  std::ofstream(path) << "# t1 t2 x y z roll pitch yaw\n"
                         "976052905.167303 976052911.885496 -0.056990 -0.128430 0 0 0 -1.682210\n"
                         "\n"
                         "976052896.784509 976052905.167303 -0.153130 -0.051420 0 0 0 -2.405850\n";
  const std::vector<Relation> relations = readRelations(path);
  ASSERT_EQ(relations.size(), 2u);
  EXPECT_EQ(relations[0].from.ns, 976052905167303000);
  EXPECT_EQ(relations[0].to.ns, 976052911885496000);
  EXPECT_NEAR(relations[0].T_from_to.x(), -0.056990, 1e-12);
  EXPECT_NEAR(relations[0].T_from_to.y(), -0.128430, 1e-12);
  EXPECT_NEAR(relations[1].T_from_to.theta(), -2.405850, 1e-12);

  const std::string bad = (test::scratchFolder("relations") / "bad.relations").string();
  std::ofstream(bad) << "1.0 2.0 0 0 0 0 0 0\n1.0 2.0 0 0 0 0\n";
  try {
    readRelations(bad);
    FAIL() << "no error";
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()), bad + ":2: not a relation (t1 t2 x y z roll pitch yaw)");
  }
  std::ofstream(bad) << "1.0 x 0 0 0 0 0 0\n";
  EXPECT_THROW(readRelations(bad), std::runtime_error);
  EXPECT_THROW(readRelations(bad + ".missing"), std::runtime_error);
}

TEST(RelationsTest, TheTrueTrajectoryHasNoErrorInAnyFrame) {
  const std::vector<StampedPose> truth = circle(100);
  std::vector<Relation> relations;
  for (std::size_t i = 0; i + 5 < truth.size(); i += 3) {
    relations.push_back(relationOf(truth, i, i + 5));
  }
  relations.push_back(relationOf(truth, 2, 90));
  // The same trajectory seen from another map frame, in another order.
  std::vector<StampedPose> moved = truth;
  const SE2 T_map_world(3.0, -7.0, 2.0);
  for (StampedPose& pose : moved) {
    pose.pose = T_map_world * pose.pose;
  }
  std::reverse(moved.begin(), moved.end());
  const RelationReport report = evaluateRelations(moved, relations);
  EXPECT_EQ(report.all.count, relations.size());
  EXPECT_EQ(report.unmatched, 0u);
  EXPECT_NEAR(report.all.translation_mean_m, 0.0, 1e-9);
  EXPECT_NEAR(report.all.rotation_mean_deg, 0.0, 1e-9);
}

TEST(RelationsTest, AnErrorIsMeasuredInTheFirstScansFrameAndSplitByTimeApart) {
  const std::vector<StampedPose> truth = circle(100);
  // The estimate of scan 10 is 0.1 m off along its own x and turned 1°; scan 80 is 0.3 m off.
  std::vector<StampedPose> estimate = truth;
  estimate[10].pose = estimate[10].pose * SE2(0.1, 0.0, M_PI / 180.0);
  estimate[80].pose = estimate[80].pose * SE2(0.0, 0.3, 0.0);
  const std::vector<Relation> relations = {relationOf(truth, 10, 11), relationOf(truth, 0, 80),
                                           relationOf(truth, 20, 21)};
  const RelationReport report = evaluateRelations(estimate, relations);
  ASSERT_EQ(report.all.count, 3u);
  ASSERT_EQ(report.near.count, 2u);
  ASSERT_EQ(report.far.count, 1u);
  // Scan 11 seen from the shifted and turned scan 10: the error of T_10_11.
  const SE2 T_10_11 = truth[10].pose.inverse() * truth[11].pose;
  const SE2 error_near = T_10_11.inverse() * SE2(0.1, 0.0, M_PI / 180.0).inverse() * T_10_11;
  EXPECT_NEAR(report.near.translation_mean_m, error_near.translation().norm() / 2.0, 1e-9);
  EXPECT_NEAR(report.near.rotation_mean_deg, 0.5, 1e-9);
  EXPECT_NEAR(report.near.translation_sigma_m, error_near.translation().norm() / 2.0, 1e-9);
  EXPECT_NEAR(report.far.translation_mean_m, 0.3, 1e-9);
  EXPECT_NEAR(report.far.rotation_mean_deg, 0.0, 1e-9);
  EXPECT_NEAR(report.all.rotation_mean_deg, 1.0 / 3.0, 1e-9);
}

TEST(RelationsTest, ARelationWhoseScanTheTrajectoryLacksIsCountedNotScored) {
  const std::vector<StampedPose> truth = circle(10);
  std::vector<Relation> relations = {relationOf(truth, 1, 2)};
  relations.push_back({at(1000.5), truth[3].stamp, SE2()});  // between two poses
  relations.push_back({truth[4].stamp, at(2000.0), SE2()});  // after the trajectory
  Relation close = relationOf(truth, 5, 6);
  close.to.ns += 500000;  // 0.5 ms off: within the stamp tolerance
  relations.push_back(close);
  const RelationReport report = evaluateRelations(truth, relations);
  EXPECT_EQ(report.unmatched, 2u);
  EXPECT_EQ(report.all.count, 2u);
  EXPECT_NEAR(report.all.translation_mean_m, 0.0, 1e-9);
}

}  // namespace
}  // namespace mrslam::robot
