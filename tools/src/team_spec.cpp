#include "mrslam/tools/team_spec.hpp"

#include "mrslam/common/dds_settings.hpp"

#include <filesystem>
#include <set>

#include "mrslam/common/config.hpp"

namespace mrslam::tools {

namespace {

std::string stemOf(const std::string& path) {
  return std::filesystem::path(path).stem().string();
}

TeamRobot readRobot(const Config& item, const TeamSpec& team) {
  TeamRobot robot;
  robot.config = item.getPath("config", "");
  if (robot.config.empty()) {
    item.fail("config", "every robot needs its robot config");
  }
  robot.id = item.getString("id", "");
  if (!robot.id.empty() && !isValidRobotId(robot.id)) {
    item.fail("id", "'" + robot.id + "' is not a robot id (1-64 of A-Z a-z 0-9 _ -)");
  }
  robot.log = item.getPath("log", "");
  if (item.has("segment")) {
    if (!team.split) {
      item.fail("segment", "needs a `split:` section in the team file");
    }
    robot.segment = static_cast<int>(
        item.requireInt("segment", {1.0, static_cast<double>(team.split->segments)}));
    if (!robot.log.empty()) {
      item.fail("segment", "give a log or a segment, not both");
    }
  }
  robot.emulate = item.getPath("emulate", "");
  robot.emulate_log = item.getPath("emulate_log", "");
  robot.emulate_duration_s = item.getDouble("emulate_duration_s", 0.0, {0.0, 1e6});
  if (robot.emulate.empty() && (!robot.emulate_log.empty() || robot.emulate_duration_s > 0.0)) {
    item.fail(robot.emulate_log.empty() ? "emulate_duration_s" : "emulate_log",
              "needs `emulate:` (the config whose source the devices play)");
  }
  if (!robot.emulate.empty() && (robot.segment || !robot.log.empty())) {
    item.fail("emulate", "a robot on emulated devices replays no log or segment itself");
  }
  robot.name = robot.id.empty() ? stemOf(robot.config) : robot.id;
  return robot;
}

void checkUniqueNames(const Config& config, const TeamSpec& team) {
  std::set<std::string> names;
  for (const TeamRobot& robot : team.robots) {
    if (!names.insert(robot.name).second) {
      config.fail("robots", "two robots are named '" + robot.name + "' (give each its own id)");
    }
  }
  for (const TeamFusion& fusion : team.fusion) {
    if (!names.insert(fusion.name).second) {
      config.fail("fusion", "the name '" + fusion.name + "' is used twice");
    }
  }
}

}  // namespace

TeamSpec loadTeamSpec(const std::string& path) {
  const Config config = Config::loadFile(path);
  TeamSpec team;
  if (config.has("domain_id")) {
    team.domain_id = static_cast<int>(config.requireInt("domain_id", {0.0, 232.0}));
  }
  if (config.has("split")) {
    const Config split = config.section("split");
    TeamSplit settings;
    settings.log = split.getPath("log", "");
    if (settings.log.empty()) {
      split.fail("log", "the split needs the CARMEN log to cut");
    }
    settings.segments = static_cast<int>(split.requireInt("segments", {1.0, 64.0}));
    settings.relations = split.getPath("relations", "");
    team.split = settings;
  }
  team.security_dir = config.getPath("security_dir", "");
  if (config.has("discovery_server")) {
    const Config server = config.section("discovery_server");
    TeamDiscoveryServer settings;
    settings.address = server.getString("address", settings.address);
    settings.port = static_cast<int>(server.getInt("port", settings.port, {1.0, 65535.0}));
    const std::string problem = checkDiscoveryServerAddress(settings.address + ":1");
    if (!problem.empty()) {
      server.fail("address", problem);
    }
    team.discovery_server = settings;
  }
  for (const Config& item : config.sectionList("robots")) {
    team.robots.push_back(readRobot(item, team));
  }
  for (const Config& item : config.sectionList("fusion")) {
    TeamFusion fusion;
    fusion.config = item.getPath("config", "");
    if (fusion.config.empty()) {
      item.fail("config", "every fusion agent needs its fusion config");
    }
    fusion.name = item.getString("name", stemOf(fusion.config));
    team.fusion.push_back(fusion);
  }
  if (team.robots.empty() && team.fusion.empty()) {
    config.fail("robots", "the team has no agent");
  }
  team.final_grace_s = config.getDouble("final_grace_s", team.final_grace_s, {0.0, 86400.0});
  checkUniqueNames(config, team);
  config.checkNoUnknownKeys();
  return team;
}

}  // namespace mrslam::tools
