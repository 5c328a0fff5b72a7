#include "mrslam/fusion/merge/merger_registry.hpp"

#include <optional>
#include <sstream>
#include <stdexcept>

#include "mrslam/fusion/merge/chain_merger.hpp"
#include "mrslam/fusion/merge/exhaustive_merger.hpp"
#include "mrslam/fusion/merge/feature_merger.hpp"
#include "mrslam/fusion/merge/psi_walk_merger.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"
#include "mrslam/fusion/merge/virtual_robot.hpp"

namespace mrslam::fusion {

std::vector<std::string> mergerNames() {
  // Best first, as measured by `mrslam merge-cases` (docs/merge_tuning.md).
  return {"chain", "seed", "exhaustive", "exhaustive_strict", "psi_walk", "virtual", "feature"};
}

std::string defaultMergerName() {
  return mergerNames().front();
}

namespace {

/// What a method name "chain:STEP+STEP[+psi]" changes in the `chain:` section's settings.
struct ChainVariant {
  std::string name;   ///< the method name it was read from
  std::string steps;  ///< comma-separated, as `steps` holds them
  bool refine_psi = false;
};

constexpr const char* kChainVariantPrefix = "chain:";
/// The last token of a chain variant that refines its accepted transforms by ψ (refine_psi).
constexpr const char* kPsiToken = "psi";

/// The variant a method name gives, or none for a name that is not "chain:...".
std::optional<ChainVariant> chainVariantOf(const std::string& name) {
  const std::string prefix = kChainVariantPrefix;
  if (name.compare(0, prefix.size(), prefix) != 0) {
    return std::nullopt;
  }
  std::vector<std::string> tokens;
  std::stringstream text(name.substr(prefix.size()));
  std::string token;
  while (std::getline(text, token, '+')) {
    tokens.push_back(token);
  }
  ChainVariant variant;
  variant.name = name;
  if (!tokens.empty() && tokens.back() == kPsiToken) {
    variant.refine_psi = true;
    tokens.pop_back();
  }
  for (const std::string& step : tokens) {
    if (step == kPsiToken) {
      throw std::invalid_argument("merge method '" + name +
                                  "': psi refines the accepted transform, so it comes last");
    }
    variant.steps += (variant.steps.empty() ? "" : ",") + step;
  }
  return variant;
}

/// A chain whose steps come from `variant` when given, else from `chain`'s `steps`; each step's
/// settings from its section of `methods`, or its defaults when there is none.
std::unique_ptr<MapMerger> makeChain(const Config& chain, const Config* methods,
                                     const std::optional<ChainVariant>& variant = std::nullopt) {
  std::vector<std::unique_ptr<MapMerger>> steps;
  const std::string names = variant ? variant->steps : chain.getString("steps", kDefaultChainSteps);
  try {
    for (const std::string& step : parseChainSteps(names)) {
      steps.push_back(methods != nullptr ? makeMergerFrom(step, *methods) : makeMerger(step));
    }
  } catch (const std::invalid_argument& error) {
    if (variant) {
      throw std::invalid_argument("merge method '" + variant->name + "': " + error.what());
    }
    chain.fail("steps", error.what());
  }
  const SeedMergerSettings judge =
      methods != nullptr ? loadSeedMergerSettings(methods->section("seed")) : SeedMergerSettings{};
  ChainSettings settings = loadChainSettings(chain);
  if (variant) {
    settings.refine_psi = variant->refine_psi;
  }
  auto merger = std::make_unique<ChainMerger>(std::move(steps), settings, judge);
  // Every step's judge and the chain's have the `seed:` settings (or all the defaults): one pair's
  // search inputs, built once each way, serve them all.
  merger->shareSearchInputs(std::make_shared<SearchInputsCache>());
  return merger;
}

/// The mergers whose hypotheses the seed pipeline's acceptance judges (makeJudgedMerger).
bool isJudgedMerger(const std::string& name) {
  return name == "virtual" || name == "exhaustive" || name == "exhaustive_strict" ||
         name == "psi_walk";
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
  if (name == "exhaustive_strict") {
    return std::make_unique<ExhaustiveMerger>(
        loadExhaustiveMergerSettings(settings, strictExhaustiveMergerSettings()), judge, name);
  }
  if (name == "psi_walk") {
    return std::make_unique<PsiWalkMerger>(loadPsiWalkSettings(settings), judge);
  }
  return nullptr;
}

}  // namespace

std::unique_ptr<MapMerger> makeMergerFrom(const std::string& name, const Config& methods) {
  if (name == "chain") {
    return makeChain(methods.section("chain"), &methods);
  }
  if (const std::optional<ChainVariant> variant = chainVariantOf(name)) {
    return makeChain(methods.section("chain"), &methods, variant);
  }
  if (isJudgedMerger(name)) {  // judged with the `seed:` section's settings
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
  if (const std::optional<ChainVariant> variant = chainVariantOf(name)) {
    return makeChain(settings, nullptr, variant);
  }
  std::string known;
  for (const std::string& candidate : mergerNames()) {
    known += (known.empty() ? "" : ", ") + candidate;
  }
  throw std::invalid_argument("unknown merge method '" + name + "' (known: " + known +
                              ", or chain:STEP+STEP[+psi] for a chain of those steps)");
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
