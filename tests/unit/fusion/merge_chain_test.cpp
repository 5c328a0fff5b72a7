// The chain of mergers: steps in turn until one accepts, the result naming the step; its steps
// read from the config with each step's own settings.

#include "mrslam/fusion/merge/chain_merger.hpp"

#include <gtest/gtest.h>

#include "mrslam/fusion/merge/merger_registry.hpp"

namespace mrslam::fusion {
namespace {

/// A merger with a fixed answer: the chain's logic is what is under test here.
class FixedAnswer : public MapMerger {
 public:
  FixedAnswer(std::string name, bool accept, int* calls)
      : name_(std::move(name)), accept_(accept), calls_(calls) {}
  MergeResult merge(const GridMap&, const GridMap&) override {
    ++*calls_;
    MergeResult result;
    result.accepted = accept_;
    result.method = name_;
    result.trials = 2;
    result.reason = accept_ ? "" : name_ + " found nothing";
    return result;
  }
  std::string name() const override { return name_; }

 private:
  std::string name_;
  bool accept_;
  int* calls_;
};

TEST(MergeChainTest, StepsRunInTurnUntilOneAcceptsAndTheResultNamesIt) {
  int calls[3] = {0, 0, 0};
  std::vector<std::unique_ptr<MapMerger>> steps;
  steps.push_back(std::make_unique<FixedAnswer>("first", false, &calls[0]));
  steps.push_back(std::make_unique<FixedAnswer>("second", true, &calls[1]));
  steps.push_back(std::make_unique<FixedAnswer>("third", true, &calls[2]));
  ChainMerger chain(std::move(steps));
  const MergeResult result = chain.merge(GridMap(), GridMap());
  EXPECT_TRUE(result.accepted);
  EXPECT_EQ(result.method, "second");
  EXPECT_EQ(result.trials, 4);
  EXPECT_EQ(calls[0], 1);
  EXPECT_EQ(calls[1], 1);
  EXPECT_EQ(calls[2], 0) << "a step after an accepting one is not run";
}

TEST(MergeChainTest, ARefusalOfEveryStepGivesEveryReason) {
  int calls = 0;
  std::vector<std::unique_ptr<MapMerger>> steps;
  steps.push_back(std::make_unique<FixedAnswer>("first", false, &calls));
  steps.push_back(std::make_unique<FixedAnswer>("second", false, &calls));
  ChainMerger chain(std::move(steps));
  const MergeResult result = chain.merge(GridMap(), GridMap());
  EXPECT_FALSE(result.accepted);
  EXPECT_EQ(result.method, "chain");
  EXPECT_EQ(result.reason, "first: first found nothing; second: second found nothing");
}

TEST(MergeChainTest, StepsAreParsedAndCheckedAndTakeTheirOwnSettings) {
  EXPECT_EQ(parseChainSteps(" seed, virtual "), (std::vector<std::string>{"seed", "virtual"}));
  EXPECT_THROW(parseChainSteps(""), std::invalid_argument);
  EXPECT_THROW(parseChainSteps("seed,seed"), std::invalid_argument);
  EXPECT_THROW(parseChainSteps("seed,chain"), std::invalid_argument);
  const Config methods = Config::loadString(
      "chain: {steps: \"feature, seed\"}\nfeature: {detector: akaze}\n", "merge.yaml");
  EXPECT_EQ(makeMergerFrom("chain", methods)->name(), "chain");
  const Config unknown = Config::loadString("chain: {steps: \"seed, magic\"}\n", "merge.yaml");
  try {
    makeMergerFrom("chain", unknown);
    FAIL() << "an unknown step must stop the load";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("merge.yaml:1"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("magic"), std::string::npos) << error.what();
  }
  const Config bad_step_setting =
      Config::loadString("chain: {steps: feature}\nfeature: {detector: sift}\n", "merge.yaml");
  EXPECT_THROW(makeMergerFrom("chain", bad_step_setting), ConfigError);
}

}  // namespace
}  // namespace mrslam::fusion
