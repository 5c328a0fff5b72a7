#include "mrslam/tools/team_launcher.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <memory>
#include <thread>

#include "mrslam/tools/carmen_split.hpp"
#include "mrslam/tools/child_process.hpp"
#include "mrslam/tools/team_evaluation.hpp"
#include "mrslam/tools/team_relations.hpp"

namespace mrslam::tools {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr double kStopGraceS = 15.0;  // SIGINT → SIGKILL

constexpr double kDevicesReadyTimeoutS = 20.0;  // an emulated robot brings its devices up
constexpr const char* kDiscoveryServerProgram = "/usr/bin/fast-discovery-server";

struct Agent {
  std::string name;
  bool is_robot = false;  ///< a robot agent, or an emulated robot's devices
  std::unique_ptr<ChildProcess> process;
  bool reported = false;
  /// An emulated robot's devices: the agent (index) that reads them, stopped when they end.
  std::optional<std::size_t> devices_of;
  bool robot_stopped = false;
  bool service = false;  ///< runs for the others (the Discovery Server): stopped when they end
};

std::optional<int> domainOf(const TeamSpec& team, const TeamRunOptions& options) {
  return options.domain_id ? options.domain_id : team.domain_id;
}

void addDomain(std::vector<std::string>& argv, const std::optional<int>& domain) {
  if (domain) {
    argv.insert(argv.end(), {"--domain", std::to_string(*domain)});
  }
}

// Every agent's DDS options: the domain, the team's Discovery Server and its credentials (the
// agent proves `identity`, or its robot id when empty) when it has them.
void addDds(std::vector<std::string>& argv, const TeamSpec& team, const TeamRunOptions& options,
            const std::string& identity) {
  addDomain(argv, domainOf(team, options));
  if (!team.security_dir.empty()) {
    argv.insert(argv.end(), {"--security-dir", team.security_dir});
    if (!identity.empty()) {  // else the agent's own: its robot id
      argv.insert(argv.end(), {"--security-identity", identity});
    }
  }
  if (team.discovery_server) {
    argv.insert(argv.end(),
                {"--discovery-server", team.discovery_server->address + ":" +
                                           std::to_string(team.discovery_server->port)});
  }
}

std::vector<std::string> segmentPaths(const TeamSpec& team, const fs::path& out) {
  std::vector<std::string> paths;
  if (!team.split) {
    return paths;
  }
  SplitSettings settings;
  settings.segments = team.split->segments;
  const std::vector<LogSegment> segments =
      splitCarmenLog(team.split->log, (out / "segments").string(), settings);
  // The true placements, by the name of the robot that replays each segment.
  std::vector<std::string> names;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    paths.push_back(segments[k].path);
    names.push_back("segment" + std::to_string(k + 1));
    for (const TeamRobot& robot : team.robots) {
      if (robot.segment && static_cast<std::size_t>(*robot.segment) == k + 1) {
        names.back() = robot.name;
      }
    }
  }
  writeSplitTruth(segments, names, (out / "segments" / "truth.json").string());
  return paths;
}

std::vector<std::string> robotArguments(const TeamRobot& robot, const TeamSpec& team,
                                        const TeamRunOptions& options,
                                        const std::vector<std::string>& segments) {
  std::vector<std::string> argv = {
      (fs::path(options.bin_dir) / "robot_agent" / "robot_agent").string(), "--config",
      robot.config};
  if (!robot.id.empty()) {
    argv.insert(argv.end(), {"--robot-id", robot.id});
  }
  if (robot.segment) {
    argv.insert(argv.end(), {"--log", segments.at(static_cast<std::size_t>(*robot.segment - 1))});
  } else if (!robot.log.empty()) {
    argv.insert(argv.end(), {"--log", robot.log});
  }
  const fs::path local = fs::path(options.out) / "robots_local";
  argv.insert(argv.end(),
              {"--out", local.string(), "--trajectory-out",
               (local / ((robot.id.empty() ? robot.name : robot.id) + ".tum")).string()});
  // Every fusion agent of the team must hold the final map before the robot leaves: waiting for
  // the first alone let a robot go before a second fusion agent had discovered it.
  argv.insert(argv.end(), {"--delivery-readers", std::to_string(team.fusion.size())});
  addDds(argv, team, options, robot.id);
  return argv;
}

fs::path fusionFolder(const TeamFusion& fusion, const TeamSpec& team,
                      const TeamRunOptions& options) {
  return team.fusion.size() == 1 ? fs::path(options.out) : fs::path(options.out) / fusion.name;
}

