// The virtual robot (seed 002 §4): its walk along a skeleton, its scans, and merges of real crops
// from the hypotheses of its Monte Carlo localisation.

#include "mrslam/fusion/merge/virtual_robot.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "merge_crop_pairs.hpp"
#include "merge_test_maps.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

TEST(MergeVirtualRobotTest, WalkFollowsTheSkeletonAtItsStepWithHeadingsAlongIt) {
  cv::Mat skeleton = cv::Mat::zeros(20, 60, CV_8U);
  for (int x = 5; x < 55; ++x) {
    skeleton.at<std::uint8_t>(10, x) = 255;  // a corridor's centre line along +x
  }
  const std::vector<CellPose> walk = skeletonWalk(skeleton, Eigen::Vector2i(5, 10), 5, 10);
  ASSERT_EQ(walk.size(), 5u);
  for (std::size_t i = 0; i < walk.size(); ++i) {
    EXPECT_DOUBLE_EQ(walk[i].cell.x(), 5.0 + 10.0 * i);
    EXPECT_DOUBLE_EQ(walk[i].cell.y(), 10.0);
    EXPECT_NEAR(walk[i].heading_rad, 0.0, 1e-12);
  }
  // From the other end, the walk heads the other way; it stops where the skeleton ends.
  const std::vector<CellPose> back = skeletonWalk(skeleton, Eigen::Vector2i(54, 10), 10, 10);
  ASSERT_EQ(back.size(), 5u);
  EXPECT_NEAR(std::abs(back[1].heading_rad), M_PI, 1e-12);
}

TEST(MergeVirtualRobotTest, ScanOfABoxRoomEndsOnItsWalls) {
  GridGeometry geometry;
  geometry.width = 41;
  geometry.height = 41;
  GridMap room(geometry, GridMap::kFree);
  for (int i = 0; i < 41; ++i) {
    room.at(i, 0) = room.at(i, 40) = room.at(0, i) = room.at(40, i) = GridMap::kOccupied;
  }
  VirtualRobotSettings settings;
  settings.beams = 8;
  const CellPose centre{Eigen::Vector2d(20.0, 20.0), M_PI / 2};
  const std::vector<Eigen::Vector2d> scan = virtualScan(room, centre, settings);
  ASSERT_EQ(scan.size(), 8u);
  // Beam 0 looks along the heading (+y in the map): 20 cells ahead, in the robot frame's x.
  EXPECT_NEAR(scan[0].x(), 20.0, 0.5);
  EXPECT_NEAR(scan[0].y(), 0.0, 1e-9);
  // Beam 1 (45°) meets a wall at the room's corner diagonal.
  EXPECT_NEAR(scan[1].norm(), 20.0 * std::sqrt(2.0), 0.75);
  // A scan into unknown space returns nothing.
  GridMap unknown(geometry, GridMap::kUnknown);
  unknown.at(20, 20) = GridMap::kFree;
  EXPECT_TRUE(virtualScan(unknown, centre, settings).empty());
}

TEST(MergeVirtualRobotTest, MergesTurnedAndShiftedCropsOfARealMap) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  const GridMap source = merge_test::loadMap(test::sharedDataPath("maps/freiburg-intel.pgm"));
  std::mt19937 random(11);
  int accepted_right = 0;
  int found_truth = 0;
  constexpr int kCases = 8;
  for (int i = 0; i < kCases; ++i) {
    const merge_test::KnownCase known = merge_test::randomCase(source, 300, 0.6, 0.8, random);
    ASSERT_GT(known.overlap, 0.0);
    VirtualRobotMerger merger;
    for (const GridTransform& hypothesis : merger.hypotheses(known.from, known.to)) {
      const merge_test::PoseError error = merge_test::poseError(hypothesis, known);
      if (error.translation_cells <= 6.0 && error.rotation_rad <= 3.0 * M_PI / 180.0) {
        ++found_truth;
        break;
      }
    }
    const MergeResult result = merger.merge(known.from, known.to);
    EXPECT_EQ(result.method, "virtual");
    if (result.accepted) {
      EXPECT_TRUE(merge_test::isSuccess(merge_test::poseError(result.T_to_from, known)))
          << "case " << i << ": a wrong merge accepted";
      accepted_right += merge_test::isSuccess(merge_test::poseError(result.T_to_from, known));
    }
  }
  // Seeded: measured 13 of 20 such cases at 40-80 % overlap, none accepted wrong.
  std::cout << "truth among the hypotheses in " << found_truth << " of " << kCases
            << " cases, merged right in " << accepted_right << "\n";
  EXPECT_GE(found_truth, 4) << "the truth is among the hypotheses";
  EXPECT_GE(accepted_right, 4);
}

