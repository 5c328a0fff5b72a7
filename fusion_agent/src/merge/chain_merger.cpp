#include "mrslam/fusion/merge/chain_merger.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace mrslam::fusion {

ChainMerger::ChainMerger(std::vector<std::unique_ptr<MapMerger>> steps) : steps_(std::move(steps)) {
  if (steps_.empty()) {
    throw std::invalid_argument("a merge chain needs at least one step");
  }
}

MergeResult ChainMerger::merge(const GridMap& from, const GridMap& to) {
  std::string reasons;
  int trials = 0;
  MergeResult last;
  for (const auto& step : steps_) {
    MergeResult result = step->merge(from, to);
    trials += result.trials;
    if (result.accepted) {
      result.trials = trials;
      return result;
    }
    reasons += (reasons.empty() ? "" : "; ") + step->name() + ": " + result.reason;
    last = std::move(result);
  }
  last.method = name();
  last.trials = trials;
  last.reason = reasons;
  return last;
}

std::vector<std::string> parseChainSteps(const std::string& steps) {
  std::vector<std::string> names;
  std::stringstream text(steps);
  std::string name;
  while (std::getline(text, name, ',')) {
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    if (name.empty()) {
      continue;
    }
    if (name == "chain") {
      throw std::invalid_argument("a merge chain cannot hold a chain");
    }
    if (std::find(names.begin(), names.end(), name) != names.end()) {
      throw std::invalid_argument("merge chain step '" + name + "' is given twice");
    }
    names.push_back(name);
  }
  if (names.empty()) {
    throw std::invalid_argument("a merge chain needs at least one step");
  }
  return names;
}

}  // namespace mrslam::fusion
