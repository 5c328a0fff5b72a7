#pragma once
// The virtual robot (seed 002, §4): a robot that does not exist drives along the free-space
// skeleton of map `from`, "scanning" that map at every step (rays cast on the grid), and Monte
// Carlo localisation finds where those scans fit in map `to`. Particles start only near `to`'s
// skeleton (where a robot can be), move with the virtual robot's steps and are weighted by a
// likelihood field of `to`'s walls. Clusters of converged particles give the virtual robot's pose
// in `to` (T1) while its pose in `from` (T2) is known, so each is a hypothesis
// T_to_from = T1 · T2⁻¹. The hypotheses are judged by the seed pipeline's own acceptance
// (SeedMerger::judgeHypotheses: ±δ placement, ranking, rival check and every refusal rule), with
// the seed merger's settings; an accepted one is aligned last, as the seed merger's are. Its ψ
// over the overlap (dissimilarity.hpp) is checked then: V and ψ both verify what it found.

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "mrslam/common/config.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion {

struct VirtualRobotSettings {
  int beams = 120;                    ///< rays of a virtual scan over the full turn
  double max_range_cells = 160.0;     ///< the virtual laser's reach (8 m at 5 cm)
  int path_poses = 24;                ///< virtual robot poses per walk
  int path_step_cells = 8;            ///< skeleton cells between two poses of a walk
  int walks = 12;                     ///< walks from different (seeded) skeleton cells
  int particles = 4000;               ///< particles of each localisation
  double hit_sigma_cells = 1.5;       ///< σ of the likelihood field (distance to `to`'s walls)
  double motion_sigma_cells = 0.7;    ///< σ of each particle's step, per step, cells
  double motion_sigma_rad = 0.03;     ///< σ of each particle's turn, per step
  double cluster_radius_cells = 5.0;  ///< particles this close form one cluster
  double cluster_angle_rad = 0.15;    ///< ... and turned by less than this
  int hypotheses_per_walk = 3;        ///< largest clusters taken from each walk
  double max_overlap_psi = 1.0;       ///< ψ over the overlap (cells) above which it refuses
  std::uint64_t seed = 1;             ///< seed of every random draw
};

/// Reads a `virtual:` section (keys as the fields); throws ConfigError for a bad value.
VirtualRobotSettings loadVirtualRobotSettings(const Config& config);

/// A pose of the virtual robot in cell coordinates (x, y, heading).
struct CellPose {
  Eigen::Vector2d cell = Eigen::Vector2d::Zero();
  double heading_rad = 0.0;
};

/// A walk along the skeleton of `map` from the skeleton cell nearest `start`: at most `poses`
/// poses `step_cells` apart along the skeleton, each heading along the walk.
std::vector<CellPose> skeletonWalk(const cv::Mat& skeleton, const Eigen::Vector2i& start, int poses,
                                   int step_cells);

/// The end points of a scan that weigh the particles: all of them up to 60, else 60 evenly
/// spaced along the scan.
std::vector<Eigen::Vector2d> scanPointsUsed(const std::vector<Eigen::Vector2d>& scan);

/// A virtual scan of `map` from `pose`: the end cell (relative to the pose, robot frame, cells)
/// of every ray that meets an occupied cell within reach; rays that leave the known map or meet
/// nothing are dropped.
std::vector<Eigen::Vector2d> virtualScan(const GridMap& map, const CellPose& pose,
                                         const VirtualRobotSettings& settings);

class VirtualRobotMerger : public MapMerger {
 public:
  explicit VirtualRobotMerger(VirtualRobotSettings settings = {},
                              const SeedMergerSettings& judge = {})
      : settings_(settings), judge_(judge) {}
  MergeResult merge(const GridMap& from, const GridMap& to) override;
  std::string name() const override { return "virtual"; }
  void shareSearchInputs(const std::shared_ptr<SearchInputsCache>& cache) override {
    judge_.shareSearchInputs(cache);
  }

  /// The hypotheses T_to_from of every walk, before verification (for tests and tuning).
  std::vector<GridTransform> hypotheses(const GridMap& from, const GridMap& to) const;

 private:
  /// Refuses an accepted `result` whose ψ over the overlap is above max_overlap_psi.
  void refuseDissimilar(const GridMap& from, const GridMap& to, MergeResult& result) const;

  VirtualRobotSettings settings_;
  SeedMerger judge_;  ///< the seed pipeline's acceptance, for the hypotheses
};

}  // namespace mrslam::fusion
