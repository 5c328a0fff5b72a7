#include "mrslam/robot/robot_runner.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <thread>

namespace mrslam::robot {

namespace {
constexpr std::uint64_t kGapsReported = 3;  // warnings for the first jumps; the rest are counted
}  // namespace

std::vector<SE2> decimateTrajectory(const std::vector<TrajectoryPoint>& trajectory,
                                    std::size_t max_points) {
  std::vector<SE2> poses;
  if (trajectory.empty() || max_points == 0) {
    return poses;
  }
  const std::size_t count = std::min(max_points, trajectory.size());
  poses.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    // Index k of count spread over [0, size - 1], the last one exactly the last pose.
    const std::size_t i =
        count == 1 ? trajectory.size() - 1 : k * (trajectory.size() - 1) / (count - 1);
    poses.push_back(trajectory[i].T_map_robot);
  }
  return poses;
}

RobotRunner::RobotRunner(const RunnerSettings& settings, drivers::SampleSource& source,
                         RobotPipeline& pipeline, RobotOutput& output)
    : settings_(settings), source_(source), pipeline_(pipeline), output_(output) {}

RunSummary RobotRunner::run(const std::atomic<bool>& stop) {
  RunSummary summary;
  publishStatus(RobotState::kRunning, "running on " + source_.describe());
  while (!stop.load()) {
    std::optional<Sample> sample = source_.next();
    if (!sample) {
      break;
    }
    ++summary.samples;
    const Stamp stamp = stampOf(*sample);
    pace(stamp);
    const RobotPipeline::Update update = pipeline_.process(*sample);
    output_.publishPose(stamp, pipeline_.pose(), pipeline_.covariance());
    if (update == RobotPipeline::Update::kSighting) {
      output_.publishSighting(pipeline_.lastSighting());
      ++sightings_published_;
    }
    const Stamp now = pipeline_.latestStamp();
    if (update == RobotPipeline::Update::kScan &&
        secondsBetween(last_map_stamp_, now) >= settings_.map_period_s) {
      publishMap(false);
    }
    if (secondsBetween(last_status_stamp_, now) >= settings_.status_period_s) {
      publishStatus(RobotState::kRunning, "running on " + source_.describe());
    }
    if (progress_ != nullptr) {
      progress_->update(source_.progress(), stamp);
    }
  }
  if (progress_ != nullptr) {
    progress_->finish();
  }
  summary.stopped_early = stop.load();
  pipeline_.finish();
  publishMap(true);
  publishStatus(RobotState::kFinished, summary.stopped_early ? "stopped" : "end of data");
  summary.maps_published = maps_published_;
  summary.sightings_published = sightings_published_;
  summary.replay_gaps_shortened = gaps_shortened_;
  summary.paced_log_s = paced_log_s_;
  return summary;
}

void RobotRunner::pace(Stamp stamp) {
  if (settings_.speed <= 0.0) {
    return;
  }
  if (!clock_started_) {
    clock_started_ = true;
    first_stamp_ = stamp;
    latest_paced_stamp_ = stamp;
    wall_start_ = std::chrono::steady_clock::now();
    return;
  }
  const double step_s = secondsBetween(latest_paced_stamp_, stamp);
  if (step_s > settings_.max_replay_gap_s) {
    skipped_log_s_ += step_s - settings_.max_replay_gap_s;
    if (gaps_shortened_++ < kGapsReported) {
      spdlog::warn(
          "replay: the log's clock jumps {:.1f} s at {:.3f} s; replayed as {:.1f} s "
          "(publish.max_replay_gap_s)",
          step_s, stamp.seconds(), settings_.max_replay_gap_s);
    }
  }
  if (step_s > 0.0) {
    latest_paced_stamp_ = stamp;
  }
  const double log_elapsed_s = secondsBetween(first_stamp_, stamp) - skipped_log_s_;
  paced_log_s_ = std::max(paced_log_s_, log_elapsed_s);
  if (log_elapsed_s <= 0.0) {
    return;  // a stamp from before the start (out of order): no waiting
  }
  const auto target =
      wall_start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                        std::chrono::duration<double>(log_elapsed_s / settings_.speed));
  std::this_thread::sleep_until(target);
}

MapSnapshot RobotRunner::snapshot(bool is_final) const {
  MapSnapshot snapshot;
  snapshot.stamp = pipeline_.latestStamp();
  snapshot.sequence = maps_published_ + 1;
  snapshot.scans_inserted = pipeline_.counters().scans;
  snapshot.is_final = is_final;
  snapshot.sightings_published = sightings_published_;
  snapshot.map = pipeline_.grid().toGridMap();
  snapshot.trajectory = decimateTrajectory(pipeline_.trajectory(), settings_.trajectory_points);
  return snapshot;
}

void RobotRunner::publishMap(bool is_final) {
  if (!output_.wantsMaps()) {
    return;  // a map nobody reads is not drawn
  }
  output_.publishMap(snapshot(is_final));
  ++maps_published_;
  last_map_stamp_ = pipeline_.latestStamp();
}

void RobotRunner::publishStatus(RobotState state, const std::string& message) {
  StatusReport report;
  report.stamp = pipeline_.latestStamp();
  report.state = state;
  report.message = message;
  report.source = source_.describe();
  report.source_counters = source_.counters();
  report.sensors = source_.sensors();
  report.pipeline_counters = pipeline_.counters();
  report.maps_published = maps_published_;
  output_.publishStatus(report);
  last_status_stamp_ = pipeline_.latestStamp();
}

}  // namespace mrslam::robot
