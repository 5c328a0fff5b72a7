#include "mrslam/fusion/map_composer.hpp"

#include <gtest/gtest.h>

#include <random>

namespace mrslam::fusion {
namespace {

GridMap randomMap(int width, int height, Eigen::Vector2d origin, std::uint32_t seed) {
  GridGeometry geometry;
  geometry.resolution_m = 0.05;
  geometry.width = width;
  geometry.height = height;
  geometry.origin_m = origin;
  GridMap map(geometry, GridMap::kUnknown);
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> value(-1, 100);
  for (auto& cell : map.cells) {
    cell = static_cast<std::int8_t>(value(random));
  }
  return map;
}

TEST(MapComposerTest, NoMapsGiveAnEmptyMap) {
  const GridMap global = composeGlobalMap({}, {});
  EXPECT_EQ(global.geometry.cellCount(), 0u);
}

TEST(MapComposerTest, OneMapAtIdentityComesBackUnchanged) {
  const GridMap map = randomMap(37, 23, Eigen::Vector2d(-0.85, 1.2), 7);
  const GridMap global = composeGlobalMap({{&map, SE2()}}, {});
  ASSERT_EQ(global.geometry.width, map.geometry.width);
  ASSERT_EQ(global.geometry.height, map.geometry.height);
  EXPECT_NEAR((global.geometry.origin_m - map.geometry.origin_m).norm(), 0.0, 1e-9);
  for (int cy = 0; cy < map.geometry.height; ++cy) {
    for (int cx = 0; cx < map.geometry.width; ++cx) {
      ASSERT_EQ(global.at(cx, cy), map.at(cx, cy)) << cx << "," << cy;
    }
  }
}

TEST(MapComposerTest, ShiftedMapLandsAtItsPlace) {
  GridGeometry geometry;
  geometry.resolution_m = 0.1;
  geometry.width = 10;
  geometry.height = 10;
  GridMap map(geometry, GridMap::kUnknown);
  map.at(2, 3) = 100;
  map.at(5, 5) = 0;
  // The robot's map origin lies at (1, -2) in the reference frame, turned by 90°.
  const SE2 T_reference_robot(1.0, -2.0, M_PI / 2);
  const GridMap global = composeGlobalMap({{&map, T_reference_robot}}, {});
  const auto valueAt = [&](const Eigen::Vector2d& p_robot) {
    const Eigen::Vector2d p = T_reference_robot * p_robot;
    const auto cx = static_cast<int>(std::floor((p.x() - global.geometry.origin_m.x()) / 0.1));
    const auto cy = static_cast<int>(std::floor((p.y() - global.geometry.origin_m.y()) / 0.1));
    return global.geometry.contains(cx, cy) ? global.at(cx, cy) : std::int8_t{-100};
  };
  EXPECT_EQ(valueAt(geometry.cellCenter(2, 3)), 100);
  EXPECT_EQ(valueAt(geometry.cellCenter(5, 5)), 0);
  EXPECT_EQ(valueAt(geometry.cellCenter(3, 4)), GridMap::kUnknown);
  EXPECT_EQ(valueAt(geometry.cellCenter(7, 1)), -100);  // outside the known cells: cropped
  // Known cells span [0.2, 0.6] x [0.3, 0.6] in the robot map; turned by 90° about (1, -2):
  // x in [0.4, 0.7], y in [-1.8, -1.4].
  EXPECT_NEAR(global.geometry.origin_m.x(), 0.4, 1e-9);
  EXPECT_NEAR(global.geometry.origin_m.y(), -1.8, 1e-9);
  EXPECT_EQ(global.geometry.width, 3);
  EXPECT_EQ(global.geometry.height, 4);
}

TEST(MapComposerTest, GlobalMapIsCroppedToTheKnownCells) {
  GridGeometry geometry;
  geometry.width = 50;
  geometry.height = 40;
  geometry.origin_m = Eigen::Vector2d(-1.25, -1.0);
  GridMap unknown(geometry, GridMap::kUnknown);
  EXPECT_EQ(composeGlobalMap({{&unknown, SE2()}}, {}).geometry.cellCount(), 0u);
  GridMap patch = unknown;
  patch.at(10, 20) = 100;
  patch.at(12, 25) = 0;
  const GridMap global = composeGlobalMap({{&unknown, SE2()}, {&patch, SE2()}}, {});
  EXPECT_EQ(global.geometry.width, 3);
  EXPECT_EQ(global.geometry.height, 6);
  EXPECT_NEAR((global.geometry.origin_m - geometry.cellCenter(10, 20)).norm(),
              std::hypot(0.025, 0.025), 1e-9);
  EXPECT_EQ(global.at(0, 0), 100);
  EXPECT_EQ(global.at(2, 5), 0);
  EXPECT_EQ(global.at(1, 1), GridMap::kUnknown);
}

TEST(MapComposerTest, EvidenceAddsUpInLogOdds) {
  GridGeometry geometry;
  geometry.width = 3;
  geometry.height = 1;
  GridMap a(geometry, GridMap::kUnknown);
  GridMap b(geometry, GridMap::kUnknown);
  a.at(0, 0) = 70;  // agree: more certain
  b.at(0, 0) = 70;
  a.at(1, 0) = 80;  // disagree equally: back to 50
  b.at(1, 0) = 20;
  a.at(2, 0) = 30;  // seen by one robot only
  const GridMap global = composeGlobalMap({{&a, SE2()}, {&b, SE2()}}, {});
  // logit(0.7) * 2 → p = 0.49 / (0.49 + 0.09) = 0.845
  EXPECT_EQ(global.at(0, 0), 84);
  EXPECT_EQ(global.at(1, 0), 50);
  EXPECT_EQ(global.at(2, 0), 30);
}

TEST(MapComposerTest, ResolutionOfTheGlobalMapIsASetting) {
  const GridMap map = randomMap(20, 20, Eigen::Vector2d(0, 0), 3);
  ComposerSettings settings;
  settings.resolution_m = 0.1;
  const GridMap global = composeGlobalMap({{&map, SE2()}}, settings);
  EXPECT_DOUBLE_EQ(global.geometry.resolution_m, 0.1);
  EXPECT_EQ(global.geometry.width, 10);
  EXPECT_EQ(global.geometry.height, 10);
}

}  // namespace
}  // namespace mrslam::fusion
