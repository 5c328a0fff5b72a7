#include "mrslam/fusion/merge/merger_registry.hpp"

#include <stdexcept>

#include "mrslam/fusion/merge/feature_merger.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion {

std::vector<std::string> mergerNames() {
  return {"seed", "feature"};
}

std::string defaultMergerName() {
  return mergerNames().front();
}

std::unique_ptr<MapMerger> makeMerger(const std::string& name, const Config& settings) {
  if (name == "seed") {
    return std::make_unique<SeedMerger>(loadSeedMergerSettings(settings));
  }
  if (name == "feature") {
    return std::make_unique<FeatureMerger>(loadFeatureMergerSettings(settings));
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
      makeMerger(name, config.section(name));
    }
  }
  config.checkNoUnknownKeys();
}

std::unique_ptr<MapMerger> makeMerger(const std::string& name) {
  return makeMerger(name, Config::loadString("", "<default " + name + " settings>"));
}

}  // namespace mrslam::fusion
