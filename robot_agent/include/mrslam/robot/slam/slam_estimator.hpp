#pragma once
// The robot's SLAM (Hess et al., "Real-Time Loop Closure in 2D LIDAR SLAM", ICRA 2016), with the
// seed's cascaded EKF as its real-time front end. Per scan, in arrival order:
//  1. The EKF predicts from the encoders or odometry up to the scan (its own scan matching off);
//     IMU samples update it between scans as in EkfEstimator.
//  2. Scan-to-submap matching in the local frame: where the prediction is uncertain (its σ beyond
//     correlative_sigma_*), a correlative search (correlative_matcher.hpp) finds the start; least
//     squares on the interpolated submap (ceres_scan_matcher.hpp) gives pose and covariance, the
//     EKF's scan update (ungated unless gate_matches).
//  3. A scan that moved past the motion filter since the last node becomes a node: it is inserted
//     into the active submaps (submaps.hpp) and into the pose graph (pose_graph.hpp) with an
//     intra-submap constraint for each submap it went into.
//  4. Loop closure (loop_closure.hpp): the node is searched for in the finished submaps, and every
//     newly finished submap is searched for the nodes before it; closures join the pose graph,
//     solved every optimise_every_n_nodes nodes when closures came in since the last solve.
//  5. pose() is the local pose carried into the map frame by the latest solve; the map and every
//     scan's pose are drawn from the submaps and nodes at their optimised poses.

#include <memory>
#include <optional>
#include <vector>

#include "mrslam/robot/ekf_estimator.hpp"
#include "mrslam/robot/slam/ceres_scan_matcher.hpp"
#include "mrslam/robot/slam/correlative_matcher.hpp"
#include "mrslam/robot/slam/drift_graph.hpp"
#include "mrslam/robot/slam/loop_closure.hpp"
#include "mrslam/robot/slam/pose_graph.hpp"
#include "mrslam/robot/slam/range_data.hpp"
#include "mrslam/robot/slam/submaps.hpp"

namespace mrslam::robot::slam {

struct MotionFilterSettings {
  double max_distance_m = 0.2;    ///< a scan this far from the last node becomes a node
  double max_angle_rad = 0.0175;  ///< ... or turned this far (1°)
  double max_time_s = 5.0;        ///< ... or this long after it
};

/// The front end's model of the odometry increments' noise. The wheels' distance is trusted as
/// the EKF alone trusts it (10 % of the way): in a long corridor a scan pins the robot across
/// it but hardly along it, and there only the wheels know how far it went (the raw aces log,
/// with 1 per metre: its corridors slid by metres and three of its loops failed to close). The
/// wheels' turn is trusted twenty to thirty times less than the EKF trusts it: a raw log's
/// heading error leaks into every scan update otherwise (intel's first loop came out bowed,
/// 0.27 m and 2.6° on its relations over a minute apart, even at 1 rad/rad and 0.5 rad/m).
inline OdometryNoise frontEndOdometryNoise() {
  OdometryNoise noise;
  noise.translation_per_m = 0.1;
  noise.rotation_per_rad = 2.0;
  noise.rotation_per_m = 1.0;
  return noise;
}

struct SlamSettings {
  EkfSettings ekf;  ///< the front end (its own scan matching is off; its odometry noise below)
  OdometryNoise odometry = frontEndOdometryNoise();  ///< the front end's odometry noise
  RangeDataSettings range_data;                      ///< which beams, thinning
  SubmapSettings submaps;                            ///< submap size and cells
  CeresScanMatcherSettings local_matching;           ///< scan-to-submap least squares
  CorrelativeMatcherSettings correlative;            ///< the search where the prediction is unsure
  double correlative_sigma_xy_m = 0.1;               ///< prediction σ beyond which the search runs
  double correlative_sigma_theta_rad = 0.05;         ///< ... or heading σ beyond this
  /// false: every submap match updates the EKF, however far from the prediction, as the scan
  /// matcher of record does in Cartographer. Gated, a wheel slip locks the estimate out of its
  /// own map: each later match disagrees with the slipped prediction by as much, and is refused
  /// (the raw fr079 log, 0.3 m and 5° lost at once, 3 m at the end).
  bool gate_matches = false;
  MotionFilterSettings motion_filter;
  PoseGraphSettings pose_graph;
  LoopClosureSettings loop_closure;
  int optimise_every_n_nodes = 90;  ///< nodes between pose-graph solves
  double map_resolution_m = 0.05;   ///< cells of the drawn map
};

struct SlamCounters {
  std::uint64_t scans = 0;
  std::uint64_t matches = 0;           ///< scan-to-submap matches made
  std::uint64_t match_failures = 0;    ///< no points or the solver failed
  std::uint64_t match_rejections = 0;  ///< gated out by the EKF (gate_matches only)
  std::uint64_t correlative_searches = 0;
  std::uint64_t nodes = 0;
  std::uint64_t submaps = 0;
  std::uint64_t closures = 0;  ///< loop closures accepted by their score
};

class SlamEstimator : public PoseEstimator {
 public:
  /// A scan node: where local SLAM put it and what loop closure searches for.
  struct NodeData {
    SE2 T_local_node;
    std::vector<Eigen::Vector2d> points;  ///< robot frame, for loop closure searches
    Stamp stamp;
  };

