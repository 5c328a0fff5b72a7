#include "mrslam/fusion/merge/merger_registry.hpp"

#include <stdexcept>

#include "mrslam/fusion/merge/chain_merger.hpp"
#include "mrslam/fusion/merge/exhaustive_merger.hpp"
#include "mrslam/fusion/merge/feature_merger.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"
#include "mrslam/fusion/merge/virtual_robot.hpp"

namespace mrslam::fusion {

std::vector<std::string> mergerNames() {
  // Best first, as measured by `mrslam merge-cases` (docs/merge_tuning.md).
  return {"chain", "seed", "exhaustive", "virtual", "feature"};
}

std::string defaultMergerName() {
  return mergerNames().front();
}

namespace {

/// A chain whose `steps` come from `chain`; each step's settings from its section of `methods`,
/// or its defaults when there is none.
std::unique_ptr<MapMerger> makeChain(const Config& chain, const Config* methods) {
  std::vector<std::unique_ptr<MapMerger>> steps;
  try {
    for (const std::string& step : parseChainSteps(chain.getString("steps", kDefaultChainSteps))) {
      steps.push_back(methods != nullptr ? makeMergerFrom(step, *methods) : makeMerger(step));
    }
  } catch (const std::invalid_argument& error) {
    chain.fail("steps", error.what());
  }
  const SeedMergerSettings judge =
      methods != nullptr ? loadSeedMergerSettings(methods->section("seed")) : SeedMergerSettings{};
  auto merger = std::make_unique<ChainMerger>(std::move(steps), loadChainSettings(chain), judge);
  // Every step's judge and the chain's have the `seed:` settings (or all the defaults): one pair's
  // search inputs, built once each way, serve them all.
  merger->shareSearchInputs(std::make_shared<SearchInputsCache>());
  return merger;
}

/// The mergers whose hypotheses the seed pipeline's acceptance judges: their own settings and the
/// seed merger's (`judge`).
std::unique_ptr<MapMerger> makeJudgedMerger(const std::string& name, const Config& settings,
                                            const SeedMergerSettings& judge) {
  if (name == "virtual") {
    return std::make_unique<VirtualRobotMerger>(loadVirtualRobotSettings(settings), judge);
  }
  if (name == "exhaustive") {
    return std::make_unique<ExhaustiveMerger>(loadExhaustiveMergerSettings(settings), judge);
  }
  return nullptr;
}

}  // namespace

std::unique_ptr<MapMerger> makeMergerFrom(const std::string& name, const Config& methods) {
  if (name == "chain") {
    return makeChain(methods.section("chain"), &methods);
  }
  if (name == "virtual" || name == "exhaustive") {  // judged with the `seed:` section's settings
    return makeJudgedMerger(name, methods.section(name),
                            loadSeedMergerSettings(methods.section("seed")));
  }
  return makeMerger(name, methods.section(name));
}

std::unique_ptr<MapMerger> makeMerger(const std::string& name, const Config& settings) {
  if (name == "seed") {
    return std::make_unique<SeedMerger>(loadSeedMergerSettings(settings));
  }
  if (name == "feature") {
    return std::make_unique<FeatureMerger>(loadFeatureMergerSettings(settings));
  }
  if (auto judged = makeJudgedMerger(name, settings, SeedMergerSettings{})) {
    return judged;
  }
  if (name == "chain") {
    return makeChain(settings, nullptr);
  }
  std::string known;
  for (const std::string& candidate : mergerNames()) {
    known += (known.empty() ? "" : ", ") + candidate;
  }
  throw std::invalid_argument("unknown merge method '" + name + "' (known: " + known + ")");
}

void checkMergerConfig(const Config& config) {
  for (const std::string& name : mergerNames()) {
    if (config.has(name)) {
      makeMergerFrom(name, config);
    }
  }
  config.checkNoUnknownKeys();
}

std::unique_ptr<MapMerger> makeMerger(const std::string& name) {
  return makeMerger(name, Config::loadString("", "<default " + name + " settings>"));
}

}  // namespace mrslam::fusion
