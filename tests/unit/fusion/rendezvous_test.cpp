// Rendezvous between robots: the algebra of two mutual sightings, their pairing, and the check
// of a rendezvous hypothesis against two real maps.

#include "mrslam/fusion/rendezvous.hpp"

#include <gtest/gtest.h>

#include <random>

#include "map_window.hpp"
#include "merge_test_maps.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

/// The sighting a robot at T_world_observer makes of one at p_world_observed.
Sighting sightingOf(const std::string& observer, const std::string& observed,
                    const SE2& T_world_observer, const Eigen::Vector2d& p_world_observed,
                    const SE2& T_world_map, double stamp_s) {
  const Eigen::Vector2d p = T_world_observer.inverse() * p_world_observed;
  Sighting sighting;
  sighting.observer = observer;
  sighting.observed = observed;
  sighting.stamp = Stamp::fromSeconds(stamp_s);
  sighting.range_m = p.norm();
  sighting.bearing_rad = std::atan2(p.y(), p.x());
  sighting.T_map_observer = T_world_map.inverse() * T_world_observer;
  return sighting;
}

void expectPose(const SE2& actual, const SE2& expected, double tolerance) {
  EXPECT_NEAR(actual.x(), expected.x(), tolerance);
  EXPECT_NEAR(actual.y(), expected.y(), tolerance);
  EXPECT_NEAR(wrapAngle(actual.theta() - expected.theta()), 0.0, tolerance);
}

TEST(RendezvousTest, MutualSightingsGiveTheTransformBetweenTheMapFrames) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int trial = 0; trial < 50; ++trial) {
    const SE2 T_world_mapA(coordinate(random), coordinate(random), angle(random));
    const SE2 T_world_mapB(coordinate(random), coordinate(random), angle(random));
    const SE2 T_world_a(coordinate(random), coordinate(random), angle(random));
    const SE2 T_world_b = T_world_a * SE2(1.0 + 0.3 * trial / 10.0, -0.5, angle(random));
    const Sighting a_sees_b =
        sightingOf("a", "b", T_world_a, T_world_b.translation(), T_world_mapA, 10.0);
    const Sighting b_sees_a =
        sightingOf("b", "a", T_world_b, T_world_a.translation(), T_world_mapB, 10.0);
    expectPose(relativePoseFromSightings(a_sees_b, b_sees_a), T_world_a.inverse() * T_world_b,
               1e-9);
    expectPose(rendezvousTransform(a_sees_b, b_sees_a), T_world_mapA.inverse() * T_world_mapB,
               1e-9);
  }
}

TEST(RendezvousTest, BookPairsMutualSightingsCloseInTimeOnce) {
  const SE2 T_world_a(0.0, 0.0, 0.0);
  const SE2 T_world_b(2.0, 0.0, M_PI);
  // a's map frame is the world's; b's is b's pose now (b at its map origin).
  RendezvousBook book;
  EXPECT_TRUE(book.add(sightingOf("a", "b", T_world_a, T_world_b.translation(), SE2(), 5.0)));
  EXPECT_TRUE(book.takeHypotheses().empty()) << "one sighting alone is no rendezvous";
  // b's sighting 2 s later is no rendezvous (default gap 0.25 s).
  EXPECT_TRUE(book.add(sightingOf("b", "a", T_world_b, T_world_a.translation(), T_world_b, 7.0)));
  EXPECT_TRUE(book.takeHypotheses().empty());
  EXPECT_TRUE(book.add(sightingOf("b", "a", T_world_b, T_world_a.translation(), T_world_b, 5.1)));
  const std::vector<RendezvousHypothesis> hypotheses = book.takeHypotheses();
  ASSERT_EQ(hypotheses.size(), 1u);
  EXPECT_EQ(hypotheses[0].from, "b");
  EXPECT_EQ(hypotheses[0].to, "a");
  expectPose(hypotheses[0].T_to_from, T_world_b, 1e-9);
  EXPECT_TRUE(book.takeHypotheses().empty()) << "each sighting is used once";
  EXPECT_EQ(book.size(), 1u) << "the unpaired sighting (b at 7 s) stays";
  EXPECT_FALSE(book.add(sightingOf("a", "a", T_world_a, T_world_b.translation(), SE2(), 5.0)));
}