  SlamEstimator(const DiffDriveParams& platform, const SensorMounting& mounting,
                const SlamSettings& settings);

  void addWheelTicks(const WheelTicks& ticks) override { ekf_.addWheelTicks(ticks); }
  void addOdometry(const OdometryPose& odometry) override { ekf_.addOdometry(odometry); }
  void addImu(const ImuSample& imu) override { ekf_.addImu(imu); }
  void addScan(const LaserScan& scan, const OccupancyGrid& map) override;

  SE2 pose() const override { return T_map_local_ * ekf_.pose(); }
  Eigen::Matrix3d covariance() const override { return ekf_.covariance(); }
  bool drawsItsOwnMap() const override { return true; }
  const OccupancyGrid* map() const override;
  std::vector<SE2> revisedScanPoses() const override;

  /// Solves the pose graph with every closure found so far (the end of a run).
  void finish() override;

  const SlamCounters& counters() const { return counters_; }
  const PoseGraph& poseGraph() const { return graph_; }
  const LoopCloser& loopCloser() const { return closer_; }
  const EkfEstimator& frontEnd() const { return ekf_; }
  const SlamSettings& settings() const { return settings_; }
  /// Every submap started so far, by id (the finished ones never change again).
  const std::vector<std::shared_ptr<Submap>>& submaps() const { return submaps_; }
  /// The scan nodes, by index in the pose graph.
  const std::vector<NodeData>& nodes() const { return nodes_; }

 private:
  struct ScanRecord {
    int node = -1;    ///< the newest node when the scan came (−1: none yet)
    SE2 T_node_scan;  ///< the scan relative to that node (local frame)
  };

  void matchScan(const std::vector<Eigen::Vector2d>& points, Stamp stamp);

  bool passesMotionFilter(const SE2& T_local_robot, Stamp stamp) const;
  void addNode(const RangeData& data_robot, std::vector<Eigen::Vector2d> points, Stamp stamp);
  void searchClosuresOfNode(int node);
  void searchClosuresInSubmap(int submap);
  void tryClosure(int submap, int node, double drift_m);
  /// The node a submap is tied to in the drift graph: the middle of its range.
  int middleNodeOf(int submap) const;
  /// The drift graph's shortcuts again, from the closures the last solve kept.
  void resetDriftShortcuts();
  void optimiseIfDue();
  void optimise();

  const SensorMounting mounting_;
  const SlamSettings settings_;
  EkfEstimator ekf_;
  ActiveSubmaps active_;
  CeresScanMatcher local_matcher_;
  CorrelativeMatcher correlative_matcher_;
  PoseGraph graph_;
  LoopCloser closer_;
  std::vector<std::shared_ptr<Submap>> submaps_;
  std::vector<NodeData> nodes_;
  std::vector<ScanRecord> scans_;
  SE2 T_map_local_;  ///< the latest solve's correction of local SLAM
  double travelled_m_ = 0.0;
  std::vector<int> submap_first_node_;  ///< the first node inserted into each submap
  DriftGraph drift_;                    ///< how far nodes and submaps drifted apart
  int nodes_since_solve_ = 0;
  std::uint64_t closures_at_solve_ = 0;
  SlamCounters counters_;
  mutable std::optional<OccupancyGrid> map_;  ///< drawn on demand, dropped when poses change
  mutable std::uint64_t map_version_ = 0;
  std::uint64_t version_ = 0;  ///< bumped by every change of submaps or their poses
};

}  // namespace mrslam::robot::slam
