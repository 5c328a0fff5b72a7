#include "mrslam/fusion/merge/feature_merger.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mrslam/common/map_loaders.hpp"
#include "mrslam/fusion/merge/merge_cases.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"
#include "mrslam/fusion/merge/overlap_score.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

constexpr double kPi = 3.14159265358979323846;

CropSpec specOf(int x, int y, int size, double theta_rad, int pad) {
  CropSpec spec;
  spec.corner = Eigen::Vector2i(x, y);
  spec.size = size;
  spec.theta_rad = theta_rad;
  spec.pad_low = Eigen::Vector2i(pad, 2 * pad);
  spec.pad_high = Eigen::Vector2i(2 * pad, pad);
  return spec;
}

/// Two crops of the Intel lab map sharing about two thirds of their known cells, B turned 35°.
MergeCase intelCase() {
  const SourceMap intel{"carpin-intel", "intel",
                        loadMapFile(test::sharedDataPath("maps/carpin-intel.txt"))};
  return makeCase(intel, specOf(150, 200, 320, 0.0, 10), intel,
                  specOf(220, 240, 320, 35.0 * kPi / 180.0, 25));
}

Config settingsOf(const std::string& yaml) {
  return Config::loadString(yaml, "test.yaml");
}

TEST(FeatureMergerTest, FindsTheKnownTransformBetweenTwoCropsOfARealMap) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  const MergeCase c = intelCase();
  ASSERT_GT(c.overlap, 0.5);
  FeatureMerger merger(FeatureMergerSettings{});
  const MergeResult result = merger.merge(c.a, c.b);
  ASSERT_TRUE(result.accepted) << result.reason;
  EXPECT_EQ(result.method, "feature");
  EXPECT_TRUE(result.reason.empty());
  const CaseError error = caseError(c, result.T_to_from);
  EXPECT_LT(error.angle_rad, 1.0 * kPi / 180.0);
  EXPECT_LT(error.distance_cells, 2.0);
  const OverlapScore score = scoreOverlap(c.a, c.b, result.T_to_from);
  EXPECT_DOUBLE_EQ(result.verification, score.verification());
  EXPECT_DOUBLE_EQ(result.entropy, score.entropy_bits);
  EXPECT_GT(result.verification, 0.9);
}

TEST(FeatureMergerTest, AkazeFeaturesFindItToo) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  const MergeCase c = intelCase();
  const auto merger = makeMerger("feature", settingsOf("detector: akaze\n"));
  const MergeResult result = merger->merge(c.a, c.b);
  ASSERT_TRUE(result.accepted) << result.reason;
  const CaseError error = caseError(c, result.T_to_from);
  EXPECT_LT(error.angle_rad, 1.0 * kPi / 180.0);
  EXPECT_LT(error.distance_cells, 2.0);
}

TEST(FeatureMergerTest, AVerificationBarRefusesWithTheFiguresKept) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  const MergeCase c = intelCase();
  FeatureMergerSettings settings;
  settings.min_verification = 1.0;  // no real overlap agrees on every cell
  const MergeResult result = FeatureMerger(settings).merge(c.a, c.b);
  EXPECT_FALSE(result.accepted);
  EXPECT_THAT(result.reason, ::testing::HasSubstr("verification"));
  EXPECT_GT(result.verification, 0.9);  // the figures of the refused estimate stay visible
}

TEST(FeatureMergerTest, RefusesMapsWithoutFeatures) {
  GridGeometry geometry;
  geometry.width = 200;
  geometry.height = 150;
  const GridMap unknown(geometry, GridMap::kUnknown);
  const GridMap free(geometry, GridMap::kFree);
  FeatureMerger merger(FeatureMergerSettings{});
  for (const auto& [from, to] : {std::pair{&unknown, &free}, std::pair{&free, &free}}) {
    const MergeResult result = merger.merge(*from, *to);
    EXPECT_FALSE(result.accepted);
    EXPECT_EQ(result.method, "feature");
    EXPECT_THAT(result.reason, ::testing::HasSubstr("matches"));
  }
}

TEST(FeatureMergerTest, TimesTheStepsItReached) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  const MergeCase c = intelCase();
  FeatureMerger merger(FeatureMergerSettings{});
  ASSERT_TRUE(merger.merge(c.a, c.b).accepted);
  const FeatureMergeTimings full = merger.lastTimings();
  EXPECT_GT(full.detection.count(), 0.0);
  EXPECT_GT(full.matching.count(), 0.0);
  EXPECT_GT(full.ransac.count(), 0.0);
  EXPECT_GT(full.verification.count(), 0.0);
  // Refused at the matches: the later steps did not run, and the last merge's times are gone.
  GridGeometry geometry;
  geometry.width = 200;
  geometry.height = 150;
  const GridMap free(geometry, GridMap::kFree);
  ASSERT_FALSE(merger.merge(free, free).accepted);
  EXPECT_GT(merger.lastTimings().detection.count(), 0.0);
  EXPECT_EQ(merger.lastTimings().ransac.count(), 0.0);
  EXPECT_EQ(merger.lastTimings().verification.count(), 0.0);
}

TEST(FeatureMergerTest, SettingsAreCheckedWhereTheyAreRead) {
  const FeatureMergerSettings read = loadFeatureMergerSettings(
      settingsOf("detector: akaze\nratio_test: 0.7\nmin_inliers: 20\nmin_verification: 0.8\n"));
  EXPECT_EQ(read.detector, "akaze");
  EXPECT_EQ(read.ratio_test, 0.7);
  EXPECT_EQ(read.min_inliers, 20);
  EXPECT_EQ(read.min_verification, 0.8);
  EXPECT_EQ(loadFeatureMergerSettings(settingsOf("")).detector, "orb");
  EXPECT_THROW(loadFeatureMergerSettings(settingsOf("detector: sift\n")), ConfigError);
  EXPECT_THROW(loadFeatureMergerSettings(settingsOf("ratio_test: 2\n")), ConfigError);
  EXPECT_THROW(loadFeatureMergerSettings(settingsOf("min_inliers: many\n")), ConfigError);
}

TEST(MergerRegistryTest, KnowsTheFeatureBaselineAndRefusesUnknownNames) {
  const auto names = mergerNames();
  EXPECT_THAT(names, ::testing::Contains("feature"));
  EXPECT_EQ(defaultMergerName(), names.front());
  for (const std::string& name : names) {
    EXPECT_EQ(makeMerger(name)->name(), name);
  }
  try {
    makeMerger("magic");
    FAIL() << "no exception for an unknown method";
  } catch (const std::invalid_argument& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("feature"));
  }
}

}  // namespace
}  // namespace mrslam::fusion