std::vector<std::string> fusionArguments(const TeamFusion& fusion, const TeamSpec& team,
                                         const TeamRunOptions& options) {
  const fs::path out = fusionFolder(fusion, team, options);
  std::vector<std::string> argv = {
      (fs::path(options.bin_dir) / "fusion_agent" / "fusion_agent").string(), "--config",
      fusion.config, "--out", out.string()};
  addDds(argv, team, options, fusion.name);
  return argv;
}

// What an emulated robot and its agent share: where the devices are and the board's feed.
std::vector<std::string> deviceEnvironment(const TeamRobot& robot, const TeamRunOptions& options) {
  const fs::path devices = fs::absolute(fs::path(options.out) / "devices" / robot.name);
  fs::create_directories(devices);
  return {"MRSLAM_DEVICE_DIR=" + devices.string(),
          "MRSLAM_PHIDGET_EMULATOR_FEED=" + (devices / "encoders.feed").string(),
          "MRSLAM_BIN_DIR=" + fs::absolute(options.bin_dir).string()};
}

std::vector<std::string> emulatorArguments(const TeamRobot& robot, const TeamRunOptions& options) {
  std::vector<std::string> argv = {
      (fs::path(options.bin_dir) / "tools" / "mrslam_emulated_robot").string(),
      "--robot-config",
      robot.config,
      "--source-config",
      robot.emulate,
      "--truth-out",
      (fs::path(options.out) / "devices" / robot.name / "truth.tum").string()};
  if (!robot.emulate_log.empty()) {
    argv.insert(argv.end(), {"--log", robot.emulate_log});
  }
  if (robot.emulate_duration_s > 0.0) {
    argv.insert(argv.end(), {"--duration", std::to_string(robot.emulate_duration_s)});
  }
  return argv;
}

