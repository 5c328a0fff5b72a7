// The chain's rivals from earlier steps (ChainSettings::slid_rivals): a transform an earlier step
// refused only because a slide scored almost as well faces a later step's accepted transform as
// a rival. Real crops of a building whose wings repeat, cut as `mrslam merge-cases` cuts them.

#include <gtest/gtest.h>

#include <cmath>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/chain_merger.hpp"
#include "mrslam/fusion/merge/exhaustive_merger.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"
#include "mrslam/fusion/merge/similarity.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::CropPair;
using merge_test::cut;

// Case 111 of `--seed 6` (35 % overlap): the exhaustive search finds the truth. Counting every
// rival, it refuses it, as the wrong wing explains the overlap as well (before walls outweighed
// open floor: as a shift of 3 cells along the corridor scored 0.985 of it); the seed pipeline then
// accepts a transform 90 cells (4.5 m) along the building, where a wing like the true one lies
// (V 0.964). The wrong wing is a dirtier rival, passed over by default: the truth is accepted.
const CropPair kRepeatingWing{"carpin-robot2_cast.txt",
                              111,
                              {{54, -99}, 230, 1.8453411708725067, {3, 27}, {27, 0}},
                              {{-197, -153}, 279, -0.2386419275941707, {4, 36}, {27, 19}}};

// The seed pipeline's transform of that case, 89.8 cells and 0.16° from the truth.
GridTransform wrongWing() {
  GridTransform T_to_from;
  T_to_from.theta_rad = -2.0868469415147692;
  T_to_from.t_cells = Eigen::Vector2d(237.9840103708645, 412.28618633229991);
  return T_to_from;
}

// The truth turned by a quarter about the centre of crop A's known cells: a transform that
// explains little of the overlap.
GridTransform quarterTurned(const MergeCase& merge_case) {
  const Eigen::Vector2d centre = knownCentroid(merge_case.a);
  GridTransform turned = merge_case.T_b_a;
  turned.theta_rad += 0.5 * M_PI;
  turned.t_cells += merge_case.T_b_a.apply(centre) - turned.apply(centre);
  return turned;
}

/// A chain step with a set answer: the chain's use of it is under test.
class SetAnswer : public MapMerger {
 public:
  SetAnswer(std::string name, MergeResult answer)
      : name_(std::move(name)), answer_(std::move(answer)) {}
  MergeResult merge(const GridMap&, const GridMap&) override { return answer_; }
  std::string name() const override { return name_; }

 private:
  std::string name_;
  MergeResult answer_;
};

MergeResult refusedAt(const GridTransform& T_to_from, MergeRefusal kind) {
  MergeResult result;
  result.T_to_from = T_to_from;
  result.refusal = kind;
  result.reason = "refused by its own test";
  return result;
}

MergeResult acceptedAt(const GridTransform& T_to_from) {
  MergeResult result;
  result.accepted = true;
  result.T_to_from = T_to_from;
  result.method = "later";
  return result;
}

MergeResult chainOf(const MergeResult& first, const MergeResult& second, bool slid_rivals,
                    const MergeCase& merge_case) {
  std::vector<std::unique_ptr<MapMerger>> steps;
  steps.push_back(std::make_unique<SetAnswer>("earlier", first));
  steps.push_back(std::make_unique<SetAnswer>("later", second));
  ChainSettings settings;
  settings.slid_rivals = slid_rivals;
  settings.sweep_rivals = false;  // it refuses the wrong wing too: the slid rival is under test
  settings.floor_crossing_min_cells = 0;  // so does the floor-crossing check
  ChainMerger chain(std::move(steps), settings);
  return chain.merge(merge_case.a, merge_case.b);
}

MergeResult exhaustiveWith(const MergeCase& merge_case, const std::string& seed_settings) {
  return makeMergerFrom("exhaustive", Config::loadString("exhaustive: {hypotheses: 16}\nseed: {" +
                                                             seed_settings + "}\n",
                                                         "merge.yaml"))
      ->merge(merge_case.a, merge_case.b);
}