TEST(MergeVirtualRobotTest, RefusesMapsOfDifferentBuildings) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-aces.pgm");
  const GridMap intel = merge_test::loadMap(test::sharedDataPath("maps/freiburg-intel.pgm"));
  const GridMap aces = merge_test::loadMap(test::sharedDataPath("maps/freiburg-aces.pgm"));
  std::mt19937 random(5);
  const merge_test::KnownCase a = merge_test::randomCase(intel, 300, 0.6, 0.8, random);
  const merge_test::KnownCase b = merge_test::randomCase(aces, 300, 0.6, 0.8, random);
  VirtualRobotMerger merger;
  const MergeResult result = merger.merge(a.from, b.to);
  EXPECT_FALSE(result.accepted) << "V " << result.verification;
  EXPECT_FALSE(result.reason.empty());
}

// Two wrong merges the virtual robot's hypotheses passed the seed acceptance with, before ψ was
// checked: case 118 of `mrslam_merge_cases --seed 8` (ACES at 40 % overlap, accepted turned 180°
// at V 0.975) and case 10 of `--seed 42` (Carpin's robot 0 at 50 %, accepted turned 92° at V
// 0.981). Their ψ over the overlap is 1.15 and 2.06 cells; 758 right merges of the virtual robot
// on seeds 1-8 lie at 0.93 cells or less.
const merge_test::CropPair kAcesTurnedCase{
    "freiburg-aces.pgm",
    118,
    {{357, 504}, 225, -2.214505476047608, {8, 23}, {12, 15}},
    {{490, 358}, 285, -2.1951161543931055, {17, 20}, {12, 25}}};
const merge_test::CropPair kRobot0TurnedCase{
    "carpin-robot0_cast.txt",
    10,
    {{335, -40}, 202, 2.9243160301177262, {23, 26}, {4, 1}},
    {{318, 132}, 304, -1.955910906785824, {4, 17}, {16, 9}}};

TEST(MergeVirtualRobotTest, PsiOverTheOverlapRefusesWrongMergesTheAcceptancePassed) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-aces.pgm");
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  for (const merge_test::CropPair& pair : {kAcesTurnedCase, kRobot0TurnedCase}) {
    const MergeCase merge_case = merge_test::cut(pair);
    VirtualRobotSettings unchecked;
    unchecked.max_overlap_psi = 1000.0;
    const MergeResult passed = VirtualRobotMerger(unchecked).merge(merge_case.a, merge_case.b);
    ASSERT_TRUE(passed.accepted) << pair.map << ": " << passed.reason;
    EXPECT_FALSE(isCorrect(caseError(merge_case, passed.T_to_from))) << pair.map;
    const MergeResult checked = VirtualRobotMerger().merge(merge_case.a, merge_case.b);
    EXPECT_FALSE(checked.accepted) << pair.map;
    EXPECT_EQ(checked.refusal, MergeRefusal::kDissimilarity) << pair.map;
    EXPECT_THAT(checked.reason, testing::HasSubstr("ψ over the overlap")) << pair.map;
    EXPECT_THAT(checked.reason, testing::HasSubstr("is above 1")) << pair.map;
    EXPECT_EQ(checked.method, "virtual");
  }
}

TEST(MergeVirtualRobotTest, SettingsAreReadFromTheVirtualSectionWithinTheirRanges) {
  const Config section = Config::loadString(
      "virtual: {walks: 3, particles: 500, max_overlap_psi: 0.5, seed: 4}\n", "merge.yaml");
  const VirtualRobotSettings read = loadVirtualRobotSettings(section.section("virtual"));
  EXPECT_EQ(read.walks, 3);
  EXPECT_EQ(read.particles, 500);
  EXPECT_DOUBLE_EQ(read.max_overlap_psi, 0.5);
  EXPECT_EQ(read.seed, 4u);
  EXPECT_DOUBLE_EQ(loadVirtualRobotSettings(Config::loadString("", "m.yaml")).max_overlap_psi,
                   VirtualRobotSettings{}.max_overlap_psi);
  EXPECT_THROW(
      loadVirtualRobotSettings(
          Config::loadString("virtual: {max_overlap_psi: -1}\n", "m.yaml").section("virtual")),
      ConfigError);
  EXPECT_THROW(loadVirtualRobotSettings(
                   Config::loadString("virtual: {particles: 5}\n", "m.yaml").section("virtual")),
               ConfigError);
}

}  // namespace
}  // namespace mrslam::fusion
