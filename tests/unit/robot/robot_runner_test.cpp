#include "mrslam/robot/robot_runner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <deque>

#include "mrslam/robot/odometry_estimator.hpp"

namespace mrslam::robot {
namespace {

// A source handing out prepared samples.
class VectorSource : public drivers::SampleSource {
 public:
  explicit VectorSource(std::deque<Sample> samples) : samples_(std::move(samples)) {}
  std::optional<Sample> next() override {
    if (samples_.empty()) {
      return std::nullopt;
    }
    Sample sample = samples_.front();
    samples_.pop_front();
    ++counters_.samples;
    return sample;
  }
  std::string describe() const override { return "test samples"; }
  drivers::SourceCounters counters() const override { return counters_; }

 private:
  std::deque<Sample> samples_;
  drivers::SourceCounters counters_;
};

// Records what the runner publishes.
class RecordingOutput : public RobotOutput {
 public:
  void publishPose(Stamp stamp, const SE2&, const Eigen::Matrix3d&) override {
    pose_stamps.push_back(stamp);
  }
  void publishMap(const MapSnapshot& snapshot) override { maps.push_back(snapshot); }
  void publishStatus(const StatusReport& report) override { states.push_back(report.state); }
  void publishSighting(const SightingReport& report) override { sightings.push_back(report); }

