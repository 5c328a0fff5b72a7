#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "merge_test_maps.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion {
namespace {

constexpr double kDegree = M_PI / 180.0;

// A synthetic floor: rooms with doors, a corridor and some furniture; walls 2 cells thick.
GridMap building() {
  cv::Mat image(300, 300, CV_8U, cv::Scalar(127));  // unknown outside
  cv::rectangle(image, cv::Rect(20, 20, 260, 250), cv::Scalar(255), cv::FILLED);
  const auto wall = [&](cv::Point a, cv::Point b) { cv::line(image, a, b, cv::Scalar(0), 2); };
  wall({20, 20}, {280, 20});
  wall({280, 20}, {280, 270});
  wall({280, 270}, {20, 270});
  wall({20, 270}, {20, 20});
  wall({20, 120}, {90, 120});  // rooms along the left, doors between
  wall({110, 120}, {170, 120});
  wall({120, 20}, {120, 80});
  wall({120, 100}, {120, 120});
  wall({200, 20}, {200, 160});
  wall({200, 180}, {200, 270});
  wall({60, 190}, {140, 190});
  wall({60, 190}, {60, 240});
  wall({230, 60}, {260, 90});  // a slanted cupboard
  cv::rectangle(image, cv::Rect(150, 220, 12, 8), cv::Scalar(0), cv::FILLED);
  cv::rectangle(image, cv::Rect(40, 40, 10, 16), cv::Scalar(0), cv::FILLED);
  cv::circle(image, cv::Point(240, 220), 9, cv::Scalar(0), 2);
  GridGeometry geometry;
  geometry.width = image.cols;
  geometry.height = image.rows;
  GridMap map(geometry, GridMap::kUnknown);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const int grey = image.at<std::uint8_t>(y, x);
      map.at(x, y) =
          grey == 0 ? GridMap::kOccupied : (grey == 255 ? GridMap::kFree : GridMap::kUnknown);
    }
  }
  return map;
}

Config yaml(const std::string& text) {
  return Config::loadString(text, "merge.yaml");
}

TEST(MergeSeedMergerTest, SettingsDefaultToTheStructsDefaults) {
  const SeedMergerSettings loaded = loadSeedMergerSettings(yaml("{}"));
  const SeedMergerSettings defaults;
  EXPECT_EQ(loaded.edges.edge_merge_distance_dt, defaults.edges.edge_merge_distance_dt);
  EXPECT_EQ(loaded.segments.segment_points_n, defaults.segments.segment_points_n);
  EXPECT_DOUBLE_EQ(loaded.verification.histogram_spread_hd,
                   defaults.verification.histogram_spread_hd);
  EXPECT_NEAR(loaded.verification.max_turn_omega_c, defaults.verification.max_turn_omega_c, 1e-12);
  EXPECT_NEAR(loaded.radon.rotation_window_rad, defaults.radon.rotation_window_rad, 1e-12);
  EXPECT_EQ(loaded.translation_window_delta, defaults.translation_window_delta);
  EXPECT_DOUBLE_EQ(loaded.min_verification_v, defaults.min_verification_v);
  EXPECT_EQ(loaded.seed, defaults.seed);
}

TEST(MergeSeedMergerTest, SettingsReadThePapersSymbolsAndDegrees) {
  const SeedMergerSettings loaded = loadSeedMergerSettings(
      yaml("edge_merge_distance_dt: 5\nsegment_points_n: 40\nhistogram_spread_hd: 3.5\n"
           "max_turn_omega_c_deg: 90\ntranslation_window_delta: 9\nmin_verification_v: 0.8\n"
           "occupied_threshold: 70\nseed: 42\nradon_fallback: false\njudged_candidates: 5\n"
           "wall_icp_iterations: 0\nwall_icp_distance_cells: 4.5\nwall_icp_samples: 500\n"));
  EXPECT_EQ(loaded.edges.edge_merge_distance_dt, 5);
  EXPECT_EQ(loaded.segments.segment_points_n, 40);
  EXPECT_DOUBLE_EQ(loaded.verification.histogram_spread_hd, 3.5);
  EXPECT_NEAR(loaded.verification.max_turn_omega_c, M_PI / 2.0, 1e-12);
  EXPECT_EQ(loaded.translation_window_delta, 9);
  EXPECT_DOUBLE_EQ(loaded.min_verification_v, 0.8);
  EXPECT_EQ(loaded.edges.occupied_threshold, 70);
  EXPECT_EQ(loaded.similarity.occupied_threshold, 70);
  EXPECT_EQ(loaded.seed, 42u);
  EXPECT_FALSE(loaded.radon_fallback);
  EXPECT_EQ(loaded.judged_candidates, 5);
  EXPECT_EQ(loaded.wall_icp_iterations, 0);
  EXPECT_DOUBLE_EQ(loaded.wall_icp_distance_cells, 4.5);
  EXPECT_EQ(loaded.wall_icp_samples, 500);
}

TEST(MergeSeedMergerTest, SettingsErrorsNameTheFileLineAndKey) {
  try {
    loadSeedMergerSettings(yaml("seed: 3\nmin_verification_v: 1.5\n"));
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("merge.yaml:2"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("min_verification_v"), std::string::npos);
  }
  EXPECT_THROW(loadSeedMergerSettings(yaml("free_threshold: 70\n")), ConfigError);
  EXPECT_THROW(loadSeedMergerSettings(yaml("canny_low: 200\ncanny_high: 100\n")), ConfigError);
  EXPECT_THROW(loadSeedMergerSettings(yaml("segment_points_n: 5\n")), ConfigError);
  EXPECT_THROW(loadSeedMergerSettings(yaml("judged_candidates: 0\n")), ConfigError);
  EXPECT_THROW(loadSeedMergerSettings(yaml("wall_icp_distance_cells: 0.1\n")), ConfigError);
  EXPECT_THROW(loadSeedMergerSettings(yaml("wall_icp_samples: -1\n")), ConfigError);
}

