#include "mrslam/robot/robot_pipeline.hpp"

namespace mrslam::robot {

RobotPipeline::RobotPipeline(const MappingSettings& mapping, const SensorMounting& mounting,
                             std::unique_ptr<PoseEstimator> estimator)
    : estimator_(std::move(estimator)), mapper_(mapping, mounting) {}

RobotPipeline::Update RobotPipeline::process(const Sample& sample) {
  const Stamp stamp = stampOf(sample);
  if (has_stamp_ && stamp < latest_stamp_) {
    ++counters_.late_samples;
  } else {
    latest_stamp_ = stamp;
    has_stamp_ = true;
  }
  if (const auto* scan = std::get_if<LaserScan>(&sample)) {
    return processScan(*scan);
  }
  if (const auto* ticks = std::get_if<WheelTicks>(&sample)) {
    ++counters_.wheel_ticks;
    estimator_->addWheelTicks(*ticks);
  } else if (const auto* odometry = std::get_if<OdometryPose>(&sample)) {
    ++counters_.odometry;
    estimator_->addOdometry(*odometry);
  } else if (const auto* imu = std::get_if<ImuSample>(&sample)) {
    ++counters_.imu;
    estimator_->addImu(*imu);
  } else if (const auto* sighting = std::get_if<RobotSighting>(&sample)) {
    ++counters_.sightings;
    last_sighting_ = {sighting->stamp,       sighting->observed_id, sighting->range_m,
                      sighting->bearing_rad, estimator_->pose(),    estimator_->covariance()};
    return Update::kSighting;
  }
  return Update::kPose;
}

const OccupancyGrid& RobotPipeline::grid() const {
  const OccupancyGrid* own = estimator_->drawsItsOwnMap() ? estimator_->map() : nullptr;
  return own != nullptr ? *own : mapper_.grid();
}

const std::vector<TrajectoryPoint>& RobotPipeline::trajectory() const {
  const std::vector<SE2> revised = estimator_->revisedScanPoses();
  if (revised.size() == trajectory_.size()) {
    for (std::size_t i = 0; i < revised.size(); ++i) {
      trajectory_[i].T_map_robot = revised[i];
    }
  }
  return trajectory_;
}

RobotPipeline::Update RobotPipeline::processScan(const LaserScan& scan) {
  ++counters_.scans;
  estimator_->addScan(scan, mapper_.grid());
  if (!estimator_->drawsItsOwnMap()) {
    mapper_.insertScan(scan, estimator_->pose());
  }
  trajectory_.push_back({scan.stamp, estimator_->pose()});
  return Update::kScan;
}

}  // namespace mrslam::robot
