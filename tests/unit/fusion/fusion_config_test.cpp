#include "mrslam/fusion/fusion_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "mrslam/fusion/global_map_builder.hpp"
#include "mrslam/fusion/team_graph.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

using ::testing::HasSubstr;

std::string writeConfig(const std::string& text) {
  const auto folder = test::scratchFolder("config");
  const std::string path = (folder / "fusion.yaml").string();
  std::ofstream(path) << text;
  return path;
}

std::string loadError(const std::string& text) {
  try {
    loadFusionConfig(writeConfig(text));
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "no error";
}

TEST(FusionConfigTest, LoadsEveryKey) {
  const FusionConfig config = loadFusionConfig(writeConfig(
      "fusion_id: f1\nreference_robot: a\nrobots:\n  - id: b\n    T_reference_robot: [1, 2, 0.5]\n"
      "expected_robots:\n  - id: a\n  - id: b\nexit_when_final: true\nmax_runtime_s: 60\n"
      "publish_period_s: 0.5\nwrite_period_s: 5\noutput:\n  folder: maps\n  write_robot_maps: "
      "false\n"
      "limits:\n  max_cells: 1000\n  allowed_robots:\n    - id: a\nglobal_map:\n  resolution_m: "
      "0.1\n"
      "dds:\n  domain_id: 7\n"));
  EXPECT_EQ(config.fusion_id, "f1");
  EXPECT_EQ(config.reference_robot, "a");
  ASSERT_EQ(config.fixed_transforms.count("b"), 1u);
  EXPECT_DOUBLE_EQ(config.fixed_transforms.at("b").y(), 2.0);
  EXPECT_EQ(config.expected_robots, (std::vector<std::string>{"a", "b"}));
  EXPECT_TRUE(config.exit_when_final);
  EXPECT_EQ(config.max_cells, 1000u);
  EXPECT_EQ(config.allowed_robots, (std::vector<std::string>{"a"}));
  EXPECT_DOUBLE_EQ(config.composer.resolution_m, 0.1);
  EXPECT_EQ(config.dds.domain_id, 7);
  EXPECT_FALSE(config.write_robot_maps);
  EXPECT_THAT(config.output_folder, HasSubstr("maps"));
  EXPECT_THAT(config.dds.profiles_file, HasSubstr("dds/profiles.xml"));
}

TEST(FusionConfigTest, TheParticipantIsOnUdpUnlessTheConfigSaysOtherwise) {
  // Shared memory may never deliver to a fusion agent restarted after a crash (Fast-DDS#5053).
  EXPECT_EQ(loadFusionConfig(writeConfig("dds:\n  domain_id: 7\n")).dds.participant_profile,
            "mrslam_participant_udp");
  EXPECT_EQ(loadFusionConfig(writeConfig("dds:\n  participant_profile: mrslam_participant\n"))
                .dds.participant_profile,
            "mrslam_participant");
}

TEST(FusionConfigTest, BadValuesNameFileLineAndKey) {
  EXPECT_THAT(loadError("publish_period_s: 0\n"),
              HasSubstr("fusion.yaml:1: publish_period_s: 0 is out of range"));
  EXPECT_THAT(loadError("reference: a\n"), HasSubstr("fusion.yaml:1: reference: unknown key"));
  EXPECT_THAT(loadError("reference_robot: a\nrobots:\n  - id: b\n    T_reference_robot: [1, 2]\n"),
              HasSubstr("fusion.yaml:4: robots[0].T_reference_robot: must have exactly 3 numbers"));
  EXPECT_THAT(loadError("robots:\n  - id: ../x\n"),
              HasSubstr("robots[0].id: '../x' is not a robot id"));
  EXPECT_THAT(loadError("exit_when_final: true\n"),
              HasSubstr("exit_when_final: needs expected_robots"));
  EXPECT_THAT(loadError("dds:\n  domain_id: 300\n"), HasSubstr("fusion.yaml:2: dds.domain_id"));
  EXPECT_THAT(loadError("merge:\n  threads: 0\n"),
              HasSubstr("fusion.yaml:2: merge.threads: 0 is out of range"));
}

TEST(FusionConfigTest, MergeThreadsAreReadWithTwoByDefault) {
  EXPECT_EQ(loadFusionConfig(writeConfig("merge:\n  method: none\n")).merge.threads, 2);
  EXPECT_EQ(loadFusionConfig(writeConfig("merge:\n  threads: 4\n")).merge.threads, 4);
}

TEST(FusionConfigTest, MergeConfirmationsAreReadWithTwoByDefault) {
  const MergeSchedulerSettings defaults =
      loadFusionConfig(writeConfig("merge:\n  method: none\n")).merge;
  EXPECT_EQ(defaults.confirmations, 2);
  EXPECT_DOUBLE_EQ(defaults.confirm_distance_m, 0.5);
  EXPECT_NEAR(defaults.confirm_angle_rad, 3.0 * M_PI / 180.0, 1e-12);
  const MergeSchedulerSettings set =
      loadFusionConfig(
          writeConfig(
              "merge:\n  confirmations: 3\n  confirm_distance_m: 0.2\n  confirm_angle_deg: 1.5\n"))
          .merge;
  EXPECT_EQ(set.confirmations, 3);
  EXPECT_DOUBLE_EQ(set.confirm_distance_m, 0.2);
  EXPECT_NEAR(set.confirm_angle_rad, 1.5 * M_PI / 180.0, 1e-12);
  EXPECT_THROW(loadFusionConfig(writeConfig("merge:\n  confirmations: 0\n")), std::exception);
}

TEST(FusionConfigTest, TheMergeMethodMakesItsMergerWithItsSettings) {
  const FusionConfig none = loadFusionConfig(writeConfig("merge:\n  method: none\n"));
  EXPECT_FALSE(none.make_merger);
  const FusionConfig seed =
      loadFusionConfig(writeConfig("merge:\n  method: seed\n  seed:\n    canny_low: 20\n"));
  ASSERT_TRUE(seed.make_merger);
  EXPECT_EQ(seed.make_merger()->name(), "seed");
  const FusionConfig chain = loadFusionConfig(writeConfig("merge:\n  method: chain\n"));
  ASSERT_TRUE(chain.make_merger);
  EXPECT_EQ(chain.make_merger()->name(), "chain");
  const FusionConfig feature = loadFusionConfig(writeConfig("merge:\n  method: feature\n"));
  ASSERT_TRUE(feature.make_merger);
  EXPECT_EQ(feature.make_merger()->name(), "feature");
  const FusionConfig walk =
      loadFusionConfig(writeConfig("merge:\n  method: psi_walk\n  psi_walk:\n    starts: 2\n"));
  ASSERT_TRUE(walk.make_merger);
  EXPECT_EQ(walk.make_merger()->name(), "psi_walk");
  EXPECT_THAT(loadError("merge:\n  method: carpin\n"),
              HasSubstr("fusion.yaml:2: merge.method: 'carpin' is not one of: chain, seed, "
                        "exhaustive, exhaustive_strict, psi_walk, virtual, feature, none"));
  EXPECT_THAT(loadError("merge:\n  method: seed\n  seed:\n    canny_low: -1\n"),
              HasSubstr("fusion.yaml:4: merge.seed.canny_low: -1 is out of range"));
  EXPECT_THAT(loadError("merge:\n  method: seed\n  seed:\n    bogus: 1\n"),
              HasSubstr("merge.seed.bogus: unknown key"));
}

TEST(GlobalMapBuilderTest, PlacesConfiguredRobotsAndReportsTheOthers) {
  TeamGraph graph;
  graph.addConfigured("b", "a", SE2(1.0, 0.0, 0.0));
  GridGeometry geometry;
  geometry.width = 4;
  geometry.height = 4;
  std::vector<RobotMap> maps(3);
  maps[0].robot_id = "a";
  maps[1].robot_id = "b";
  maps[2].robot_id = "c";
  for (auto& map : maps) {
    map.map = GridMap(geometry, 0);
  }
  const GlobalMapResult result =
      buildGlobalMap(maps, "a", graph.place("a", {"a", "b", "c"}), ComposerSettings{});
  EXPECT_EQ(result.reference_robot, "a");
  ASSERT_EQ(result.placements.size(), 3u);
  EXPECT_TRUE(result.placements[0].placed);
  EXPECT_EQ(result.placements[0].source, "reference");
  EXPECT_TRUE(result.placements[1].placed);
  EXPECT_EQ(result.placements[1].source, "config");
  EXPECT_DOUBLE_EQ(result.placements[1].T_reference_robot.x(), 1.0);
  EXPECT_FALSE(result.placements[2].placed);
  EXPECT_THAT(result.placements[2].source, HasSubstr("no verified transform"));
  // a and b, 0.2 m wide each, 1 m apart: the global map spans 1.2 m.
  EXPECT_EQ(result.map.geometry.width, 24);
  EXPECT_EQ(result.map.geometry.height, 4);
}

TEST(FusionConfigTest, ConfiguredTransformsNeedAReference) {
  EXPECT_THAT(loadError("robots:\n  - id: b\n"),
              HasSubstr("robots: configured transforms need reference_robot"));
}

}  // namespace
}  // namespace mrslam::fusion
