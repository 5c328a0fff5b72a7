// Map delivery delay over UDP when the network loses DATA_FRAG messages (Fast DDS's test UDP
// transport; UDP only, intraprocess delivery off): write() → the reader's take() of one
// 800 × 800 map (640 kB, 11 fragments), with the agents' map QoS, at 0 % and 20 % loss.
//   build/bench/dds_loss_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <random>

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

void BM_MapOverLossyUdp(benchmark::State& state) {
  dds::LossyLinkSettings settings;
  settings.domain_id = 230;
  settings.profiles_file = MRSLAM_PROFILES_FILE;
  settings.drop_data_frag_percent = static_cast<int>(state.range(0));
  dds::LossyMapLink link(settings);
  std::mt19937 random(1);
  std::uint64_t sequence = 0;
  std::uint64_t lost = 0;
  for (auto _ : state) {
    const msg::LocalMap map = mapOfSequence(++sequence, random);
    const dds::MapDelivery delivery = link.send(map, 30.0);
    lost += delivery.whole ? 0 : 1;
    state.SetIterationTime(delivery.delay_ms / 1000.0);
  }
  const dds::LossyLinkCounters counters = link.counters();
  state.counters["frags_dropped_%"] =
      100.0 * static_cast<double>(counters.data_frags_dropped) /
      static_cast<double>(std::max<std::uint64_t>(1, counters.data_frags_sent));
  state.counters["maps_not_whole"] = static_cast<double>(lost);
}

BENCHMARK(BM_MapOverLossyUdp)
    ->Arg(0)
    ->Arg(20)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(40);

}  // namespace
}  // namespace mrslam

BENCHMARK_MAIN();