  std::vector<Stamp> pose_stamps;
  std::vector<SightingReport> sightings;
  std::vector<MapSnapshot> maps;
  std::vector<RobotState> states;
};

LaserScan scanAt(double seconds) {
  LaserScan scan;
  scan.stamp = Stamp::fromSeconds(seconds);
  scan.angle_min_rad = -0.5;
  scan.angle_increment_rad = 0.5;
  scan.range_min_m = 0.02;
  scan.range_max_m = 4.0;
  scan.ranges_m = {1.0f, 1.0f, 1.0f};
  return scan;
}

// 10 Hz scans for `seconds`, with wheel ticks before each.
std::deque<Sample> drive(double seconds) {
  std::deque<Sample> samples;
  for (int i = 0; i < static_cast<int>(seconds * 10); ++i) {
    const double t = 100.0 + 0.1 * i;
    samples.push_back(WheelTicks{Stamp::fromSeconds(t), 10 * i, 10 * i});
    samples.push_back(scanAt(t));
  }
  return samples;
}

TEST(RobotRunnerTest, PublishesMapsAtThePeriodOfTheSampleClockAndAFinalOne) {
  VectorSource source(drive(5.0));  // 50 scans over 4.9 s
  RobotPipeline pipeline(MappingSettings{}, SensorMounting{},
                         std::make_unique<OdometryEstimator>(DiffDriveParams{}, OdometryNoise{}));
  RecordingOutput output;
  RunnerSettings settings;
  settings.map_period_s = 1.0;
  RobotRunner runner(settings, source, pipeline, output);
  std::atomic<bool> stop{false};
  const RunSummary summary = runner.run(stop);
  EXPECT_EQ(summary.samples, 100u);
  EXPECT_FALSE(summary.stopped_early);
  EXPECT_EQ(output.pose_stamps.size(), 100u);
  // Maps at t = 100.0 (first scan), 101.0, 102.0, 103.0, 104.0, then the final one.
  ASSERT_EQ(output.maps.size(), 6u);
  for (std::size_t i = 0; i + 1 < output.maps.size(); ++i) {
    EXPECT_FALSE(output.maps[i].is_final);
    EXPECT_EQ(output.maps[i].sequence, i + 1);
  }
  const MapSnapshot& last = output.maps.back();
  EXPECT_TRUE(last.is_final);
  EXPECT_EQ(last.scans_inserted, 50u);
  EXPECT_EQ(last.map, pipeline.grid().toGridMap());
  EXPECT_EQ(last.trajectory.size(), 50u);
  EXPECT_EQ(summary.maps_published, 6u);
  EXPECT_EQ(output.states.front(), RobotState::kRunning);
  EXPECT_EQ(output.states.back(), RobotState::kFinished);
}

TEST(RobotRunnerTest, EachMapCountsTheSightingsPublishedBeforeIt) {
  // A sighting of robot2 at 100.45 s and two of robot3 at 102.45 and 102.55 s: the map at
  // 100.0 s follows none, those at 101.0 and 102.0 s one, the later ones all three.
  std::deque<Sample> samples = drive(5.0);
  const auto insertBefore = [&samples](double seconds, const RobotSighting& sighting) {
    const auto at = std::find_if(samples.begin(), samples.end(), [seconds](const Sample& sample) {
      return stampOf(sample).seconds() >= seconds;
    });
    samples.insert(at, sighting);
  };
  insertBefore(100.45, RobotSighting{Stamp::fromSeconds(100.45), "robot2", 2.0, 0.1});
  insertBefore(102.45, RobotSighting{Stamp::fromSeconds(102.45), "robot3", 3.0, -0.2});
  insertBefore(102.55, RobotSighting{Stamp::fromSeconds(102.55), "robot3", 3.1, -0.2});
  VectorSource source(samples);
  RobotPipeline pipeline(MappingSettings{}, SensorMounting{},
                         std::make_unique<OdometryEstimator>(DiffDriveParams{}, OdometryNoise{}));
  RecordingOutput output;
  RobotRunner runner(RunnerSettings{}, source, pipeline, output);
  std::atomic<bool> stop{false};
  runner.run(stop);
  ASSERT_EQ(output.sightings.size(), 3u);
  EXPECT_EQ(output.sightings[0].observed_id, "robot2");
  // Maps at 100.0, 101.0, 102.0, 103.0, 104.0 s and the final one.
  ASSERT_EQ(output.maps.size(), 6u);
  const std::vector<std::uint64_t> expected{0, 1, 1, 3, 3, 3};
  for (std::size_t i = 0; i < output.maps.size(); ++i) {
    EXPECT_EQ(output.maps[i].sightings_published, expected[i]) << "map " << i;
  }
}

TEST(RobotRunnerTest, StopFlagEndsTheRunWithAFinalMap) {
  VectorSource source(drive(5.0));
  RobotPipeline pipeline(MappingSettings{}, SensorMounting{},
                         std::make_unique<OdometryEstimator>(DiffDriveParams{}, OdometryNoise{}));
  RecordingOutput output;
  RobotRunner runner(RunnerSettings{}, source, pipeline, output);
  std::atomic<bool> stop{true};
  const RunSummary summary = runner.run(stop);
  EXPECT_TRUE(summary.stopped_early);
  EXPECT_EQ(summary.samples, 0u);
  ASSERT_EQ(output.maps.size(), 1u);
  EXPECT_TRUE(output.maps.front().is_final);
}

TEST(RobotRunnerTest, APacedReplayShortensAJumpOfTheLogsClock) {
  // Two scans 0.1 s apart, then one 10000 s later (as the csail log's stamps jump), then one
  // 0.1 s after it, replayed at 1000 times real time with jumps capped at 0.2 s: the pacing
  // follows 0.4 s of log time, not 10000.2 s.
  std::deque<Sample> samples;
  for (const double t : {100.0, 100.1, 10100.1, 10100.2}) {
    samples.push_back(scanAt(t));
  }
  VectorSource source(samples);
  RobotPipeline pipeline(MappingSettings{}, SensorMounting{},
                         std::make_unique<OdometryEstimator>(DiffDriveParams{}, OdometryNoise{}));
  RecordingOutput output;
  RunnerSettings settings;
  settings.speed = 1000.0;
  settings.max_replay_gap_s = 0.2;
  RobotRunner runner(settings, source, pipeline, output);
  std::atomic<bool> stop{false};
  const RunSummary summary = runner.run(stop);
  EXPECT_EQ(summary.samples, 4u);
  EXPECT_EQ(summary.replay_gaps_shortened, 1u);
  EXPECT_NEAR(summary.paced_log_s, 0.4, 1e-6);
  ASSERT_EQ(output.pose_stamps.size(), 4u);
  EXPECT_EQ(output.pose_stamps[2], Stamp::fromSeconds(10100.1)) << "the stamps stay the log's";
}

TEST(DecimateTrajectoryTest, KeepsFirstAndLastAndSpreadsTheRest) {
  std::vector<TrajectoryPoint> trajectory;
  for (int i = 0; i < 101; ++i) {
    trajectory.push_back({Stamp{i}, SE2(i, 0, 0)});
  }
  const auto five = decimateTrajectory(trajectory, 5);
  ASSERT_EQ(five.size(), 5u);
  EXPECT_DOUBLE_EQ(five[0].x(), 0.0);
  EXPECT_DOUBLE_EQ(five[1].x(), 25.0);
  EXPECT_DOUBLE_EQ(five[4].x(), 100.0);
  EXPECT_EQ(decimateTrajectory(trajectory, 1000).size(), 101u);
  EXPECT_DOUBLE_EQ(decimateTrajectory(trajectory, 1).front().x(), 100.0);
  EXPECT_TRUE(decimateTrajectory({}, 10).empty());
}

}  // namespace
}  // namespace mrslam::robot