TEST(RendezvousTest, APairIsCheckedOneWayWhicheverSightingCameFirst) {
  const SE2 T_world_a(1.0, -0.5, 0.3);
  const SE2 T_world_b(2.5, 1.0, 2.0);
  // a's map frame is the world's; b's is b's pose now (b at its map origin).
  for (const bool b_first : {false, true}) {
    RendezvousBook book;
    const Sighting a_sees_b = sightingOf("a", "b", T_world_a, T_world_b.translation(), SE2(), 5.0);
    const Sighting b_sees_a =
        sightingOf("b", "a", T_world_b, T_world_a.translation(), T_world_b, 5.1);
    ASSERT_TRUE(book.add(b_first ? b_sees_a : a_sees_b));
    ASSERT_TRUE(book.add(b_first ? a_sees_b : b_sees_a));
    const std::vector<RendezvousHypothesis> hypotheses = book.takeHypotheses();
    ASSERT_EQ(hypotheses.size(), 1u);
    EXPECT_EQ(hypotheses[0].from, "b") << "b's sighting first: " << b_first;
    EXPECT_EQ(hypotheses[0].to, "a") << "b's sighting first: " << b_first;
    expectPose(hypotheses[0].T_to_from, T_world_b, 1e-9);
  }
}

/// Two overlapping crops of a real map, each in its own frame: the truth is a pure shift.
struct CropPair {
  GridMap a;
  GridMap b;
  SE2 T_a_b;  ///< pose of b's map frame in a's
};

CropPair intelCrops() {
  const GridMap source = merge_test::loadMap(test::sharedDataPath("maps/freiburg-intel.pgm"));
  CropPair pair;
  pair.a = test::cropWindow(source, 250, 250, 300);
  pair.b = test::cropWindow(source, 330, 300, 300);
  pair.T_a_b = SE2(80 * 0.05, 50 * 0.05, 0.0);
  return pair;
}

TEST(RendezvousTest, ANearlyRightRendezvousIsRefinedAndAccepted) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  const CropPair pair = intelCrops();
  // A rendezvous 12 cm and 1.5° off: what range and bearing noise and pose error give.
  const RendezvousHypothesis hypothesis{
      "b", "a", pair.T_a_b * SE2(0.1, -0.07, 1.5 * M_PI / 180.0), {}};
  const RendezvousCheck check = checkRendezvous(hypothesis, pair.b, pair.a, RendezvousSettings{});
  ASSERT_TRUE(check.accepted) << check.reason;
  EXPECT_GT(check.verification, 0.9);
  EXPECT_NEAR(check.T_to_from.x(), pair.T_a_b.x(), 0.05);
  EXPECT_NEAR(check.T_to_from.y(), pair.T_a_b.y(), 0.05);
  EXPECT_NEAR(wrapAngle(check.T_to_from.theta()), 0.0, 0.5 * M_PI / 180.0);
}

TEST(RendezvousTest, AWrongRendezvousIsRefusedByTheMaps) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  const CropPair pair = intelCrops();
  // Robots that mistook each other's bearing: the maps disagree.
  for (const SE2& error :
       {SE2(0.0, 0.0, 25.0 * M_PI / 180.0), SE2(2.5, -1.5, 0.0), SE2(0.0, 0.0, M_PI)}) {
    const RendezvousHypothesis hypothesis{"b", "a", pair.T_a_b * error, {}};
    const RendezvousCheck check = checkRendezvous(hypothesis, pair.b, pair.a, RendezvousSettings{});
    EXPECT_FALSE(check.accepted) << "error " << error.x() << ", " << error.y() << ", "
                                 << error.theta() << ": V " << check.verification;
    EXPECT_NE(check.reason.find("rendezvous refused by the maps"), std::string::npos)
        << check.reason;
  }
}

}  // namespace
}  // namespace mrslam::fusion
