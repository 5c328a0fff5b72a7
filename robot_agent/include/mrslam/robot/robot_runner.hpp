#pragma once
// Drives a RobotPipeline from a SampleSource: paces replay (as fast as possible or at a speed
// factor of the log's clock), and hands poses, maps and status to an output (the DDS node).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "mrslam/drivers/sample_source.hpp"
#include "mrslam/robot/replay_progress.hpp"
#include "mrslam/robot/robot_pipeline.hpp"

namespace mrslam::robot {

/// A published local map with what goes with it.
struct MapSnapshot {
  Stamp stamp;
  std::uint64_t sequence = 0;
  std::uint64_t scans_inserted = 0;
  bool is_final = false;
  /// Sightings of other robots handed to the output before this map: a fusion agent that holds
  /// the final map waits until it holds as many (they travel on another topic, unordered).
  std::uint64_t sightings_published = 0;
  GridMap map;
  std::vector<SE2> trajectory;  ///< map-frame poses at scans (decimated)
};

enum class RobotState { kStarting, kRunning, kFinished, kFailed };

struct StatusReport {
  Stamp stamp;
  RobotState state = RobotState::kStarting;
  std::string message;
  std::string source;  ///< SampleSource::describe()
  drivers::SourceCounters source_counters;
  std::vector<drivers::SensorStatus> sensors;  ///< of a live source (devices)
  PipelineCounters pipeline_counters;
  std::uint64_t maps_published = 0;
};

/// Where the runner sends its results.
class RobotOutput {
 public:
  virtual ~RobotOutput() = default;
  virtual void publishPose(Stamp stamp, const SE2& T_map_robot,
                           const Eigen::Matrix3d& covariance) = 0;
  virtual void publishMap(const MapSnapshot& snapshot) = 0;
  /// false: nobody reads the maps while the run goes on (only the final one is drawn).
  virtual bool wantsMaps() const { return true; }
  virtual void publishStatus(const StatusReport& report) = 0;
  /// A rendezvous: another robot seen (outputs without a rendezvous topic ignore it).
  virtual void publishSighting(const SightingReport& /*report*/) {}
};

struct RunnerSettings {
  double speed = 0.0;  ///< replay speed factor of the sample clock; 0: as fast as possible
  /// Longest step of the sample clock a paced replay waits for, s: a longer jump of a log's
  /// stamps (the csail log's, written with 6 significant digits, jumps 10000 s at once) is
  /// replayed as this long.
  double max_replay_gap_s = 10.0;
  double map_period_s = 1.0;             ///< sample-clock time between published maps
  double status_period_s = 1.0;          ///< sample-clock time between status reports
  std::size_t trajectory_points = 2000;  ///< most trajectory poses sent with a map
};

struct RunSummary {
  std::uint64_t samples = 0;
  std::uint64_t maps_published = 0;
  std::uint64_t sightings_published = 0;    ///< handed to the output's publishSighting
  bool stopped_early = false;               ///< the stop flag ended the run before the source did
  std::uint64_t replay_gaps_shortened = 0;  ///< steps of the log's clock beyond max_replay_gap_s
  double paced_log_s = 0.0;  ///< log time a paced replay followed, the jumps shortened
};

class RobotRunner {
 public:
  RobotRunner(const RunnerSettings& settings, drivers::SampleSource& source,
              RobotPipeline& pipeline, RobotOutput& output);

  /// Runs until the source ends or `stop` becomes true; the last map is published final.
  RunSummary run(const std::atomic<bool>& stop);

  /// The map as it would be published now.
  MapSnapshot snapshot(bool is_final) const;
  /// Reports the replay's progress there after every sample (none: no report).
  void setProgress(ReplayProgress* progress) { progress_ = progress; }

 private:
  void pace(Stamp stamp);
  void publishMap(bool is_final);
  void publishStatus(RobotState state, const std::string& message);

  RunnerSettings settings_;
  drivers::SampleSource& source_;
  RobotPipeline& pipeline_;
  RobotOutput& output_;
  std::uint64_t maps_published_ = 0;
  std::uint64_t sightings_published_ = 0;  ///< handed to output_.publishSighting
  Stamp last_map_stamp_;
  Stamp last_status_stamp_;
  bool clock_started_ = false;
  Stamp first_stamp_;
  Stamp latest_paced_stamp_;    ///< the latest stamp paced so far
  double skipped_log_s_ = 0.0;  ///< log time left out of the pacing (gaps shortened)
  double paced_log_s_ = 0.0;    ///< the latest log time paced to
  std::uint64_t gaps_shortened_ = 0;
  std::chrono::steady_clock::time_point wall_start_;
  ReplayProgress* progress_ = nullptr;
};

/// Keeps at most `max_points` poses, evenly spread, always with the last.
std::vector<SE2> decimateTrajectory(const std::vector<TrajectoryPoint>& trajectory,
                                    std::size_t max_points);

}  // namespace mrslam::robot
