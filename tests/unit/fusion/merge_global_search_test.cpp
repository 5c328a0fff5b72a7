// The global search (global_search.hpp): seeded crops of a real map with a known turn and shift
// are found among its hypotheses, and its settings are read from the seed merger's section.

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <tuple>

#include "merge_crop_pairs.hpp"
#include "merge_test_maps.hpp"
#include "mrslam/fusion/merge/global_search.hpp"
#include "mrslam/fusion/merge/padded_spectrum.hpp"
#include "mrslam/fusion/merge/quarter_turns.hpp"
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

// A known-answer pair of crops of the Intel map, `side` cells, overlapping by at least
// `least_overlap`, drawn by a generator seeded with `seed`.
merge_test::KnownCase intelCase(unsigned seed, int side, double least_overlap) {
  const GridMap map = merge_test::loadMap(test::sharedDataPath("maps/carpin-intel.txt"));
  if (!map.isValid()) {
    ADD_FAILURE() << "carpin-intel.txt did not load";
    return {};
  }
  std::mt19937 random(seed);
  merge_test::KnownCase known;
  while (known.overlap == 0.0) {
    known = merge_test::randomCase(map, side, least_overlap, 1.01, random);
  }
  return known;
}

TEST(MergeGlobalSearchTest, APaddedSpectrumLeavesThePaddingRowsOutAndStaysTheSame) {
  // Random images of the sizes the sweep pads (odd sides, padded to DFT-friendly ones): the
  // spectrum with the padding rows left out of the first pass equals the full DFT bit for bit.
  std::mt19937 random(5);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  for (const auto& [image_size, padded_size] :
       {std::pair{cv::Size(37, 23), cv::Size(64, 48)},
        std::pair{cv::Size(101, 143), cv::Size(250, 243)}}) {
    cv::Mat image(image_size, CV_32F);
    for (int y = 0; y < image.rows; ++y) {
      for (int x = 0; x < image.cols; ++x) {
        image.at<float>(y, x) = value(random);
      }
    }
    cv::Mat padded(padded_size, CV_32F, cv::Scalar(0.0f));
    image.copyTo(padded(cv::Rect(cv::Point(0, 0), image_size)));
    cv::Mat full;
    cv::dft(padded, full);
    const cv::Mat spectrum = paddedSpectrum(image, padded_size);
    ASSERT_EQ(spectrum.size(), full.size());
    EXPECT_EQ(cv::norm(spectrum, full, cv::NORM_INF), 0.0) << image_size << " in " << padded_size;
  }
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

// Brute-force circular cross-correlation S(s) = Σ_u canvas(u) target(u + s) on a side × side
// torus, the canvas and the target at its origin.
cv::Mat correlation(const cv::Mat& canvas, const cv::Mat& target, int side) {
  cv::Mat scores(side, side, CV_32F, cv::Scalar(0.0f));
  for (int s2 = 0; s2 < side; ++s2) {
    for (int s1 = 0; s1 < side; ++s1) {
      double sum = 0.0;
      for (int y = 0; y < canvas.rows; ++y) {
        for (int x = 0; x < canvas.cols; ++x) {
          const int tx = (x + s1) % side;
          const int ty = (y + s2) % side;
          if (tx < target.cols && ty < target.rows) {
            sum += canvas.at<float>(y, x) * target.at<float>(ty, tx);
          }
        }
      }
      scores.at<float>(s2, s1) = static_cast<float>(sum);
    }
  }
  return scores;
}

// The canvas turned by a quarter turn about its centre, (x, y) → (-y, x) in image coordinates:
// turned(x, y) = canvas(y, n - 1 - x), (column, row).
cv::Mat quarterTurned(const cv::Mat& canvas) {
  const int n = canvas.rows;
  cv::Mat turned(n, n, CV_32F);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      turned.at<float>(y, x) = canvas.at<float>(n - 1 - x, y);
    }
  }
  return turned;
}

