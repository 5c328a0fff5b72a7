#pragma once
// Starts a team (team_spec.hpp) as separate processes, one log file per agent, and watches it:
// Ctrl-C stops every agent cleanly; once every robot agent has ended, the fusion agents get the
// team's final_grace_s to finish before they are asked to stop (they write their files then).

#include <atomic>
#include <optional>
#include <string>

#include "mrslam/tools/team_spec.hpp"

namespace mrslam::tools {

struct TeamRunOptions {
  std::string bin_dir;           ///< build folder holding robot_agent/ and fusion_agent/
  std::string out;               ///< output folder: logs/, segments/, the fusion outputs
  std::optional<int> domain_id;  ///< overrides the team file's and the configs' domain
  double timeout_s = 0.0;        ///< stop everything after this long (0: no limit)
  std::string relations;         ///< overrides the split's relations (team_relations.hpp)
};

/// Exit code bits of a team run: 0 when every agent ended well.
enum TeamExit : int {
  kTeamOk = 0,
  kTeamRobotFailed = 1,   ///< a robot agent ended with an error
  kTeamFusionFailed = 2,  ///< a fusion agent ended with an error
  kTeamLaunchFailed = 4,  ///< an agent could not be started (or the split failed)
  kTeamTimedOut = 8,      ///< the run hit timeout_s
};

/// Runs the team until it ends or `shutdown` is set; returns the TeamExit bits. A team on a split
/// log is evaluated at the end (evaluateTeam).
int runTeam(const TeamSpec& team, const TeamRunOptions& options, const std::atomic<bool>& shutdown);

/// The placements of a finished run of `team` in `options.out` against the split's truth and the
/// truth in the robots' estimated frames (team_evaluation.hpp): writes them and logs one line per
/// robot. False when there is nothing to evaluate.
bool evaluateTeam(const TeamSpec& team, const TeamRunOptions& options);

}  // namespace mrslam::tools
