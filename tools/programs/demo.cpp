// mrslam_demo: three simulated robots and one fusion agent as separate processes over DDS.
// Waits for them, then prints where the map files are.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "mrslam/common/logging.hpp"
#include "mrslam/common/shutdown.hpp"
#include "mrslam/common/version.hpp"
#include "mrslam/tools/child_process.hpp"

namespace {

/// One line per robot: how the fusion agent placed it (the demo finds no transform given).
void reportPlacements(const std::filesystem::path& transforms_path) {
  std::ifstream file(transforms_path);
  const nlohmann::json transforms = nlohmann::json::parse(file, nullptr, false);
  if (transforms.is_discarded() || !transforms.contains("robots")) {
    spdlog::warn("demo: no placements in {}", transforms_path.string());
    return;
  }
  for (const nlohmann::json& robot : transforms["robots"]) {
    if (!robot.value("placed", false)) {
      spdlog::warn("demo: {} not placed ({})", robot.value("id", "?"), robot.value("source", ""));
    } else if (robot["verification"].is_number()) {
      spdlog::info("demo: {} placed at ({:.2f} m, {:.2f} m, {:.1f} deg) by {} (V {:.3f})",
                   robot.value("id", "?"), robot.value("x", 0.0), robot.value("y", 0.0),
                   robot.value("theta", 0.0) * 180.0 / M_PI,
                   robot.value("methods", robot.value("source", "")),
                   robot["verification"].get<double>());
    } else {
      spdlog::info("demo: {} is the {}", robot.value("id", "?"), robot.value("source", ""));
    }
  }
}

namespace fs = std::filesystem;
using mrslam::tools::ChildProcess;

struct DemoOptions {
  std::string config_dir;
  std::string bin_dir;
  std::string out = "out/demo";
  int domain = -1;
  double timeout_s = 600.0;
  double speed = 0.0;
};

std::vector<std::string> agentArguments(const std::string& program, const std::string& config,
                                        const DemoOptions& options) {
  std::vector<std::string> argv = {program, "--config", config};
  if (options.domain >= 0) {
    argv.insert(argv.end(), {"--domain", std::to_string(options.domain)});
  }
  return argv;
}

// Waits for every child; on Ctrl-C stops them all. Returns false if one failed.
bool waitForAll(std::vector<std::unique_ptr<ChildProcess>>& children, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(timeout_s));
  const std::atomic<bool>& shutdown = mrslam::shutdownRequested();
  bool all_ok = true;
  for (auto& child : children) {
    while (!child->poll()) {
      if (shutdown.load() || std::chrono::steady_clock::now() > deadline) {
        spdlog::warn("demo: stopping {} (pid {})", child->name(), child->pid());
        child->stop(10.0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    const int code = child->poll().value_or(-1);
    if (code != 0) {
      all_ok = false;
      spdlog::error("demo: {} ended with exit code {}; the end of {}:\n{}", child->name(), code,
                    child->logPath(), mrslam::tools::tailOfFile(child->logPath(), 15));
    }
  }
  return all_ok;
}

int runDemo(const DemoOptions& options) {
  const fs::path out = fs::absolute(options.out);
  fs::create_directories(out / "logs");
  const std::string robot_program =
      (fs::path(options.bin_dir) / "robot_agent" / "robot_agent").string();
  const std::string fusion_program =
      (fs::path(options.bin_dir) / "fusion_agent" / "fusion_agent").string();
  std::vector<std::string> fusion_argv = agentArguments(
      fusion_program, (fs::path(options.config_dir) / "demo_fusion.yaml").string(), options);
  fusion_argv.insert(fusion_argv.end(),
                     {"--out", out.string(), "--max-runtime", std::to_string(options.timeout_s)});
  auto fusion = std::make_unique<ChildProcess>(fusion_argv, (out / "logs" / "fusion.log").string());
  std::vector<std::unique_ptr<ChildProcess>> robots;
  for (int robot = 1; robot <= 3; ++robot) {
    const std::string name = "sim_robot" + std::to_string(robot);
    std::vector<std::string> argv = agentArguments(
        robot_program, (fs::path(options.config_dir) / (name + ".yaml")).string(), options);
    argv.insert(argv.end(), {"--speed", std::to_string(options.speed), "--out",
                             (out / "robots_local").string()});
    robots.push_back(
        std::make_unique<ChildProcess>(argv, (out / "logs" / (name + ".log")).string()));
  }
  spdlog::info("demo: 3 robot agents and 1 fusion agent started; logs in {}",
               (out / "logs").string());
  const bool robots_ok = waitForAll(robots, options.timeout_s);
  std::vector<std::unique_ptr<ChildProcess>> fusion_only;
  fusion_only.push_back(std::move(fusion));
  const bool fusion_ok = waitForAll(fusion_only, options.timeout_s);
  if (!robots_ok || !fusion_ok) {
    return 1;
  }
  reportPlacements(out / "transforms.json");
  spdlog::info("demo: done. Global map: {} (+ .pgm, .png, .bt); placements: {}; robot maps: {}",
               (out / "global_map.yaml").string(), (out / "transforms.json").string(),
               (out / "robots").string());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  mrslam::logToStandardError("mrslam_demo");
  CLI::App app{"mrslam demo: three simulated robots and a fusion agent over DDS"};
  DemoOptions options;
  app.add_option("--config-dir", options.config_dir, "folder of sim_robot*.yaml, demo_fusion.yaml")
      ->required();
  app.add_option("--bin-dir", options.bin_dir,
                 "build folder holding robot_agent/ and fusion_agent/")
      ->required();
  app.add_option("--out", options.out, "output folder")->capture_default_str();
  app.add_option("--domain", options.domain, "DDS domain id (default: the configs')")
      ->check(CLI::Range(0, 232));
  app.add_option("--timeout", options.timeout_s, "give up after this many seconds")
      ->capture_default_str();
  app.add_option("--speed", options.speed, "replay speed factor, 0 = as fast as possible")
      ->capture_default_str();
  app.set_version_flag("--version", mrslam::versionLine("demo"));
  CLI11_PARSE(app, argc, argv);
  try {
    return runDemo(options);
  } catch (const std::exception& error) {
    spdlog::error("demo: {}", error.what());
    return 1;
  }
}