TEST(MergeChainRivalsTest, TheExhaustiveStepFindsTheTruthOfTheRepeatingWing) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot2_cast.txt");
  const MergeCase merge_case = cut(kRepeatingWing);
  // The wrong wing covers more cells but fits them worse (a dirtier rival): the truth stands.
  const MergeResult accepted = exhaustiveWith(merge_case, "");
  ASSERT_TRUE(accepted.accepted) << accepted.reason;
  EXPECT_TRUE(isCorrect(caseError(merge_case, accepted.T_to_from)))
      << caseError(merge_case, accepted.T_to_from).distance_cells << " cells from the truth";
  // Every rival counted, the wrong wing refuses it; before walls outweighed open floor
  // (walls_over_floor_min_v), the slide refused it.
  for (const bool walls_over_floor : {true, false}) {
    const MergeResult result = exhaustiveWith(
        merge_case, walls_over_floor ? "dirtier_rival_structure: 0"
                                     : "dirtier_rival_structure: 0, walls_over_floor_min_v: 2");
    ASSERT_FALSE(result.accepted);
    EXPECT_EQ(result.refusal, walls_over_floor ? MergeRefusal::kRival : MergeRefusal::kTranslation)
        << result.reason;
    EXPECT_TRUE(isCorrect(caseError(merge_case, result.T_to_from)))
        << caseError(merge_case, result.T_to_from).distance_cells << " cells from the truth";
  }
}

TEST(MergeChainRivalsTest, TheTwoWingsAreEachOthersRivalsUnlessTheDirtierIsPassedOver) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot2_cast.txt");
  const MergeCase merge_case = cut(kRepeatingWing);
  ASSERT_GT(caseError(merge_case, wrongWing()).distance_cells, 80.0);
  // At the structure bar of 0.88: the wrong wing's walls meet walls less than 0.89 of the time.
  SeedMergerSettings bar_of_088;
  bar_of_088.min_structure_agreement = 0.88;
  SeedMergerSettings every_rival = bar_of_088;
  every_rival.dirtier_rival_structure = 0.0;
  SeedMerger judge(every_rival);
  const double max_share = judge.settings().max_rival_share;
  // The truth's known cells disagree half as often (a cleaner rival, share 1); the wrong wing's
  // overlap is three times larger, and so is its agr - dis. Every rival counted, block 9 cannot
  // tell them apart.
  EXPECT_GT(judge.rivalShareAgainst(merge_case.a, merge_case.b, wrongWing(), {merge_case.T_b_a}),
            max_share);
  EXPECT_GT(judge.rivalShareAgainst(merge_case.a, merge_case.b, merge_case.T_b_a, {wrongWing()}),
            max_share);
  EXPECT_EQ(judge.rivalShareAgainst(merge_case.a, merge_case.b, wrongWing(), {}), 0.0);
  EXPECT_LE(judge.rivalShareAgainst(merge_case.a, merge_case.b, merge_case.T_b_a,
                                    {quarterTurned(merge_case)}),
            max_share);
  // With the dirtier rivals passed over (the default), the wrong wing, whose walls meet walls less
  // well and whose cells disagree more often, is no rival of the truth; the truth still rivals the
  // wrong wing.
  SeedMerger by_default(bar_of_088);
  EXPECT_LE(
      by_default.rivalShareAgainst(merge_case.a, merge_case.b, merge_case.T_b_a, {wrongWing()}),
      max_share);
  EXPECT_GT(
      by_default.rivalShareAgainst(merge_case.a, merge_case.b, wrongWing(), {merge_case.T_b_a}),
      max_share);
  // At the default bar the wrong wing fails the structure test on its own: no rival at all.
  SeedMerger at_default_bar;
  EXPECT_EQ(
      at_default_bar.rivalShareAgainst(merge_case.a, merge_case.b, merge_case.T_b_a, {wrongWing()}),
      0.0);
  const MergeResult wing_alone =
      at_default_bar.judgeHypotheses(merge_case.a, merge_case.b, {wrongWing()});
  EXPECT_FALSE(wing_alone.accepted);
  EXPECT_EQ(wing_alone.refusal, MergeRefusal::kStructure) << wing_alone.reason;
}

TEST(MergeChainRivalsTest, ALaterStepsTransformIsRefusedWhenAnEarlierSlidOneIsItsRival) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot2_cast.txt");
  const MergeCase merge_case = cut(kRepeatingWing);
  const MergeResult slid_truth = refusedAt(merge_case.T_b_a, MergeRefusal::kTranslation);
  const MergeResult refused = chainOf(slid_truth, acceptedAt(wrongWing()), true, merge_case);
  EXPECT_FALSE(refused.accepted);
  EXPECT_NE(refused.reason.find("later: a transform an earlier step refused explains the overlap"),
            std::string::npos)
      << refused.reason;
  // Off, the later step's transform stands: the setting decides.
  EXPECT_TRUE(chainOf(slid_truth, acceptedAt(wrongWing()), false, merge_case).accepted);
  // Only a slide counts: a transform refused for another test found nothing to rely on.
  EXPECT_TRUE(chainOf(refusedAt(merge_case.T_b_a, MergeRefusal::kEntropy), acceptedAt(wrongWing()),
                      true, merge_case)
                  .accepted);
}

