// The global search (global_search.hpp): seeded crops of a real map with a known turn and shift
// are found among its hypotheses, and its settings are read from the seed merger's section.

#include <gtest/gtest.h>

#include <random>

#include "merge_test_maps.hpp"
#include "mrslam/fusion/merge/global_search.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

constexpr double kDegree = M_PI / 180.0;

// Whether one of the hypotheses lies within a coarse answer's reach of the truth: half a
// rotation step (plus rounding) and about one and a half coarse cells at the overlap's centre.
bool truthAmong(const std::vector<GlobalHypothesis>& hypotheses, const merge_test::KnownCase& known,
                const GlobalSearchSettings& settings) {
  for (const GlobalHypothesis& hypothesis : hypotheses) {
    const merge_test::PoseError error = merge_test::poseError(hypothesis.T_to_from, known);
    if (error.rotation_rad <= 0.5 * settings.rotation_step_rad + 0.5 * kDegree &&
        error.translation_cells <= 1.5 * settings.coarse_cells + 2.0) {
      return true;
    }
  }
  return false;
}

TEST(MergeGlobalSearchTest, FindsAKnownTurnAndShiftOfARealCrop) {
  const GridMap map = merge_test::loadMap(test::sharedDataPath("maps/carpin-intel.txt"));
  ASSERT_TRUE(map.isValid());
  const GlobalSearchSettings settings;
  std::mt19937 random(3);
  int cases = 0;
  int found = 0;
  while (cases < 4) {
    const merge_test::KnownCase known = merge_test::randomCase(map, 300, 0.6, 1.01, random);
    if (known.overlap == 0.0) {
      continue;
    }
    ++cases;
    const std::vector<GlobalHypothesis> hypotheses =
        globalSearch(known.from, known.to, settings, SimilaritySettings{});
    EXPECT_LE(static_cast<int>(hypotheses.size()),
              settings.kept_hypotheses + settings.free_agreement_hypotheses);
    found += truthAmong(hypotheses, known, settings) ? 1 : 0;
  }
  EXPECT_GE(found, 3) << "of " << cases << " crops overlapping by 60 % or more";
}

// Best first within each score: the walls' (s) first, then those with free agreement (s_f).
TEST(MergeGlobalSearchTest, HypothesesComeBestFirst) {
  const GridMap map = merge_test::loadMap(test::sharedDataPath("maps/carpin-intel.txt"));
  ASSERT_TRUE(map.isValid());
  std::mt19937 random(5);
  merge_test::KnownCase known;
  while (known.overlap == 0.0) {
    known = merge_test::randomCase(map, 250, 0.5, 1.01, random);
  }
  const std::vector<GlobalHypothesis> hypotheses =
      globalSearch(known.from, known.to, GlobalSearchSettings{}, SimilaritySettings{});
  ASSERT_FALSE(hypotheses.empty());
  for (std::size_t i = 1; i < hypotheses.size(); ++i) {
    EXPECT_TRUE(!hypotheses[i - 1].by_free_agreement || hypotheses[i].by_free_agreement);
    if (hypotheses[i - 1].by_free_agreement == hypotheses[i].by_free_agreement) {
      EXPECT_GE(hypotheses[i - 1].score, hypotheses[i].score);
    }
  }
}

TEST(MergeGlobalSearchTest, NoHypothesisWithoutWalls) {
  GridGeometry geometry;
  geometry.width = 60;
  geometry.height = 60;
  const GridMap free_only(geometry, GridMap::kFree);
  const GridMap map = merge_test::loadMap(test::sharedDataPath("maps/carpin-intel.txt"));
  EXPECT_TRUE(globalSearch(free_only, map, GlobalSearchSettings{}, SimilaritySettings{}).empty());
  EXPECT_TRUE(globalSearch(GridMap(), map, GlobalSearchSettings{}, SimilaritySettings{}).empty());
}

TEST(MergeGlobalSearchTest, SettingsComeFromTheSeedSection) {
  const SeedMergerSettings settings = loadSeedMergerSettings(Config::loadString(
      "global_search: false\nglobal_coarse_cells: 6\nglobal_rotation_step_deg: 2\n"
      "global_hypotheses: 20\nglobal_candidates: 9\nglobal_free_agreement_weight: 0.3\n"
      "global_free_agreement_hypotheses: 4\n",
      "merge.yaml"));
  EXPECT_FALSE(settings.global_search);
  EXPECT_EQ(settings.global.coarse_cells, 6);
  EXPECT_NEAR(settings.global.rotation_step_rad, 2.0 * kDegree, 1e-12);
  EXPECT_EQ(settings.global.kept_hypotheses, 20);
  EXPECT_EQ(settings.global_candidates, 9);
  EXPECT_DOUBLE_EQ(settings.global.free_agreement_weight, 0.3);
  EXPECT_EQ(settings.global.free_agreement_hypotheses, 4);
}

TEST(MergeGlobalSearchTest, TheSeedMergerNamesTheStepOfItsAnswer) {
  const GridMap map = merge_test::loadMap(test::sharedDataPath("maps/carpin-intel.txt"));
  ASSERT_TRUE(map.isValid());
  std::mt19937 random(11);
  merge_test::KnownCase known;
  while (known.overlap == 0.0) {
    known = merge_test::randomCase(map, 300, 0.6, 1.01, random);
  }
  SeedMerger merger;
  const MergeResult result = merger.merge(known.from, known.to);
  ASSERT_TRUE(result.accepted) << result.reason;
  EXPECT_TRUE(merge_test::isSuccess(merge_test::poseError(result.T_to_from, known)));
  EXPECT_TRUE(result.method == "seed" || result.method == "seed/radon-fallback" ||
              result.method == "seed/global-search" || result.method == "seed/global-search-free")
      << result.method;
}

}  // namespace
}  // namespace mrslam::fusion