// The correlation of a canvas turned by q quarter turns equals that of the unturned canvas
// against the target turned back on the torus, read at the mapped shifts: exactly, on random
// images, canvases of odd and even sides, targets wider and taller.
TEST(MergeGlobalSearchTest, AQuarterTurnOfTheCanvasIsATurnOfTheTargetOnTheTorus) {
  std::mt19937 random(17);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  const auto randomImage = [&](int rows, int cols) {
    cv::Mat image(rows, cols, CV_32F);
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < cols; ++x) {
        image.at<float>(y, x) = value(random);
      }
    }
    return image;
  };
  for (const auto& [n, target_size, side] :
       {std::tuple{7, cv::Size(9, 5), 17}, std::tuple{6, cv::Size(4, 11), 18}}) {
    const cv::Mat canvas = randomImage(n, n);
    const cv::Mat target = randomImage(target_size.height, target_size.width);
    cv::Mat turned = canvas;
    for (int quarters = 1; quarters <= 3; ++quarters) {
      turned = quarterTurned(turned);
      const cv::Mat expected = correlation(turned, target, side);
      const cv::Mat found = quarterTurnScores(
          correlation(canvas, turnedOnTorus(target, side, quarters), side), n, quarters);
      EXPECT_LT(cv::norm(found, expected, cv::NORM_INF), 1e-4)
          << "canvas " << n << ", " << quarters << " quarter turns";
    }
  }
}

// The sweep with quarter turns against turning `from` by every rotation: the same rotations and
// shifts, the scores within 1 % (bilinear turns by 90° more differ by OpenCV's 1/32-cell
// interpolation steps). Crops of unequal sides (the square DFT pads one side more). A hypothesis
// within 1 % of the weakest kept one of its score may give way to another.
TEST(MergeGlobalSearchTest, QuarterTurnsOfToGiveTheHypothesesOfTurningFrom) {
  const GridMap map = merge_test::loadMap(test::sharedDataPath("maps/carpin-intel.txt"));
  ASSERT_TRUE(map.isValid());
  std::mt19937 random(11);
  GlobalSearchSettings every_turn;
  every_turn.quarter_turns = false;
  GlobalSearchSettings quarters;
  ASSERT_TRUE(quarters.quarter_turns);
  ASSERT_EQ(std::lround(2.0 * M_PI / quarters.rotation_step_rad) % 4, 0);
  int matched = 0;
  int beyond_first_quarter = 0;
  for (int c = 0; c < 3; ++c) {
    merge_test::KnownCase known;
    while (known.overlap == 0.0) {
      known = merge_test::randomCase(map, 200 + 40 * c, 0.3, 1.01, random);
    }
    GridMap from = known.from;  // cut to unequal sides
    from.geometry.height -= 30 + 10 * c;
    from.cells.resize(from.geometry.cellCount());
    const std::vector<GlobalHypothesis> expected =
        globalSearch(from, known.to, every_turn, SimilaritySettings{});
    const std::vector<GlobalHypothesis> found =
        globalSearch(from, known.to, quarters, SimilaritySettings{});
    ASSERT_EQ(found.size(), expected.size()) << "crop " << c;
    double weakest[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
    for (const GlobalHypothesis& want : expected) {
      double& least = weakest[want.by_free_agreement ? 1 : 0];
      least = std::min(least, want.score);
    }
    for (const GlobalHypothesis& want : expected) {
      const bool same = std::any_of(found.begin(), found.end(), [&](const auto& got) {
        return got.by_free_agreement == want.by_free_agreement &&
               std::abs(got.T_to_from.theta_rad - want.T_to_from.theta_rad) < 1e-9 &&
               (got.T_to_from.t_cells - want.T_to_from.t_cells).norm() < 1e-6 &&
               std::abs(got.score - want.score) <= 0.01 * std::abs(want.score);
      });
      const bool at_the_cut = want.score <= 1.01 * weakest[want.by_free_agreement ? 1 : 0];
      EXPECT_TRUE(same || at_the_cut)
          << "crop " << c << ": " << want.T_to_from.theta_rad << " rad, ("
          << want.T_to_from.t_cells.transpose() << "), score " << want.score;
      matched += same ? 1 : 0;
      beyond_first_quarter +=
          same && std::abs(std::remainder(want.T_to_from.theta_rad, 2.0 * M_PI)) > 0.5 * M_PI ? 1
                                                                                              : 0;
    }
  }
  EXPECT_GE(matched, 30);
  EXPECT_GE(beyond_first_quarter, 10) << "the other quarters are compared too";
}

// Best first within each score: the walls' (s) first, then those with free agreement (s_f).
TEST(MergeGlobalSearchTest, HypothesesComeBestFirst) {
  const merge_test::KnownCase known = intelCase(5, 250, 0.5);
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
      "global_free_agreement_hypotheses: 4\nglobal_max_grid_cells: 0\n",
      "merge.yaml"));
  EXPECT_FALSE(settings.global_search);
  EXPECT_EQ(settings.global.coarse_cells, 6);
  EXPECT_NEAR(settings.global.rotation_step_rad, 2.0 * kDegree, 1e-12);
  EXPECT_EQ(settings.global.kept_hypotheses, 20);
  EXPECT_EQ(settings.global_candidates, 9);
  EXPECT_DOUBLE_EQ(settings.global.free_agreement_weight, 0.3);
  EXPECT_EQ(settings.global.free_agreement_hypotheses, 4);
  EXPECT_EQ(settings.global_max_grid_cells, 0);
  EXPECT_EQ(SeedMergerSettings{}.global_max_grid_cells, 160);
  EXPECT_THROW(loadSeedMergerSettings(Config::loadString("global_max_grid_cells: -1\n", "m.yaml")),
               ConfigError);
}

