#pragma once
// Known-answer crop pairs of the shared maps, cut as `mrslam merge-cases` cuts them, for the seed
// merger's tests of single cases (the same case numbers as its --json --details output).

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "mrslam/common/map_loaders.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/merge/merge_cases.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"
#include "test_data.hpp"

namespace mrslam::fusion::merge_test {

struct CropPair {
  const char* map;
  int case_id;
  CropSpec a;
  CropSpec b;
};

/// Every figure of two merge results equal: the decision, its method and reason, the transform,
/// V and the entropy (`what` names the comparison in a failure).
inline void expectTheSameDecision(const MergeResult& kept, const MergeResult& built,
                                  const std::string& what) {
  EXPECT_EQ(kept.accepted, built.accepted) << what;
  EXPECT_EQ(kept.method, built.method) << what;
  EXPECT_EQ(kept.reason, built.reason) << what;
  EXPECT_EQ(kept.T_to_from.theta_rad, built.T_to_from.theta_rad) << what;
  EXPECT_EQ(kept.T_to_from.t_cells, built.T_to_from.t_cells) << what;
  EXPECT_EQ(kept.verification, built.verification) << what;
  EXPECT_EQ(kept.entropy, built.entropy) << what;
}

inline MergeCase cut(const CropPair& pair) {
  const SourceMap source{pair.map, "one building",
                         loadMapFile(test::sharedDataPath(std::string("maps/") + pair.map))};
  MergeCase merge_case = makeCase(source, pair.a, source, pair.b);
  merge_case.id = pair.case_id;
  return merge_case;
}

/// Case 0 of `--seed 1` (the Intel lab, 28 % overlap): the exhaustive step places it within the
/// tolerance, and the chain's checks run on it.
inline const CropPair kIntelCaseZeroOfSeedOne{
    "carpin-intel.txt",
    0,
    {{143, 420}, 263, -0.33844691394674564, {28, 6}, {3, 35}},
    {{169, 196}, 308, -0.19328004906128005, {34, 23}, {9, 26}}};

/// A `width` × `height` grid of unknown cells, to be filled by hand.
inline GridMap unknownMap(int width, int height) {
  GridGeometry geometry;
  geometry.width = width;
  geometry.height = height;
  return GridMap(geometry, GridMap::kUnknown);
}

/// Crops of two buildings (a negative case of `mrslam merge-cases`).
struct TwoBuildings {
  const char* map_a;
  CropSpec a;
  const char* map_b;
  CropSpec b;
};

inline MergeCase cut(const TwoBuildings& pair) {
  const auto source = [](const char* name) {
    return SourceMap{name, name, loadMapFile(test::sharedDataPath(std::string("maps/") + name))};
  };
  return makeCase(source(pair.map_a), pair.a, source(pair.map_b), pair.b);
}

/// The exhaustive search over every rotation of the full turn (a merge config's section): cases
/// found before the search was kept near the walls' turns (`rotation_peaks`), where a rule
/// decides the case only when the search proposes every rotation's transforms.
inline const std::string kEveryRotation = "exhaustive: {rotation_peaks: 0}\n";

/// A structure bar of 0.88 (a `seed:` section's body): cases whose
/// wrong placement's walls meet walls 0.88 to 0.89 of the time were found at it, where another
/// rule decides the case; the default bar (0.89) refuses such a placement on its own.
inline const std::string kStructureBarAt088 = "min_structure_agreement: 0.88";

/// The chain merger with the settings of `yaml` (a merge config's sections) over its defaults.
inline std::unique_ptr<MapMerger> chainFrom(const std::string& yaml) {
  return makeMergerFrom("chain", Config::loadString(yaml, "merge.yaml"));
}

/// The chain's first two default steps (a `chain:` section's `steps`, "key: value" of a flow
/// mapping): the checks of the exhaustive and seed steps decide a case as they did before the
/// virtual robot became the default's third step, which may place a case both refuse.
inline const std::string kFirstTwoSteps = "steps: \"exhaustive,seed\"";

/// The default steps without the strict search (a `chain:` section's `steps`): cases that step
/// places itself are decided by the others as before it became the default's second step.
inline const std::string kWithoutTheStrictSearch = "steps: \"exhaustive,seed,virtual\"";

/// The chain of the first two default steps with `chain_body` ("key: value, ...") as the rest of
/// its `chain:` section and `rest` (a merge config's other sections) over the defaults.
inline std::unique_ptr<MapMerger> chainOfTwoSteps(const std::string& chain_body = "",
                                                  const std::string& rest = "") {
  return chainFrom("chain: {" + kFirstTwoSteps + (chain_body.empty() ? "" : ", " + chain_body) +
                   "}\n" + rest);
}

/// The chain merger with `seed_section` (a flow mapping's body, "key: value, ...") as its `seed:`
/// settings over the defaults.
inline std::unique_ptr<MapMerger> chainWithSeed(const std::string& seed_section) {
  return chainFrom("seed: {" + seed_section + "}\n");
}

/// How far `T_b_a` turns from the case's truth, degrees.
inline double angleErrorDeg(const MergeCase& merge_case, const GridTransform& T_b_a) {
  return caseError(merge_case, T_b_a).angle_rad * 180.0 / M_PI;
}

/// Merges a case's crops with `merger`, expecting an accepted transform within 2 cells and 1° of
/// the truth; returns the result for further checks.
inline MergeResult expectMergedWithinTwoCellsAndOneDegree(const MergeCase& merge_case,
                                                          MapMerger& merger) {
  const MergeResult result = merger.merge(merge_case.a, merge_case.b);
  const CaseError error = caseError(merge_case, result.T_to_from);
  EXPECT_TRUE(result.accepted) << "case " << merge_case.id << ": " << result.reason;
  EXPECT_TRUE(isCorrect(error)) << "case " << merge_case.id << ": " << error.distance_cells
                                << " cells, " << error.angle_rad * 180.0 / M_PI << "°";
  return result;
}

/// The same for a pair's crops.
inline MergeResult expectMergedWithinTwoCellsAndOneDegree(const CropPair& pair, MapMerger& merger) {
  return expectMergedWithinTwoCellsAndOneDegree(cut(pair), merger);
}

/// Expects the default chain to merge a pair's crops within the tolerance, and returns what the
/// chain with `yaml` (chainFrom()) makes of the same crops: a setting that decides the case.
inline MergeResult mergedRightByDefaultThenWith(const CropPair& pair, const std::string& yaml) {
  const MergeCase merge_case = cut(pair);
  expectMergedWithinTwoCellsAndOneDegree(merge_case, *makeMerger(defaultMergerName()));
  return chainFrom(yaml)->merge(merge_case.a, merge_case.b);
}

/// Merges a case's crops with `merger`, expecting no accepted transform but a correct one.
inline void expectNoWrongAccept(const MergeCase& merge_case, MapMerger& merger) {
  const MergeResult result = merger.merge(merge_case.a, merge_case.b);
  if (result.accepted) {
    EXPECT_TRUE(isCorrect(caseError(merge_case, result.T_to_from))) << "case " << merge_case.id;
  }
}

/// The same for a pair's crops.
inline void expectNoWrongAccept(const CropPair& pair, MapMerger& merger) {
  expectNoWrongAccept(cut(pair), merger);
}

/// `found` holds `reference`'s hypotheses in its order, each transform and score bit for bit:
/// a search done another way (prepared once, on kept buffers) that must change nothing.
template <typename Hypothesis>
void expectTheSameHypotheses(const std::vector<Hypothesis>& found,
                             const std::vector<Hypothesis>& reference) {
  ASSERT_FALSE(reference.empty());
  ASSERT_EQ(found.size(), reference.size());
  for (std::size_t i = 0; i < found.size(); ++i) {
    EXPECT_EQ(found[i].T_to_from.theta_rad, reference[i].T_to_from.theta_rad) << i;
    EXPECT_EQ(found[i].T_to_from.t_cells, reference[i].T_to_from.t_cells) << i;
    EXPECT_EQ(found[i].score, reference[i].score) << i;
  }
}

}  // namespace mrslam::fusion::merge_test