// Waits until the emulated robot says its devices are up. Throws when it ends or takes too long.
void waitForDevices(ChildProcess& emulator, const std::string& name) {
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(
                         std::chrono::duration<double>(kDevicesReadyTimeoutS));
  while (tailOfFile(emulator.logPath(), 50).find("devices ready") == std::string::npos) {
    if (emulator.poll() || Clock::now() > deadline) {
      throw std::runtime_error("the emulated devices of " + name +
                               " did not come up: " + tailOfFile(emulator.logPath(), 5));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

// Starts every agent (fusion first, so no early map is missed); an emulated robot's devices
// before the agent that reads them. Throws when one cannot start.
std::vector<Agent> startAgents(const TeamSpec& team, const TeamRunOptions& options,
                               const std::vector<std::string>& segments) {
  const fs::path logs = fs::path(options.out) / "logs";
  std::vector<Agent> agents;
  if (team.discovery_server) {
    // fast-discovery-server (Debian's fastdds-tools) with id 0: its GUID prefix is the one the
    // agents' clients assume (dds.discovery_server_id 0).
    const TeamDiscoveryServer& server = *team.discovery_server;
    agents.push_back(
        {"discovery_server", false,
         std::make_unique<ChildProcess>(
             std::vector<std::string>{kDiscoveryServerProgram, "-i", "0", "-l", server.address,
                                      "-p", std::to_string(server.port)},
             (logs / "discovery_server.log").string()),
         false, std::nullopt, false, true});
  }
  for (const TeamFusion& fusion : team.fusion) {
    agents.push_back({fusion.name, false,
                      std::make_unique<ChildProcess>(fusionArguments(fusion, team, options),
                                                     (logs / (fusion.name + ".log")).string()),
                      false, std::nullopt, false, false});
  }
  for (const TeamRobot& robot : team.robots) {
    std::vector<std::string> environment;
    if (!robot.emulate.empty()) {
      environment = deviceEnvironment(robot, options);
      auto emulator = std::make_unique<ChildProcess>(
          emulatorArguments(robot, options), (logs / (robot.name + ".devices.log")).string(),
          environment);
      waitForDevices(*emulator, robot.name);
      agents.push_back({robot.name + " devices", true, std::move(emulator), false,
                        agents.size() + 1, false, false});
    }
    agents.push_back(
        {robot.name, true,
         std::make_unique<ChildProcess>(robotArguments(robot, team, options, segments),
                                        (logs / (robot.name + ".log")).string(), environment),
         false, std::nullopt, false, false});
  }
  return agents;
}

// A robot on emulated devices runs until its devices end: then it is asked to finish.
void stopRobotsWhoseDevicesEnded(std::vector<Agent>& agents) {
  for (Agent& devices : agents) {
    if (devices.devices_of && !devices.robot_stopped && devices.process->poll()) {
      Agent& robot = agents.at(*devices.devices_of);
      spdlog::info("team: the devices of {} ended; asking it to finish", robot.name);
      robot.process->signal(SIGINT);
      devices.robot_stopped = true;
    }
  }
}

// Logs each agent's end once; returns the TeamExit bits of the agents that failed.
int reportEnded(std::vector<Agent>& agents) {
  int failed = kTeamOk;
  for (Agent& agent : agents) {
    const std::optional<int> code = agent.process->poll();
    if (!code) {
      continue;
    }
    if (*code != 0 && !agent.service) {
      failed |= agent.is_robot ? kTeamRobotFailed : kTeamFusionFailed;
    }
    if (!agent.reported) {
      agent.reported = true;
      if (*code == 0) {
        spdlog::info("team: {} ended", agent.name);
      } else {
        spdlog::error("team: {} ended with exit code {}; the end of {}:\n{}", agent.name, *code,
                      agent.process->logPath(), tailOfFile(agent.process->logPath(), 15));
      }
    }
  }
  return failed;
}

bool allEnded(std::vector<Agent>& agents, bool robots_only) {
  for (Agent& agent : agents) {
    if (!agent.service && (agent.is_robot || !robots_only) && !agent.process->poll()) {
      return false;
    }
  }
  return true;
}

void stopAll(std::vector<Agent>& agents) {
  for (Agent& agent : agents) {
    agent.process->signal(SIGINT);
  }
  for (Agent& agent : agents) {
    agent.process->stop(kStopGraceS);
  }
}

int watch(std::vector<Agent>& agents, const TeamSpec& team, const TeamRunOptions& options,
          const std::atomic<bool>& shutdown) {
  const Clock::time_point start = Clock::now();
  std::optional<Clock::time_point> robots_done;
  while (!allEnded(agents, false)) {
    reportEnded(agents);
    stopRobotsWhoseDevicesEnded(agents);
    const double elapsed_s = std::chrono::duration<double>(Clock::now() - start).count();
    if (shutdown.load()) {
      spdlog::info("team: stopping every agent");
      stopAll(agents);
      break;
    }
    if (options.timeout_s > 0.0 && elapsed_s > options.timeout_s) {
      spdlog::error("team: still running after {} s; stopping every agent", options.timeout_s);
      stopAll(agents);
      return reportEnded(agents) | kTeamTimedOut;
    }
    if (!robots_done && allEnded(agents, true)) {
      robots_done = Clock::now();
    }
    if (robots_done &&
        std::chrono::duration<double>(Clock::now() - *robots_done).count() > team.final_grace_s) {
      spdlog::warn("team: the fusion agents run {} s after the last robot; asking them to stop",
                   team.final_grace_s);
      stopAll(agents);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  stopAll(agents);  // the services (those still running)
  return reportEnded(agents);
}

}  // namespace

bool evaluateTeam(const TeamSpec& team, const TeamRunOptions& options) {
  std::vector<std::string> folders;
  for (const TeamFusion& fusion : team.fusion) {
    folders.push_back(fusionFolder(fusion, team, options).string());
  }
  // A raw log has no truth to place the robots by, only its relations: they score the team.
  const std::string relations =
      !options.relations.empty() ? options.relations : (team.split ? team.split->relations : "");
  if (!relations.empty()) {
    return scoreTeamRun(options.out, folders, relations);
  }
  return evaluateTeamRun(options.out, folders);
}

int runTeam(const TeamSpec& team, const TeamRunOptions& options,
            const std::atomic<bool>& shutdown) {
  fs::create_directories(fs::path(options.out) / "logs");
  std::vector<Agent> agents;
  try {
    const std::vector<std::string> segments = segmentPaths(team, options.out);
    agents = startAgents(team, options, segments);
  } catch (const std::exception& error) {
    spdlog::error("team: {}", error.what());
    stopAll(agents);
    return kTeamLaunchFailed;
  }
  spdlog::info("team: {} robot agent(s) and {} fusion agent(s) started; logs in {}",
               team.robots.size(), team.fusion.size(), (fs::path(options.out) / "logs").string());
  const int exit_bits = watch(agents, team, options, shutdown);
  if (team.split) {
    evaluateTeam(team, options);
  }
  return exit_bits;
}

}  // namespace mrslam::tools