TEST(MergeGlobalSearchTest, LargeMapsAreSweptOnLargerBlocks) {
  const GridMap crop(GridGeometry{0.05, 400, 300, Eigen::Vector2d::Zero()}, GridMap::kUnknown);
  const GridMap building(GridGeometry{0.05, 1915, 1539, Eigen::Vector2d::Zero()},
                         GridMap::kUnknown);
  EXPECT_EQ(blockCellsForSize(crop, crop, 4, 160), 4);       // 100 blocks a side
  EXPECT_EQ(blockCellsForSize(crop, building, 4, 160), 12);  // 1915 / 160, rounded up
  EXPECT_EQ(blockCellsForSize(building, crop, 2, 320), 6);
  EXPECT_EQ(blockCellsForSize(crop, building, 4, 0), 4);  // no limit
  EXPECT_EQ(blockCellsForSize(crop, crop, 0, 0), 1);
}

// Two turned 700-cell windows of the ACES map (crops of about 1000 cells a side) swept on
// blocks of 7 cells: the truth is still among the coarse hypotheses, within about a block and
// half a rotation step.
TEST(MergeGlobalSearchTest, AWholeBuildingOnLargerBlocksStillHoldsTheTruth) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-aces.pgm");
  const MergeCase merge_case =
      merge_test::cut(merge_test::CropPair{"freiburg-aces.pgm",
                                           0,
                                           {{150, 120}, 700, 0.6, {10, 20}, {30, 5}},
                                           {{380, 330}, 700, -0.35, {25, 3}, {4, 18}}});
  GlobalSearchSettings settings;
  settings.coarse_cells = blockCellsForSize(merge_case.a, merge_case.b, settings.coarse_cells, 160);
  ASSERT_EQ(settings.coarse_cells, 7);
  const std::vector<GlobalHypothesis> hypotheses =
      globalSearch(merge_case.a, merge_case.b, settings, SimilaritySettings{});
  const bool has_truth = std::any_of(hypotheses.begin(), hypotheses.end(), [&](const auto& h) {
    const CaseError error = caseError(merge_case, h.T_to_from);
    return error.distance_cells <= 2.0 * settings.coarse_cells && error.angle_rad <= 3.0 * kDegree;
  });
  EXPECT_TRUE(has_truth) << hypotheses.size() << " hypotheses";
}

TEST(MergeGlobalSearchTest, TheSeedMergerNamesTheStepOfItsAnswer) {
  const merge_test::KnownCase known = intelCase(11, 300, 0.6);
  SeedMerger merger;
  const MergeResult result = merger.merge(known.from, known.to);
  ASSERT_TRUE(result.accepted) << result.reason;
  EXPECT_TRUE(merge_test::isSuccess(merge_test::poseError(result.T_to_from, known)));
  EXPECT_TRUE(result.method == "seed" || result.method == "seed/radon-fallback" ||
              result.method == "seed/global-search" || result.method == "seed/global-search-free")
      << result.method;
}

