#include "mrslam/robot/evaluation.hpp"

#include <chrono>

namespace mrslam::robot {

std::vector<Sample> readAllSamples(drivers::SampleSource& source) {
  std::vector<Sample> samples;
  while (auto sample = source.next()) {
    samples.push_back(std::move(*sample));
  }
  return samples;
}

PipelineRun runPipeline(const RobotConfig& config, EstimatorType type,
                        const std::vector<Sample>& samples) {
  PipelineRun run;
  run.type = type;
  std::unique_ptr<PoseEstimator> estimator = makeEstimator(config, type);
  const auto* ekf = dynamic_cast<const EkfEstimator*>(estimator.get());  // owned by the pipeline
  run.pipeline =
      std::make_unique<RobotPipeline>(config.mapping, config.mounting, std::move(estimator));
  const auto start = std::chrono::steady_clock::now();
  for (const Sample& sample : samples) {
    if (run.pipeline->process(sample) == RobotPipeline::Update::kScan) {
      run.covariances.push_back(run.pipeline->covariance());
    }
  }
  run.pipeline->finish();
  run.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (ekf != nullptr) {
    run.ekf_counters = ekf->counters();
    run.ekf_timings = ekf->timings();
  }
  return run;
}

std::optional<std::vector<SE2>> groundTruth(const std::vector<Sample>& samples) {
  std::vector<SE2> truth;
  for (const Sample& sample : samples) {
    if (const auto* scan = std::get_if<LaserScan>(&sample)) {
      if (!scan->logged_pose) {
        return std::nullopt;
      }
      truth.push_back(*scan->logged_pose);
    }
  }
  return truth;
}

std::vector<LaserScan> scansOf(const std::vector<Sample>& samples) {
  std::vector<LaserScan> scans;
  for (const Sample& sample : samples) {
    if (const auto* scan = std::get_if<LaserScan>(&sample)) {
      scans.push_back(*scan);
    }
  }
  return scans;
}

std::vector<SE2> posesOf(const PipelineRun& run) {
  std::vector<SE2> poses;
  for (const TrajectoryPoint& point : run.pipeline->trajectory()) {
    poses.push_back(point.T_map_robot);
  }
  return poses;
}

AccuracyReport evaluateRun(const PipelineRun& run, const std::vector<SE2>& truth) {
  const std::vector<SE2> estimate = posesOf(run);
  AccuracyReport report;
  report.rpe_consecutive = relativePoseError(estimate, truth, 1);
  report.rpe_10 = relativePoseError(estimate, truth, 10);
  report.ate = absoluteTrajectoryError(estimate, truth);
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 1; i < estimate.size() && i < run.covariances.size(); ++i) {
    sum += nees(estimate[i], run.covariances[i], truth.front().inverse() * truth[i]);
    ++count;
  }
  report.mean_nees = count > 0 ? sum / static_cast<double>(count) : 0.0;
  return report;
}

}  // namespace mrslam::robot
