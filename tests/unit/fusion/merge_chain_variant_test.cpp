// Chain variants by name ("chain:STEP+STEP[+psi]"): their own steps and ψ refinement, the chain
// section's other settings, and clear errors for names that make no chain.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/chain_merger.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::CropPair;
using merge_test::cut;

/// The message makeMergerFrom(name) stops with (std::invalid_argument), empty when it builds.
std::string refusalOf(const std::string& name) {
  try {
    makeMergerFrom(name, Config::loadString("", "merge.yaml"));
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(MergeChainVariantTest, ANameGivesTheStepsAndPsiComesLast) {
  const Config defaults = Config::loadString("", "merge.yaml");
  EXPECT_EQ(makeMergerFrom("chain:seed+virtual+psi", defaults)->name(), "chain");
  EXPECT_EQ(makeMerger("chain:exhaustive+seed")->name(), "chain");
  EXPECT_THAT(refusalOf("chain:"), testing::HasSubstr("'chain:': a merge chain needs at least"));
  EXPECT_THAT(refusalOf("chain:psi"), testing::HasSubstr("needs at least one step"));
  EXPECT_THAT(refusalOf("chain:psi+seed"),
              testing::HasSubstr("'chain:psi+seed': psi refines the accepted transform, so it "
                                 "comes last"));
  EXPECT_THAT(refusalOf("chain:seed+seed"), testing::HasSubstr("step 'seed' is given twice"));
  EXPECT_THAT(refusalOf("chain:seed+chain:feature"),
              testing::HasSubstr("a merge chain cannot hold a chain"));
  EXPECT_THAT(refusalOf("chain:seed+magic"),
              testing::HasSubstr("'chain:seed+magic': unknown merge method 'magic'"));
  EXPECT_THAT(refusalOf("magic"), testing::HasSubstr("or chain:STEP+STEP[+psi]"));
}

TEST(MergeChainVariantTest, AVariantReadsTheChainSectionAndItsStepsSections) {
  // Its steps take their own sections, as the configured chain's do ...
  const Config bad_step =
      Config::loadString("chain: {steps: seed}\nfeature: {detector: sift}\n", "merge.yaml");
  EXPECT_THROW(makeMergerFrom("chain:feature", bad_step), ConfigError);
  EXPECT_NO_THROW(makeMergerFrom("chain:seed", bad_step));
  // ... and its other settings are the chain section's.
  const Config bad_chain = Config::loadString("chain: {sweep_step_deg: 200}\n", "merge.yaml");
  EXPECT_THROW(makeMergerFrom("chain:seed", bad_chain), ConfigError);
}

// Case 5 of `mrslam merge-cases --seed 1 --cases 12` (LongRun6, 74 % overlap): the feature
// baseline's transform lies 0.66 cells from the truth at V 0.966; Carpin's ψ random walk moves it
// to 0.31 cells at V 0.979.
const CropPair kLongRunFeatureCase{"carpin-LongRun6.txt",
                                   5,
                                   {{354, 4}, 161, 0.4925364292621306, {13, 38}, {39, 23}},
                                   {{266, 61}, 301, 2.5345082509333574, {34, 6}, {30, 25}}};

TEST(MergeChainVariantTest, PsiAtTheEndRefinesTheAcceptedTransformTowardsTheTruth) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-LongRun6.txt");
  const MergeCase merge_case = cut(kLongRunFeatureCase);
  // psi in the chain section does not reach a variant without it: the name says it all.
  const Config psi_section = Config::loadString("chain: {refine_psi: true}\n", "merge.yaml");
  const MergeResult plain =
      makeMergerFrom("chain:feature", psi_section)->merge(merge_case.a, merge_case.b);
  const MergeResult refined =
      makeMergerFrom("chain:feature+psi", Config::loadString("", "merge.yaml"))
          ->merge(merge_case.a, merge_case.b);
  ASSERT_TRUE(plain.accepted) << plain.reason;
  ASSERT_TRUE(refined.accepted) << refined.reason;
  EXPECT_EQ(plain.method, "feature");
  EXPECT_EQ(refined.method, "feature+psi");
  EXPECT_GT(refined.verification, plain.verification + 0.005);
  const CaseError before = caseError(merge_case, plain.T_to_from);
  const CaseError after = caseError(merge_case, refined.T_to_from);
  EXPECT_GT(before.distance_cells, 0.6);
  EXPECT_LT(after.distance_cells, 0.4);
  EXPECT_LT(after.angle_rad, 0.1 * M_PI / 180.0);
}

}  // namespace
}  // namespace mrslam::fusion
