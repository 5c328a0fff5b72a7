// The seed pipeline's search inputs kept for a chain (SearchInputsCache): a pair's inputs, built
// once each way, serve the steps' judges and the chain's own, and the way back reuses the wall
// fields of the way there. None of it may change what the chain decides.

#include <gtest/gtest.h>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/chain_merger.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::CropPair;
using merge_test::TwoBuildings;

/// The default chain, every judge of it building its inputs again at every call (the cache it
/// hands its judge and steps holds no pair).
std::unique_ptr<MapMerger> chainBuildingEveryInput() {
  std::vector<std::unique_ptr<MapMerger>> steps;
  for (const std::string& name : parseChainSteps(kDefaultChainSteps)) {
    steps.push_back(makeMerger(name));
  }
  auto chain = std::make_unique<ChainMerger>(
      std::move(steps), loadChainSettings(Config::loadString("{}", "chain.yaml")),
      SeedMergerSettings{});
  chain->shareSearchInputs(std::make_shared<SearchInputsCache>(0));
  return chain;
}

TEST(SearchInputsTest, AChainThatKeepsThemDecidesAsOneThatBuildsThemEveryTime) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-aces.pgm");
  // Cases 2 (Carpin's robot 3, 63 % overlap, merged by the exhaustive step) and 82 (ACES, 46 %,
  // merged by the seed step) and negative case 201 (ACES and Carpin's robot 3) of `--seed 1`:
  // each both ways, one after the other, so that the cache of two pairs holds both ways of one
  // pair and lets go of the one before.
  const CropPair robot3{"carpin-robot3_cast.txt",
                        2,
                        {{-21, 43}, 274, -1.6900799518023857, {35, 39}, {3, 0}},
                        {{125, 65}, 305, -0.04360786023670249, {16, 10}, {40, 23}}};
  const CropPair aces{"freiburg-aces.pgm",
                      82,
                      {{704, -14}, 220, -0.3748103292460949, {3, 33}, {21, 2}},
                      {{787, 128}, 283, -2.9149687238277573, {11, 2}, {16, 2}}};
  const TwoBuildings apart{"freiburg-aces.pgm",
                           {{401, 438}, 284, -2.1885844958090224, {18, 30}, {0, 6}},
                           "carpin-robot3_cast.txt",
                           {{-7, 141}, 192, 0.33750050103913498, {1, 3}, {26, 15}}};
  const MergeCase cases[] = {merge_test::cut(robot3), merge_test::cut(aces),
                             merge_test::cut(apart)};
  const std::unique_ptr<MapMerger> keeping = makeMerger("chain");
  const std::unique_ptr<MapMerger> building = chainBuildingEveryInput();
  int accepted = 0;  // of the right transform
  for (const MergeCase& merge_case : cases) {
    for (const bool back : {false, true}) {
      const GridMap& from = back ? merge_case.b : merge_case.a;
      const GridMap& to = back ? merge_case.a : merge_case.b;
      const MergeResult kept = keeping->merge(from, to);
      merge_test::expectTheSameDecision(
          kept, building->merge(from, to),
          "case " + std::to_string(merge_case.id) + (back ? " back" : ""));
      accepted +=
          kept.accepted &&
                  isCorrect(caseError(merge_case, back ? kept.T_to_from.inverse() : kept.T_to_from))
              ? 1
              : 0;
    }
  }
  EXPECT_GE(accepted, 3) << "the rules that judge an accepted transform ran too";
}

}  // namespace
}  // namespace mrslam::fusion
