// mrslam_team: starts a team file's robot and fusion agents as separate processes over DDS,
// one log per agent; Ctrl-C stops them all. The exit code's bits say what failed (1 a robot
// agent, 2 a fusion agent, 4 a launch, 8 the time-out). A team on a split log is evaluated at the
// end (DIR/segments/truth_estimated.json, DIR/evaluation.json); --evaluate-only does just that.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>

#include "mrslam/common/config.hpp"
#include "mrslam/common/logging.hpp"
#include "mrslam/common/shutdown.hpp"
#include "mrslam/common/version.hpp"
#include "mrslam/tools/team_launcher.hpp"

int main(int argc, char** argv) {
  mrslam::logToStandardError("mrslam_team");
  CLI::App app{"mrslam team: robot agents and fusion agents of a team file, over DDS"};
  std::string team_path;
  mrslam::tools::TeamRunOptions options;
  options.out = "out/team";
  int domain = -1;
  app.add_option("team", team_path, "team YAML (see config/intel_team.yaml)")->required();
  app.add_option("--out", options.out, "output folder")->capture_default_str();
  app.add_option("--domain", domain, "DDS domain id of every agent (default: the team file's)")
      ->check(CLI::Range(0, 232));
  app.add_option("--bin-dir", options.bin_dir,
                 "build folder holding robot_agent/ and fusion_agent/")
      ->required();
  app.add_option("--timeout", options.timeout_s,
                 "stop everything after this many seconds (0: never)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--relations", options.relations,
                 "score the team by this file's benchmark relations (default: the split's)");
  bool evaluate_only = false;
  app.add_flag("--evaluate-only", evaluate_only,
               "start nothing: evaluate the finished run in --out (a team on a split log)");
  app.set_version_flag("--version", mrslam::versionLine("team"));
  CLI11_PARSE(app, argc, argv);
  if (domain >= 0) {
    options.domain_id = domain;
  }
  const std::atomic<bool>& shutdown = mrslam::shutdownRequested();
  try {
    const mrslam::tools::TeamSpec team = mrslam::tools::loadTeamSpec(team_path);
    if (evaluate_only) {
      return mrslam::tools::evaluateTeam(team, options) ? 0 : mrslam::tools::kTeamLaunchFailed;
    }
    const int result = mrslam::tools::runTeam(team, options, shutdown);
    if (result == mrslam::tools::kTeamOk) {
      spdlog::info("team: done; outputs in {}", options.out);
    }
    return result;
  } catch (const std::exception& error) {
    spdlog::error("team: {}", error.what());
    return mrslam::tools::kTeamLaunchFailed;
  }
}