TEST(MergeSeedMergerTest, RefusesEmptyInvalidAndMismatchedMaps) {
  SeedMerger merger;
  const GridMap map = building();
  EXPECT_FALSE(merger.merge(GridMap{}, map).accepted);
  GridMap broken = map;
  broken.cells.pop_back();
  const MergeResult invalid = merger.merge(broken, map);
  EXPECT_FALSE(invalid.accepted);
  EXPECT_FALSE(invalid.reason.empty());
  GridMap coarser = map;
  coarser.geometry.resolution_m = 0.1;
  EXPECT_FALSE(merger.merge(coarser, map).accepted);
  EXPECT_EQ(merger.name(), "seed");
}

TEST(MergeSeedMergerTest, RefusesAMapWithoutStructure) {
  GridGeometry geometry;
  geometry.width = 200;
  geometry.height = 200;
  const GridMap open_space(geometry, GridMap::kFree);
  const MergeResult result = SeedMerger().merge(open_space, open_space);
  EXPECT_FALSE(result.accepted);
  EXPECT_FALSE(result.reason.empty());
}

TEST(MergeSeedMergerTest, RefusesTinyMapsWithoutFailing) {
  SeedMerger merger;
  for (const int side : {1, 2, 5}) {
    GridGeometry geometry;
    geometry.width = side;
    geometry.height = side;
    GridMap tiny(geometry, GridMap::kFree);
    tiny.at(0, 0) = GridMap::kOccupied;
    const MergeResult result = merger.merge(tiny, building());
    EXPECT_FALSE(result.accepted) << side;
    EXPECT_FALSE(result.reason.empty()) << side;
  }
}

TEST(MergeSeedMergerTest, RefusesAStraightCorridorThatFixesNoTranslation) {
  GridGeometry geometry;
  geometry.width = 400;
  geometry.height = 60;
  GridMap corridor(geometry, GridMap::kUnknown);
  for (int x = 0; x < geometry.width; ++x) {
    for (int y = 20; y <= 40; ++y) {
      corridor.at(x, y) = (y == 20 || y == 40) ? GridMap::kOccupied : GridMap::kFree;
    }
  }
  const merge_test::KnownCase known =
      merge_test::cropPair(corridor, Eigen::Vector2i(0, 0), 200, Eigen::Vector2d(160.0, 30.0), 0.3);
  ASSERT_GT(known.overlap, 0.5);
  const MergeResult result = SeedMerger().merge(known.from, known.to);
  EXPECT_FALSE(result.accepted) << "accepted a shift along the corridor";
}

TEST(MergeSeedMergerTest, MergesTurnedAndShiftedCropsOfASyntheticFloor) {
  const GridMap floor = building();
  SeedMerger merger;
  for (const double turn_deg : {33.0, -120.0, 181.0}) {
    const merge_test::KnownCase known = merge_test::cropPair(
        floor, Eigen::Vector2i(10, 10), 220, Eigen::Vector2d(160.0, 150.0), turn_deg * kDegree);
    ASSERT_GT(known.overlap, 0.6);
    const MergeResult result = merger.merge(known.from, known.to);
    ASSERT_TRUE(result.accepted) << turn_deg << "°: " << result.reason;
    const merge_test::PoseError error = merge_test::poseError(result.T_to_from, known);
    EXPECT_LT(error.rotation_rad, 1.0 * kDegree) << turn_deg;
    EXPECT_LT(error.translation_cells, 2.0) << turn_deg;
    EXPECT_GE(result.verification, 0.9);
    EXPECT_GT(result.entropy, 0.0);
    EXPECT_GT(result.trials, 0);
    EXPECT_EQ(result.method.rfind("seed", 0), 0u) << result.method;  // seed or one of its steps
    EXPECT_TRUE(result.reason.empty());
  }
}

TEST(MergeSeedMergerTest, SameSeedSameAnswer) {
  const merge_test::KnownCase known = merge_test::cropPair(building(), Eigen::Vector2i(30, 20), 200,
                                                           Eigen::Vector2d(150.0, 140.0), 1.0);
  const MergeResult first = SeedMerger().merge(known.from, known.to);
  const MergeResult second = SeedMerger().merge(known.from, known.to);
  EXPECT_EQ(first.accepted, second.accepted);
  EXPECT_EQ(first.T_to_from.theta_rad, second.T_to_from.theta_rad);
  EXPECT_EQ(first.T_to_from.t_cells, second.T_to_from.t_cells);
  EXPECT_EQ(first.trials, second.trials);
}

TEST(MergeSeedMergerTest, RecordsTheTimeOfEveryBlock) {
  const merge_test::KnownCase known = merge_test::cropPair(building(), Eigen::Vector2i(10, 10), 220,
                                                           Eigen::Vector2d(160.0, 150.0), 0.5);
  SeedMerger merger;
  merger.merge(known.from, known.to);
  const SeedMergeTimings& timings = merger.lastTimings();
  EXPECT_GT(timings.edges.count(), 0.0);
  EXPECT_GT(timings.segments.count(), 0.0);
  EXPECT_GT(timings.translation.count(), 0.0);
}

}  // namespace
}  // namespace mrslam::fusion
