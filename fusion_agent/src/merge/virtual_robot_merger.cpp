// The virtual-robot merger: its hypotheses judged by the seed pipeline's acceptance
// (virtual_robot.hpp).

#include "mrslam/fusion/merge/virtual_robot.hpp"

#include "mrslam/fusion/merge/dissimilarity.hpp"
#include "mrslam/fusion/merge/reason_text.hpp"

namespace mrslam::fusion {

VirtualRobotSettings loadVirtualRobotSettings(const Config& config) {
  VirtualRobotSettings s;
  s.beams = static_cast<int>(config.getInt("beams", s.beams, {8, 3600}));
  s.max_range_cells = config.getDouble("max_range_cells", s.max_range_cells, {2.0, 10000.0});
  s.path_poses = static_cast<int>(config.getInt("path_poses", s.path_poses, {3, 1000}));
  s.path_step_cells =
      static_cast<int>(config.getInt("path_step_cells", s.path_step_cells, {1, 1000}));
  s.walks = static_cast<int>(config.getInt("walks", s.walks, {1, 1000}));
  s.particles = static_cast<int>(config.getInt("particles", s.particles, {10, 1000000}));
  s.hit_sigma_cells = config.getDouble("hit_sigma_cells", s.hit_sigma_cells, {0.1, 100.0});
  s.motion_sigma_cells = config.getDouble("motion_sigma_cells", s.motion_sigma_cells, {0.0, 100.0});
  s.motion_sigma_rad = config.getDouble("motion_sigma_rad", s.motion_sigma_rad, {0.0, 1.0});
  s.cluster_radius_cells =
      config.getDouble("cluster_radius_cells", s.cluster_radius_cells, {0.5, 1000.0});
  s.cluster_angle_rad = config.getDouble("cluster_angle_rad", s.cluster_angle_rad, {0.01, M_PI});
  s.hypotheses_per_walk =
      static_cast<int>(config.getInt("hypotheses_per_walk", s.hypotheses_per_walk, {1, 100}));
  s.max_overlap_psi = config.getDouble("max_overlap_psi", s.max_overlap_psi, {0.0, 1000.0});
  s.seed = static_cast<std::uint64_t>(
      config.getInt("seed", static_cast<long long>(s.seed), {0.0, 9007199254740992.0}));
  return s;
}

MergeResult VirtualRobotMerger::merge(const GridMap& from, const GridMap& to) {
  MergeResult result = judgeFoundHypotheses(judge_, from, to, hypotheses(from, to), name(),
                                            "virtual robot (skeleton walks)");
  judge_.alignOnInputs(from, to, result);
  if (result.accepted) {
    refuseDissimilar(from, to, result);
  }
  return result;
}

void VirtualRobotMerger::refuseDissimilar(const GridMap& from, const GridMap& to,
                                          MergeResult& result) const {
  const SimilaritySettings& classes = judge_.settings().similarity;
  const double psi = overlapDissimilarity(prepareDissimilarity(from, classes),
                                          prepareDissimilarity(to, classes), result.T_to_from);
  if (psi <= settings_.max_overlap_psi) {
    return;
  }
  result.accepted = false;
  result.refusal = MergeRefusal::kDissimilarity;
  result.reason = "virtual robot (skeleton walks): ψ over the overlap " + reasonFigure(psi) +
                  " cells is above " + reasonFigure(settings_.max_overlap_psi);
}

}  // namespace mrslam::fusion
