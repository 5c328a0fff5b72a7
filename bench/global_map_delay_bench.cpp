// The delay from a robot's local map change to the new global map on DDS, merge estimation
// excluded: a real fusion agent process (placements given in its config, publish period 10 ms)
// reads two robots' 400 × 400 maps; this process changes robot1's map and takes the global map
// that carries the change (its stamp is the newest local map's). Median and p99 (ms).
//   build/bench/global_map_delay_bench
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "mrslam/dds/convert.hpp"
#include "mrslam/dds/participant.hpp"
#include "mrslam/dds/topics.hpp"
#include "mrslam/tools/child_process.hpp"
#include "mrslam_msgsPubSubTypes.h"

namespace mrslam {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kDomain = 228;
constexpr int kCells = 400;

std::string fusionConfig(const std::filesystem::path& folder) {
  const std::string path = (folder / "fusion.yaml").string();
  std::ofstream(path) << "fusion_id: bench\nreference_robot: robot1\nrobots:\n"
                      << "  - id: robot2\n    T_reference_robot: [12.0, 0.0, 0.0]\n"
                      << "merge:\n  method: none\npublish_period_s: 0.01\n"
                      << "output:\n  folder: " << (folder / "out").string() << "\n"
                      << "dds:\n  domain_id: " << kDomain
                      << "\n  profiles_file: " << MRSLAM_PROFILES_FILE << "\n";
  return path;
}

msg::LocalMap localMap(const std::string& robot, std::uint64_t sequence, int stamp_s) {
  GridMap grid;
  grid.geometry.resolution_m = 0.05;
  grid.geometry.width = kCells;
  grid.geometry.height = kCells;
  grid.cells.assign(static_cast<std::size_t>(kCells * kCells), 0);
  for (int i = 0; i < kCells; ++i) {  // a room's walls, and a moving mark
    grid.cells[static_cast<std::size_t>(i)] = 100;
    grid.cells[static_cast<std::size_t>(i * kCells)] = 100;
  }
  grid.cells[static_cast<std::size_t>(kCells * (kCells / 2) +
                                      static_cast<int>(sequence % kCells))] = 100;
  msg::LocalMap map;
  map.robot_id(robot);
  map.sequence_number(sequence);
  map.stamp(dds::toMsg(Stamp::fromSeconds(stamp_s)));
  map.scans_inserted(static_cast<std::uint32_t>(sequence));
  dds::gridToMsg(grid, map.info(), map.data());
  return map;
}

// Takes global maps until one carries `stamp_s`; false after `timeout_s`.
bool awaitGlobalStamp(eprosima::fastdds::dds::DataReader* reader, int stamp_s, double timeout_s) {
  const Clock::time_point deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                        std::chrono::duration<double>(timeout_s));
  msg::GlobalMap global;
  eprosima::fastdds::dds::SampleInfo info;
  while (Clock::now() < deadline) {
    if (!reader->wait_for_unread_message({0, 20'000'000})) {
      continue;
    }
    while (reader->take_next_sample(&global, &info) ==
           eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      if (info.valid_data && dds::fromMsg(global.stamp()).ns == Stamp::fromSeconds(stamp_s).ns) {
        return true;
      }
    }
  }
  return false;
}

void BM_LocalChangeToGlobalMap(benchmark::State& state) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("mrslam-bench-" + std::to_string(getpid()));
  std::filesystem::create_directories(folder);
  tools::ChildProcess fusion(
      {MRSLAM_FUSION_AGENT, "--config", fusionConfig(folder), "--max-runtime", "300"},
      (folder / "fusion.log").string());
  DdsSettings settings;
  settings.domain_id = kDomain;
  settings.profiles_file = MRSLAM_PROFILES_FILE;
  std::vector<double> delays_ms;
  {
    dds::Participant participant(settings, "global map delay bench");
    auto* writer = participant.createWriter<msg::LocalMapPubSubType>(dds::kLocalMapTopic,
                                                                     dds::kMapWriterProfile);
    auto* reader = participant.createReader<msg::GlobalMapPubSubType>(
        dds::kGlobalMapTopic, dds::kStateReaderProfile, nullptr);
    if (!dds::waitForReaders(writer, 1, 20.0)) {
      state.SkipWithError("the fusion agent did not come up");
      return;
    }
    int stamp_s = 1;
    std::uint64_t sequence = 1;
    msg::LocalMap second = localMap("robot2", sequence, stamp_s);
    writer->write(&second);
    for (auto _ : state) {
      msg::LocalMap changed = localMap("robot1", ++sequence, ++stamp_s);
      const Clock::time_point written = Clock::now();
      writer->write(&changed);
      if (!awaitGlobalStamp(reader, stamp_s, 10.0)) {
        state.SkipWithError("no global map with the change");
        break;
      }
      const double delay_ms =
          std::chrono::duration<double, std::milli>(Clock::now() - written).count();
      delays_ms.push_back(delay_ms);
      state.SetIterationTime(delay_ms / 1000.0);
    }
  }
  fusion.stop(10.0);
  std::filesystem::remove_all(folder);
  if (!delays_ms.empty()) {
    std::sort(delays_ms.begin(), delays_ms.end());
    state.counters["median_ms"] = delays_ms[delays_ms.size() / 2];
    state.counters["p99_ms"] = delays_ms[(delays_ms.size() - 1) * 99 / 100];
  }
}

BENCHMARK(BM_LocalChangeToGlobalMap)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(100);

}  // namespace
}  // namespace mrslam

BENCHMARK_MAIN();
