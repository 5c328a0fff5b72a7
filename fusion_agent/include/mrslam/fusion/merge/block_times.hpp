#pragma once
// Where a merger's last merge spent its time, block by block (MapMerger::lastBlockTimes): the
// benchmarks report each block's share of a merge (bench/merge_bench.cpp, BM_MergeBlocks400).
// Wall-clock milliseconds on the steady clock; a block that ran several times in one merge is
// one entry, its times summed; a block that did not run is absent.

#include <chrono>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace mrslam::fusion {

struct BlockTime {
  std::string name;
  double ms = 0.0;
};
using BlockTimes = std::vector<BlockTime>;

/// Adds `ms` to the entry `name` of `times`, appended in the order blocks first run.
void addBlockTime(BlockTimes& times, const std::string& name, double ms);

/// Every entry of `inner` added to `times` as "prefix/name".
void addBlockTimes(BlockTimes& times, const std::string& prefix, const BlockTimes& inner);

/// The sum of every entry.
double totalMs(const BlockTimes& times);

/// Milliseconds since it was made or last lapped (steady clock), for a block whose result cannot
/// be moved out of timeBlock().
class BlockClock {
 public:
  double lapMs() {
    const Clock::time_point now = Clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - start_).count();
    start_ = now;
    return ms;
  }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_ = Clock::now();
};

/// Runs `block()` and adds its wall-clock time to the entry `name` of `times`; returns what the
/// block returns.
template <typename Block>
auto timeBlock(BlockTimes& times, const std::string& name, Block&& block) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  };
  if constexpr (std::is_void_v<decltype(block())>) {
    block();
    addBlockTime(times, name, elapsed());
  } else {
    auto result = block();
    addBlockTime(times, name, elapsed());
    return result;
  }
}

}  // namespace mrslam::fusion
