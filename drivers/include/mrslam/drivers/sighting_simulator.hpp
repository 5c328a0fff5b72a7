#pragma once
// Rendezvous in the simulator: the other simulated robots of the team drive their built-in
// routes alongside this one (their true motion only), and whenever one of them is within range
// and in line of sight of this robot at a scan, a RobotSighting of it (range and bearing with
// seeded noise) is added to this robot's samples — at most one per robot every period_s.

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "mrslam/drivers/simulator.hpp"

namespace mrslam::drivers {

/// Another simulated robot this one can see.
struct SimulatedTeammate {
  std::string id;       ///< its robot id (what the sighting names)
  int robot_index = 0;  ///< its built-in route
};

struct SightingSettings {
  std::vector<SimulatedTeammate> robots;  ///< empty: no sightings
  double max_range_m = 4.0;               ///< farthest robot seen
  double period_s = 2.0;                  ///< least time between two sightings of one robot
  double range_sigma_m = 0.02;            ///< σ of the range noise
  double bearing_sigma_rad = 0.01;        ///< σ of the bearing noise
};

/// Reads `simulator.sightings` (keys as the fields; robots as a list of {id, robot_index}).
SightingSettings loadSightingSettings(const Config& section);

/// The simulator's samples with RobotSighting samples added (stamped as the scan that saw them).
class SightingSimulator : public SampleSource {
 public:
  SightingSimulator(const SimulatorSettings& settings, const SightingSettings& sightings,
                    const DiffDriveParams& drive, const SensorMounting& mounting);
  ~SightingSimulator() override;

  std::optional<Sample> next() override;
  std::string describe() const override { return robot_.describe() + " with sightings"; }
  SourceCounters counters() const override { return robot_.counters(); }
  std::optional<double> progress() const override { return robot_.progress(); }

  /// The true pose of this robot at its latest sample.
  SE2 truePose() const { return robot_.truePose(); }

 private:
  struct Teammate {
    SimulatedTeammate who;
    std::unique_ptr<Simulator> motion;  ///< noise-free: only its true pose is used
    Stamp last_seen;
    bool seen = false;
  };

  void lookForTeammates(Stamp stamp);
  bool inSight(const SE2& T_world_robot, const Eigen::Vector2d& p_world_other) const;

  Simulator robot_;
  SightingSettings settings_;
  std::vector<Teammate> teammates_;
  std::vector<RobotSighting> pending_;
  std::mt19937_64 rng_;
};

}  // namespace mrslam::drivers
