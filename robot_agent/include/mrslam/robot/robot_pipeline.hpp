#pragma once
// The robot's whole estimation and mapping pipeline, free of DDS, devices and files:
// samples in (in processing order), pose and map out.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mrslam/robot/grid_mapper.hpp"
#include "mrslam/robot/pose_estimator.hpp"

namespace mrslam::robot {

/// The estimated pose at one inserted scan.
struct TrajectoryPoint {
  Stamp stamp;
  SE2 T_map_robot;
};

/// Another robot seen (a rendezvous), with this robot's pose estimate at that moment.
struct SightingReport {
  Stamp stamp;
  std::string observed_id;
  double range_m = 0.0;
  double bearing_rad = 0.0;  ///< in this robot's frame
  SE2 T_map_robot;           ///< this robot's estimated pose when it saw the other
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

struct PipelineCounters {
  std::uint64_t scans = 0;
  std::uint64_t wheel_ticks = 0;
  std::uint64_t odometry = 0;
  std::uint64_t imu = 0;
  std::uint64_t sightings = 0;
  std::uint64_t late_samples = 0;  ///< samples older than one already processed
};

class RobotPipeline {
 public:
  /// What a sample changed.
  enum class Update { kPose, kScan, kSighting };

  RobotPipeline(const MappingSettings& mapping, const SensorMounting& mounting,
                std::unique_ptr<PoseEstimator> estimator);

  Update process(const Sample& sample);
  /// The samples have ended: the estimator's last optimisation (its map and poses settle).
  void finish() { estimator_->finish(); }
  const PoseEstimator& estimator() const { return *estimator_; }

  SE2 pose() const { return estimator_->pose(); }
  Eigen::Matrix3d covariance() const { return estimator_->covariance(); }
  /// The robot's map: the estimator's own (drawn from its optimised submaps) when it has one,
  /// else every scan inserted at its pose.
  const OccupancyGrid& grid() const;
  /// The pose at every scan; revised by the estimator's loop closures where it makes them.
  const std::vector<TrajectoryPoint>& trajectory() const;
  const PipelineCounters& counters() const { return counters_; }
  /// The newest sighting (valid after process() returned kSighting).
  const SightingReport& lastSighting() const { return last_sighting_; }
  /// Stamp of the newest sample processed (zero before the first).
  Stamp latestStamp() const { return latest_stamp_; }

 private:
  Update processScan(const LaserScan& scan);

  std::unique_ptr<PoseEstimator> estimator_;
  GridMapper mapper_;
  mutable std::vector<TrajectoryPoint> trajectory_;
  PipelineCounters counters_;
  SightingReport last_sighting_;
  Stamp latest_stamp_;
  bool has_stamp_ = false;
};

}  // namespace mrslam::robot
