// fusion_agent: subscribes to every robot's local map, composes the global map, publishes it on
// DDS and writes it to files.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <thread>

#include "fusion_node.hpp"
#include "mrslam/common/shutdown.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using mrslam::fusion::FusionConfig;
using mrslam::fusion::RobotMapStore;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

bool allExpectedFinal(const FusionConfig& config, const RobotMapStore& store) {
  for (const std::string& robot_id : config.expected_robots) {
    if (!store.isFinal(robot_id)) {
      return false;
    }
  }
  return true;
}

std::string missingRobots(const FusionConfig& config, const RobotMapStore& store) {
  std::string missing;
  for (const std::string& robot_id : config.expected_robots) {
    if (!store.isFinal(robot_id)) {
      missing += (missing.empty() ? "" : ", ") + robot_id +
                 (store.has(robot_id) ? " (no final map)" : " (no map)");
    }
  }
  return missing;
}

// The main loop: publish when maps changed, write files when due, stop when done.
int runFusion(const FusionConfig& config) {
  RobotMapStore store;
  mrslam::fusion::FusionNode node(config, store);
  const std::atomic<bool>& shutdown = mrslam::shutdownRequested();
  const Clock::time_point start = Clock::now();
  Clock::time_point last_publish = start;
  Clock::time_point last_write = start;
  std::uint64_t published_version = 0;
  std::uint64_t written_version = ~std::uint64_t{0};
  std::uint64_t sequence = 0;
  std::vector<mrslam::fusion::RobotMap> maps;
  mrslam::fusion::GlobalMapResult result = mrslam::fusion::buildGlobalMap(maps, config);
  spdlog::info("fusion: {} listening on domain {}", config.fusion_id, config.dds.domain_id);
  while (true) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const bool complete = config.exit_when_final && allExpectedFinal(config, store);
    const bool timed_out = config.max_runtime_s > 0.0 && secondsSince(start) > config.max_runtime_s;
    const bool stopping = complete || timed_out || shutdown.load();
    const bool publish_due = secondsSince(last_publish) >= config.publish_period_s;
    if (store.version() != published_version && (publish_due || stopping)) {
      published_version = store.version();
      maps = store.snapshot();
      result = mrslam::fusion::buildGlobalMap(maps, config);
      node.publish(result, ++sequence);
      last_publish = Clock::now();
    }
    const bool write_due =
        config.write_period_s > 0.0 && secondsSince(last_write) >= config.write_period_s;
    if ((write_due || stopping) && written_version != published_version) {
      mrslam::fusion::writeFusionOutputs(result, maps, config.output_folder,
                                         config.write_robot_maps);
      written_version = published_version;
      last_write = Clock::now();
    }
    if (stopping) {
      if (timed_out && config.exit_when_final && !complete) {
        spdlog::error("fusion: gave up after {} s; missing: {}", config.max_runtime_s,
                      missingRobots(config, store));
        return 2;
      }
      break;
    }
  }
  spdlog::info("fusion: wrote {} ({} maps refused)", config.output_folder, node.rejected().total());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mrslam fusion agent: merges the robots' maps into one global map"};
  std::string config_path;
  int domain = -1;
  std::string out;
  double max_runtime = -1.0;
  std::string log_level = "info";
  app.add_option("--config", config_path, "fusion config YAML")->required();
  app.add_option("--domain", domain, "DDS domain id (overrides the config)")
      ->check(CLI::Range(0, 232));
  app.add_option("--out", out, "output folder (overrides the config)");
  app.add_option("--max-runtime", max_runtime, "give up after this many seconds (0: never)");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error");
  app.set_version_flag("--version", "mrslam fusion_agent 0.1.0");
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::from_str(log_level));
  try {
    FusionConfig config = mrslam::fusion::loadFusionConfig(config_path);
    if (domain >= 0) {
      config.dds.domain_id = domain;
    }
    if (!out.empty()) {
      config.output_folder = out;
    }
    if (max_runtime >= 0.0) {
      config.max_runtime_s = max_runtime;
    }
    return runFusion(config);
  } catch (const std::exception& error) {
    spdlog::error("fusion_agent: {}", error.what());
    return 1;
  }
}