TEST(MergeChainRivalsTest, AnEarlierSlidTransformThatExplainsLittleDoesNotRefuseTheTruth) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot2_cast.txt");
  const MergeCase merge_case = cut(kRepeatingWing);
  const MergeResult result =
      chainOf(refusedAt(quarterTurned(merge_case), MergeRefusal::kTranslation),
              acceptedAt(merge_case.T_b_a), true, merge_case);
  EXPECT_TRUE(result.accepted) << result.reason;
  EXPECT_EQ(result.method, "later");
}

// The wing case merged by a chain with these `chain:` and `seed:` settings (over the structure
// bar of 0.88) and 16 exhaustive hypotheses.
MergeResult mergeWingWith(const MergeCase& merge_case, const std::string& chain_settings,
                          const std::string& seed_settings = "dirtier_rival_structure: 0") {
  const std::string seed = merge_test::kStructureBarAt088 +
                           (seed_settings.empty() ? std::string() : ", " + seed_settings);
  return makeMergerFrom("chain", Config::loadString("chain: {" + chain_settings +
                                                        "}\nexhaustive: {hypotheses: 16}\n" +
                                                        "seed: {" + seed + "}\n",
                                                    "m.yaml"))
      ->merge(merge_case.a, merge_case.b);
}

TEST(MergeChainRivalsTest, TheConfiguredChainDoesNotAcceptTheWrongWing) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot2_cast.txt");
  const MergeCase merge_case = cut(kRepeatingWing);
  const MergeResult result = mergeWingWith(merge_case, "slid_rivals: true", "");
  ASSERT_TRUE(result.accepted) << result.reason;
  EXPECT_TRUE(isCorrect(caseError(merge_case, result.T_to_from)))
      << caseError(merge_case, result.T_to_from).distance_cells << " cells from the truth";
  // Every rival counted (the wrong wing refuses the truth), the chain's own checks decide.
  const std::string unchecked =
      "slid_rivals: false, sweep_rivals: false, cleaner_alternative_rate: 0";
  const MergeResult wrong = mergeWingWith(merge_case, unchecked + ", floor_crossing_min_cells: 0");
  ASSERT_TRUE(wrong.accepted) << "without the earlier rival, the sweep, the alternatives and the "
                                 "floor-crossing check the wrong wing is taken";
  EXPECT_GT(caseError(merge_case, wrong.T_to_from).distance_cells, 80.0);
  const MergeResult swept = mergeWingWith(
      merge_case, "slid_rivals: false, cleaner_alternative_rate: 0, floor_crossing_min_cells: 0");
  EXPECT_FALSE(swept.accepted) << "the sweep finds the cleaner truth at the wrong wing's rotation";
  const MergeResult weighed = mergeWingWith(
      merge_case, "slid_rivals: false, sweep_rivals: false, floor_crossing_min_cells: 0");
  EXPECT_FALSE(weighed.accepted) << "the exhaustive search's own hypotheses hold the truth";
  EXPECT_NE(weighed.reason.find("another placement"), std::string::npos) << weighed.reason;
  const MergeResult crossing =
      mergeWingWith(merge_case, unchecked + ", floor_crossing_min_cells: 4");
  EXPECT_FALSE(crossing.accepted) << "the wrong wing's walls cross the other map's open floor";
  EXPECT_NE(crossing.reason.find("crosses the other's open floor"), std::string::npos)
      << crossing.reason;
}

TEST(MergeChainRivalsTest, TheSettingIsRead) {
  EXPECT_TRUE(ChainSettings{}.slid_rivals);  // `false` from a file: the test above
  EXPECT_TRUE(ChainSettings{}.sweep_rivals);
  const ChainSettings loaded = loadChainSettings(
      Config::loadString("sweep_step_deg: 2\nsweep_peaks: 8\nsweep_coarse_cells: 2\n", "m.yaml"));
  EXPECT_DOUBLE_EQ(loaded.sweep_step_deg, 2.0);
  EXPECT_EQ(loaded.sweep_peaks, 8);
  EXPECT_EQ(loaded.sweep_coarse_cells, 2);
  EXPECT_THROW(loadChainSettings(Config::loadString("sweep_peaks: 0\n", "m.yaml")), ConfigError);
  EXPECT_EQ(ChainSettings{}.sweep_prefilter_rate, 2.0);
  EXPECT_EQ(loadChainSettings(Config::loadString("sweep_prefilter_rate: 0\n", "m.yaml"))
                .sweep_prefilter_rate,
            0.0);
  EXPECT_THROW(loadChainSettings(Config::loadString("sweep_prefilter_rate: -1\n", "m.yaml")),
               ConfigError);
  EXPECT_THROW(makeMergerFrom("chain", Config::loadString("chain: {slid_rivals: 3}\n", "m.yaml")),
               ConfigError);
}

