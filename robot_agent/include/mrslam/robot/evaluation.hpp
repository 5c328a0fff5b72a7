#pragma once
// Offline evaluation: replay the same samples through several pipelines (odometry, EKF) and
// measure each against the ground truth the samples carry (LaserScan::logged_pose: CARMEN's
// corrected poses, the simulator's true poses). Used by mrslam_evaluate_trajectory and the tests.

#include <optional>
#include <string>
#include <vector>

#include "mrslam/drivers/sample_source.hpp"
#include "mrslam/robot/ekf_estimator.hpp"
#include "mrslam/robot/robot_config.hpp"
#include "mrslam/robot/trajectory_metrics.hpp"

namespace mrslam::robot {

/// Every sample of a source, in its order.
std::vector<Sample> readAllSamples(drivers::SampleSource& source);

/// One pipeline's run over the samples.
struct PipelineRun {
  EstimatorType type = EstimatorType::kEkf;
  std::unique_ptr<RobotPipeline> pipeline;   ///< after the last sample (grid, trajectory)
  std::vector<Eigen::Matrix3d> covariances;  ///< the pose covariance at every scan
  std::optional<EkfCounters> ekf_counters;   ///< when the estimator is the EKF
  std::optional<EkfTimings> ekf_timings;     ///< when the estimator is the EKF
  double wall_time_s = 0.0;                  ///< processing time of all samples
};

/// Runs the config's pipeline with an estimator of `type` over `samples`.
PipelineRun runPipeline(const RobotConfig& config, EstimatorType type,
                        const std::vector<Sample>& samples);

/// The logged pose of every scan, in order; nothing when a scan lacks one. logged_pose is taken
/// as the robot's pose (CARMEN logs its laser pose: the CARMEN config mounts the laser at 0).
std::optional<std::vector<SE2>> groundTruth(const std::vector<Sample>& samples);

/// The scans, in order.
std::vector<LaserScan> scansOf(const std::vector<Sample>& samples);

struct AccuracyReport {
  ErrorStats rpe_consecutive;  ///< RPE(1): consecutive scans
  ErrorStats rpe_10;           ///< RPE(10): scans 10 apart
  ErrorStats ate;              ///< after SE(2) alignment
  double mean_nees = 0.0;      ///< over every scan after the first, truth in the map frame
};

/// Accuracy of a run against `truth` (world frame; the map frame is the first scan's pose).
AccuracyReport evaluateRun(const PipelineRun& run, const std::vector<SE2>& truth);

/// The poses of a run's trajectory.
std::vector<SE2> posesOf(const PipelineRun& run);

}  // namespace mrslam::robot
