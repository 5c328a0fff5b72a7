// Robot → fusion delivery of one 800 × 800 local map (640 kB) with the agents' map QoS,
// write() → the reader's take(), intraprocess delivery off: over shared memory, over UDP
// loopback, and over UDP losing 20 % of the DATA_FRAG messages (Fast DDS's test transport).
// Median and p99 of the iterations as counters (ms).
//   build/bench/map_delivery_bench --benchmark_repetitions=3
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <random>
#include <vector>

#include "mrslam/dds/lossy_link.hpp"

namespace mrslam {
namespace {

msg::LocalMap mapOfSequence(std::uint64_t sequence, std::mt19937& random) {
  msg::LocalMap map;
  map.robot_id("robot1");
  map.sequence_number(sequence);
  map.info().resolution(0.05);
  map.info().width(800);
  map.info().height(800);
  std::vector<std::uint8_t> cells(800 * 800);
  for (std::uint8_t& cell : cells) {
    cell = static_cast<std::uint8_t>(random() % 102) - 1;
  }
  map.data(std::move(cells));
  return map;
}

double percentile(std::vector<double> values, double fraction) {
  std::sort(values.begin(), values.end());
  const auto index = static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1));
  return values[index];
}

// Arguments: transport (0 UDP, 1 shared memory), DATA_FRAG drop percent.
void BM_MapDelivery(benchmark::State& state) {
  dds::LossyLinkSettings settings;
  settings.domain_id = 230;
  settings.profiles_file = MRSLAM_PROFILES_FILE;
  settings.transport =
      state.range(0) == 1 ? dds::LinkTransport::kSharedMemory : dds::LinkTransport::kUdp;
  settings.drop_data_frag_percent = static_cast<int>(state.range(1));
  dds::LossyMapLink link(settings);
  std::mt19937 random(1);
  std::uint64_t sequence = 0;
  std::uint64_t lost = 0;
  std::vector<double> delays_ms;
  for (auto _ : state) {
    state.PauseTiming();
    const msg::LocalMap map = mapOfSequence(++sequence, random);
    state.ResumeTiming();
    const dds::MapDelivery delivery = link.send(map, 30.0);
    lost += delivery.whole ? 0 : 1;
    delays_ms.push_back(delivery.delay_ms);
    state.SetIterationTime(delivery.delay_ms / 1000.0);
  }
  state.counters["median_ms"] = percentile(delays_ms, 0.5);
  state.counters["p99_ms"] = percentile(delays_ms, 0.99);
  const dds::LossyLinkCounters counters = link.counters();
  state.counters["frags_dropped_%"] =
      100.0 * static_cast<double>(counters.data_frags_dropped) /
      static_cast<double>(std::max<std::uint64_t>(1, counters.data_frags_sent));
  state.counters["maps_not_whole"] = static_cast<double>(lost);
}

BENCHMARK(BM_MapDelivery)
    ->ArgNames({"shm", "drop%"})
    ->Args({1, 0})
    ->Args({0, 0})
    ->Args({0, 20})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(200);

}  // namespace
}  // namespace mrslam

BENCHMARK_MAIN();