// The same hypotheses, each also found by the same score (s or s_f).
void expectTheSameHypotheses(const std::vector<GlobalHypothesis>& found,
                             const std::vector<GlobalHypothesis>& reference) {
  merge_test::expectTheSameHypotheses(found, reference);
  for (std::size_t i = 0; i < std::min(found.size(), reference.size()); ++i) {
    EXPECT_EQ(found[i].by_free_agreement, reference[i].by_free_agreement) << i;
  }
}

// The merge chain sweeps one pair at the accepted rotation (the 1° grid about it) and at its
// exact quarter turns from one preparation: each finds what a sweep of its own finds.
TEST(MergeGlobalSearchTest, OnePreparedSweepFindsWhatSweepsOfTheirOwnFind) {
  const merge_test::KnownCase known = intelCase(9, 250, 0.5);
  const double theta = known.T_to_from.theta_rad;
  GlobalSearchSettings at_rotation;
  at_rotation.rotation_step_rad = kDegree;
  at_rotation.only_rotations_rad = {theta};
  at_rotation.free_agreement_hypotheses = 0;
  at_rotation.peaks_per_rotation = 24;
  at_rotation.kept_hypotheses = 24;
  GlobalSearchSettings at_turns = at_rotation;
  at_turns.exact_rotations = true;
  at_turns.only_rotations_rad = {theta + M_PI / 2.0, theta + M_PI, theta + 1.5 * M_PI};
  at_turns.peaks_per_rotation = 100;
  at_turns.kept_hypotheses = 100;
  const GlobalSweep sweep(known.from, known.to, at_rotation, SimilaritySettings{});
  const std::vector<GlobalHypothesis> near = sweep.search(at_rotation);
  expectTheSameHypotheses(near, globalSearch(known.from, known.to, at_rotation, {}));
  expectTheSameHypotheses(sweep.search(at_turns), globalSearch(known.from, known.to, at_turns, {}));
  EXPECT_TRUE(truthAmong(near, known, at_rotation)) << "the truth is among the peaks at its turn";
  // The whole turn by quarter turns (the seed step's sweep), prepared for it.
  const GlobalSearchSettings whole;
  expectTheSameHypotheses(GlobalSweep(known.from, known.to, whole, {}).search(whole),
                          globalSearch(known.from, known.to, whole, {}));
}

TEST(MergeGlobalSearchTest, APreparedSweepRefusesSettingsItWasNotPreparedFor) {
  const merge_test::KnownCase known = intelCase(9, 250, 0.5);
  GlobalSearchSettings prepared_for;
  prepared_for.only_rotations_rad = {0.3};
  prepared_for.free_agreement_hypotheses = 0;
  const GlobalSweep sweep(known.from, known.to, prepared_for, SimilaritySettings{});
  EXPECT_NO_THROW(sweep.search(prepared_for));
  GlobalSearchSettings coarser = prepared_for;
  coarser.coarse_cells = 8;
  EXPECT_THROW(sweep.search(coarser), std::invalid_argument);
  GlobalSearchSettings by_free = prepared_for;
  by_free.free_agreement_hypotheses = 6;
  EXPECT_THROW(sweep.search(by_free), std::invalid_argument);
  GlobalSearchSettings heavier = prepared_for;
  heavier.free_weight = 0.7;
  EXPECT_THROW(sweep.search(heavier), std::invalid_argument);
  GlobalSearchSettings whole_turn = prepared_for;
  whole_turn.only_rotations_rad.clear();  // by quarter turns, on a square DFT
  EXPECT_THROW(sweep.search(whole_turn), std::invalid_argument);
  GridGeometry geometry;
  geometry.width = 60;
  geometry.height = 60;
  EXPECT_TRUE(GlobalSweep(GridMap(geometry, GridMap::kFree), known.to, prepared_for, {})
                  .search(prepared_for)
                  .empty())
      << "no walls: no hypothesis";
}

}  // namespace
}  // namespace mrslam::fusion
