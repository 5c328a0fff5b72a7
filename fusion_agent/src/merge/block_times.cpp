#include "mrslam/fusion/merge/block_times.hpp"

#include <algorithm>

namespace mrslam::fusion {

void addBlockTime(BlockTimes& times, const std::string& name, double ms) {
  const auto entry = std::find_if(times.begin(), times.end(),
                                  [&](const BlockTime& time) { return time.name == name; });
  if (entry == times.end()) {
    times.push_back({name, ms});
  } else {
    entry->ms += ms;
  }
}

void addBlockTimes(BlockTimes& times, const std::string& prefix, const BlockTimes& inner) {
  for (const BlockTime& time : inner) {
    addBlockTime(times, prefix + "/" + time.name, time.ms);
  }
}

double totalMs(const BlockTimes& times) {
  double total = 0.0;
  for (const BlockTime& time : times) {
    total += time.ms;
  }
  return total;
}

}  // namespace mrslam::fusion