// Case 60 of `--seed 5` (34 % overlap), another robot's map of the building of the wings above:
// the exhaustive and seed steps place crop A 91 cells (4.5 m) along the building, at V 0.954, and
// neither search proposes the truth (V 0.989 at its place, 0.011 of its known cells disagreeing).
const CropPair kRepeatingRooms{"carpin-robot0_cast.txt",
                               60,
                               {{55, -72}, 202, 2.5837842604140846, {28, 34}, {19, 6}},
                               {{-145, -138}, 228, -2.467975408167685, {40, 5}, {40, 16}}};

// Case 85 of `--seed 5` (51 % overlap), ACES: at the truth's rotation a slide along the long
// corridors overlaps more (agr - dis 1.03 times the truth's) but is not cleaner.
const CropPair kAcesCorridors{"freiburg-aces.pgm",
                              85,
                              {{561, -38}, 320, -1.9365132230915805, {25, 39}, {31, 0}},
                              {{690, 1}, 254, -1.5614571367744312, {12, 15}, {27, 1}}};

std::unique_ptr<MapMerger> chainWithSweep(bool sweep_rivals) {
  // The floor-crossing check off: it refuses the repeated room too. The first two steps alone:
  // the strict search, the default's second step, proposes the truth itself (the last test).
  return makeMergerFrom(
      "chain",
      Config::loadString(std::string("chain: {sweep_rivals: ") + (sweep_rivals ? "true" : "false") +
                             ", floor_crossing_min_cells: 0, " + merge_test::kFirstTwoSteps +
                             "}\n"
                             "exhaustive: {hypotheses: 16}\n",
                         "m.yaml"));
}

TEST(MergeChainSweepRivalsTest, ARepeatedRoomIsRefusedForTheCleanerTruthAtItsRotation) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  const MergeCase merge_case = cut(kRepeatingRooms);
  const MergeResult wrong = chainWithSweep(false)->merge(merge_case.a, merge_case.b);
  ASSERT_TRUE(wrong.accepted) << "without the sweep the repeated room is taken";
  ASSERT_GT(caseError(merge_case, wrong.T_to_from).distance_cells, 80.0);
  SeedMerger judge;
  EXPECT_TRUE(
      judge.cleanerRivalAmong(merge_case.a, merge_case.b, wrong.T_to_from, {merge_case.T_b_a}));
  EXPECT_FALSE(
      judge.cleanerRivalAmong(merge_case.a, merge_case.b, merge_case.T_b_a, {wrong.T_to_from}));
  EXPECT_FALSE(judge.cleanerRivalAmong(merge_case.a, merge_case.b, wrong.T_to_from, {}));
  const MergeResult result = chainWithSweep(true)->merge(merge_case.a, merge_case.b);
  EXPECT_FALSE(result.accepted) << caseError(merge_case, result.T_to_from).distance_cells
                                << " cells from the truth";
  EXPECT_NE(result.reason.find("more cleanly"), std::string::npos) << result.reason;
}

// The strict search (conflicts cost 20) proposes the truth of the repeated room that neither
// search of the first two steps proposes, and the default chain places it there.
TEST(MergeChainSweepRivalsTest, TheStrictSearchPlacesTheRepeatedRoomRight) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  const MergeCase merge_case = cut(kRepeatingRooms);
  const MergeResult placed = merge_test::expectMergedWithinTwoCellsAndOneDegree(
      merge_case, *makeMerger(defaultMergerName()));
  EXPECT_EQ(placed.method, "exhaustive_strict");
}

// The default prefilter keeps the cleaner truth among the peaks placed (the test above); a bar
// below every peak's disagreement leaves none to place, and the repeated room is taken.
TEST(MergeChainSweepRivalsTest, APrefilterBelowEveryPeakLeavesNoRivalToPlace) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  const MergeCase merge_case = cut(kRepeatingRooms);
  const std::unique_ptr<MapMerger> chain =
      makeMergerFrom("chain", Config::loadString("chain: {sweep_prefilter_rate: 0.01, "
                                                 "floor_crossing_min_cells: 0}\n"
                                                 "exhaustive: {hypotheses: 16}\n",
                                                 "m.yaml"));
  const MergeResult result = chain->merge(merge_case.a, merge_case.b);
  EXPECT_TRUE(result.accepted) << result.reason;
  EXPECT_GT(caseError(merge_case, result.T_to_from).distance_cells, 80.0);
}

TEST(MergeChainSweepRivalsTest, ALargerSlideAlongCorridorsDoesNotRefuseTheTruth) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-aces.pgm");
  const std::unique_ptr<MapMerger> chain = chainWithSweep(true);
  merge_test::expectMergedWithinTwoCellsAndOneDegree(kAcesCorridors, *chain);
}

}  // namespace
}  // namespace mrslam::fusion
