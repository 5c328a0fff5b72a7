#include "mrslam/tools/team_relations.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mrslam::tools {
namespace {

using robot::Relation;
using robot::StampedPose;

Stamp at(double seconds) {
  return Stamp::fromSeconds(seconds);
}

// The true pose of the scan at time t: along x at 1 m/s, y = 1 after t = 10, turning slowly.
SE2 truthAt(double t) {
  return SE2(t, t > 10.0 ? 1.0 : 0.0, 0.01 * t);
}

// A robot replaying scans [first, last] from its own origin: its poses in its own map frame.
std::vector<StampedPose> localTrajectory(int first, int last) {
  std::vector<StampedPose> poses;
  const SE2 T_world_origin = truthAt(first);
  for (int t = first; t <= last; ++t) {
    poses.push_back({at(t), T_world_origin.inverse() * truthAt(t)});
  }
  return poses;
}

Relation relation(double from, double to) {
  return {at(from), at(to), truthAt(from).inverse() * truthAt(to)};
}

struct Team {
  std::map<std::string, std::vector<StampedPose>> local{{"robot1", localTrajectory(1, 5)},
                                                        {"robot2", localTrajectory(11, 15)},
                                                        {"robot3", localTrajectory(21, 25)}};
  TeamPlacements placements;
};

// robot2 placed `offset` (in its own origin's frame) from its true placement; robot3 not placed.
Team teamWithOffset(const SE2& offset) {
  Team team;
  team.placements.reference = "robot1";
  team.placements.robots = {{"robot1", true, SE2(), ""},
                            {"robot2", true, truthAt(1).inverse() * truthAt(11) * offset, ""},
                            {"robot3", false, SE2(), ""}};
  return team;
}

const std::vector<Relation> kRelations = {
    relation(1, 2),    // within robot1
    relation(11, 13),  // within robot2
    relation(2, 12),   // across robot1 and robot2
    relation(4, 14),   // across
    relation(3, 22),   // robot3 is not placed: not scored
    relation(5, 99),   // no scan of the team at 99 s: no concern of the team's
};

TEST(TeamRelationsTest, TheRightPlacementScoresNoErrorAnywhere) {
  const Team team = teamWithOffset(SE2());
  const auto global = globalTrajectories(team.placements, team.local);
  ASSERT_EQ(global.size(), 2u);  // robot3 has no place in the reference frame
  const TeamRelationReport report = scoreTeam(global, team.local, kRelations);
  EXPECT_EQ(report.within.all.count, 2u);
  EXPECT_EQ(report.across.all.count, 2u);
  EXPECT_EQ(report.all.all.count, 4u);
  EXPECT_EQ(report.unscored, 1u);
  EXPECT_NEAR(report.all.all.translation_mean_m, 0.0, 1e-9);
  EXPECT_NEAR(report.all.all.rotation_mean_deg, 0.0, 1e-9);
  // The global trajectory lies on the truth seen from robot1's origin.
  const SE2 expected = truthAt(1).inverse() * truthAt(13);
  EXPECT_NEAR((global.at("robot2")[2].pose.inverse() * expected).translation().norm(), 0.0, 1e-9);
}

TEST(TeamRelationsTest, AMisplacedRobotShowsAcrossRobotsOnly) {
  const Team team = teamWithOffset(SE2(0.1, 0.0, 0.0));
  const TeamRelationReport report =
      scoreTeam(globalTrajectories(team.placements, team.local), team.local, kRelations);
  EXPECT_NEAR(report.within.all.translation_mean_m, 0.0, 1e-9);
  EXPECT_NEAR(report.across.all.translation_mean_m, 0.1, 1e-9);
  EXPECT_NEAR(report.all.all.translation_mean_m, 0.05, 1e-9);
  ASSERT_EQ(report.across_by_robot.count("robot2"), 1u);
  EXPECT_EQ(report.across_by_robot.at("robot2").count, 2u);
  EXPECT_NEAR(report.across_by_robot.at("robot2").translation_mean_m, 0.1, 1e-9);
}

TEST(TeamRelationsTest, AMisturnedRobotErrsByItsTurnAcross) {
  const Team team = teamWithOffset(SE2(0.0, 0.0, 2.0 * M_PI / 180.0));
  const TeamRelationReport report =
      scoreTeam(globalTrajectories(team.placements, team.local), team.local, kRelations);
  EXPECT_NEAR(report.within.all.rotation_mean_deg, 0.0, 1e-9);
  EXPECT_NEAR(report.across.all.rotation_mean_deg, 2.0, 1e-6);
  EXPECT_GT(report.across.all.translation_mean_m, 0.0);  // robot2's scans swing about its origin
}

}  // namespace
}  // namespace mrslam::tools
