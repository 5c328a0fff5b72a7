#pragma once
// A team file: which robot agents and fusion agents to start together, each on its own config
// and data (a device config, a log, a segment of a split log, or the simulator).
//
//   domain_id: 44                 # optional: every agent on this DDS domain (else the configs')
//   split:                        # optional: cut a CARMEN log into segments before starting
//     log: ../../shared/data/logs/carmen-intel-corrected.log.gz
//     segments: 3
//   robots:
//     - config: intel_team_robot.yaml   # relative paths: from the team file's folder
//       id: robot1                      # optional: overrides the config's robot_id
//       segment: 1                      # or  log: FILE  (or neither: the config's own source)
//     - config: emulated_robot.yaml     # an agent on its devices (source: devices) ...
//       id: robot2
//       emulate: sim_robot2.yaml        # ... emulated: that config's source played through them
//       emulate_log: FILE               # optional: a log played instead of that source
//       emulate_duration_s: 40          # optional: stop the emulated robot after this long
//   fusion:
//     - config: intel_team_fusion.yaml
//   final_grace_s: 120            # after the last robot ended, fusion agents get this long
//   security_dir: pki             # optional: DDS Security; every agent proves its name (robot id
//                                 #   or fusion name): scripts/make_test_pki.sh pki robot1 ...
//   discovery_server:             # optional: start a Discovery Server (fast-discovery-server,
//     address: 127.0.0.1          #   id 0) listening here; every agent discovers through it
//     port: 11811

#include <optional>
#include <string>
#include <vector>

namespace mrslam::tools {

struct TeamRobot {
  std::string config;          ///< robot config file
  std::string id;              ///< empty: the config's robot_id
  std::string log;             ///< a log to replay instead of the config's source
  std::optional<int> segment;  ///< 1-based segment of the team's split log
  /// Emulated devices: a config whose source mrslam_emulated_robot plays through the devices
  /// the robot config names (each robot gets its own $MRSLAM_DEVICE_DIR); empty: none.
  std::string emulate;
  std::string emulate_log;          ///< a log the emulated robot plays instead
  double emulate_duration_s = 0.0;  ///< 0: the whole source
  std::string name;                 ///< the agent's name in logs (id, or the config's stem)
};

struct TeamFusion {
  std::string config;
  std::string name;  ///< for its log and output folder
};

struct TeamSplit {
  std::string log;  ///< CARMEN log cut into segments
  int segments = 0;
  std::string relations;  ///< the log's benchmark relations, to score the team by; empty: none
};

struct TeamDiscoveryServer {
  std::string address = "127.0.0.1";  ///< IPv4 the server listens on (a LAN address for hosts)
  int port = 11811;
};

struct TeamSpec {
  std::optional<int> domain_id;
  std::optional<TeamDiscoveryServer> discovery_server;
  std::string security_dir;  ///< DDS Security credentials of every agent; empty: off
  std::optional<TeamSplit> split;
  std::vector<TeamRobot> robots;
  std::vector<TeamFusion> fusion;
  double final_grace_s = 120.0;
};

/// Reads and checks a team file; a mistake throws ConfigError (`file:line: key: what`).
TeamSpec loadTeamSpec(const std::string& path);

}  // namespace mrslam::tools
