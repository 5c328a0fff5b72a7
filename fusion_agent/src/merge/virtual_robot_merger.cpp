// The virtual-robot merger: its hypotheses fitted to the maps and verified (virtual_robot.hpp).

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mrslam/fusion/merge/local_fit.hpp"
#include "mrslam/fusion/merge/overlap_score.hpp"
#include "mrslam/fusion/merge/virtual_robot.hpp"

namespace mrslam::fusion {

namespace {

constexpr double kDistinctCells = 10.0;                ///< hypotheses farther apart are rivals
constexpr double kDistinctRad = 5.0 * M_PI / 180.0;    ///< ... or turned by more than this
constexpr double kPolishShiftM = 0.1;                  ///< the final fit's shifts, m
constexpr double kPolishTurnRad = 0.6 * M_PI / 180.0;  ///< ... and turns
constexpr double kPolishStepRad = 0.1 * M_PI / 180.0;  ///< ... in steps of this

struct Judged {
  LocalFit fit;
  bool passes = false;
  std::string failure;
};

bool distinct(const GridTransform& a, const GridTransform& b, const Eigen::Vector2d& pivot) {
  return (a.apply(pivot) - b.apply(pivot)).norm() > kDistinctCells ||
         std::abs(wrapAngle(a.theta_rad - b.theta_rad)) > kDistinctRad;
}

Judged judge(const GridMap& from, const GridMap& to, const GridTransform& hypothesis,
             const VirtualRobotSettings& settings) {
  LocalFitSettings fit_settings;
  fit_settings.max_shift_m = settings.fit_shift_m;
  fit_settings.max_turn_rad = settings.fit_turn_rad;
  Judged judged;
  judged.fit = fitNear(from, to, hypothesis, fit_settings);
  std::ostringstream failure;
  if (judged.fit.overlap_cells < settings.min_overlap_cells) {
    failure << "overlap " << judged.fit.overlap_cells << " cells < " << settings.min_overlap_cells;
  } else if (judged.fit.verification < settings.min_verification_v) {
    failure << "V " << judged.fit.verification << " < " << settings.min_verification_v;
  } else if (judged.fit.structure < settings.min_structure_agreement) {
    failure << "structure agreement " << judged.fit.structure << " < "
            << settings.min_structure_agreement;
  }
  judged.failure = failure.str();
  judged.passes = judged.failure.empty();
  return judged;
}

/// A building of right angles fits itself turned by 90° or 180° nearly as well: the best
/// hypothesis turned so about its overlap, each fitted within ±rotation_rival_shift_m, must
/// score clearly less. Returns the largest such score as a share of the best's.
double rotationRivalShare(const GridMap& from, const GridMap& to, const Judged& best,
                          const Eigen::Vector2d& pivot, const VirtualRobotSettings& settings) {
  const LocalFitSettings fit_settings{settings.rotation_rival_shift_m, settings.fit_turn_rad,
                                      0.5 * M_PI / 180.0};
  double largest = 0.0;
  for (const double turn : {0.5 * M_PI, M_PI, -0.5 * M_PI}) {
    const LocalFit rival =
        fitNear(from, to, turnedAbout(best.fit.T_to_from, pivot, turn), fit_settings);
    largest = std::max(largest, rival.similarity() / best.fit.similarity());
  }
  return largest;
}

Eigen::Vector2d centreOf(const GridMap& map) {
  return Eigen::Vector2d(0.5 * map.geometry.width, 0.5 * map.geometry.height);
}

}  // namespace

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
  s.min_verification_v = config.getDouble("min_verification_v", s.min_verification_v, {0.0, 1.0});
  s.min_structure_agreement =
      config.getDouble("min_structure_agreement", s.min_structure_agreement, {0.0, 1.0});
  s.min_overlap_cells = static_cast<std::size_t>(
      config.getInt("min_overlap_cells", static_cast<long long>(s.min_overlap_cells), {0.0, 1e9}));
  s.max_rival_share = config.getDouble("max_rival_share", s.max_rival_share, {0.0, 1.0});
  s.rotation_rival_shift_m =
      config.getDouble("rotation_rival_shift_m", s.rotation_rival_shift_m, {0.0, 100.0});
  s.fit_shift_m = config.getDouble("fit_shift_m", s.fit_shift_m, {0.0, 10.0});
  s.fit_turn_rad = config.getDouble("fit_turn_rad", s.fit_turn_rad, {0.0, M_PI});
  s.seed = static_cast<std::uint64_t>(
      config.getInt("seed", static_cast<long long>(s.seed), {0.0, 9007199254740992.0}));
  return s;
}

MergeResult VirtualRobotMerger::merge(const GridMap& from, const GridMap& to) {
  MergeResult result;
  result.method = name();
  if (from.geometry.resolution_m != to.geometry.resolution_m) {
    result.reason = "the maps' resolutions differ";
    return result;
  }
  const std::vector<GridTransform> found = hypotheses(from, to);
  result.trials = static_cast<int>(found.size());
  if (found.empty()) {
    result.reason = "virtual robot: no skeleton walk or no hypothesis";
    return result;
  }
  std::vector<Judged> judged;
  for (const GridTransform& hypothesis : found) {
    judged.push_back(judge(from, to, hypothesis, settings_));
  }
  const auto best =
      std::max_element(judged.begin(), judged.end(), [](const Judged& a, const Judged& b) {
        return (a.passes ? 1 : 0) != (b.passes ? 1 : 0) ? !a.passes
                                                        : a.fit.similarity() < b.fit.similarity();
      });
  result.verification = best->fit.verification;
  if (!best->passes) {
    result.reason = "virtual robot: best hypothesis refused: " + best->failure;
    return result;
  }
  // A distinct hypothesis with walls on walls nearly as good: the maps do not decide.
  const Eigen::Vector2d pivot = centreOf(from);
  for (const Judged& other : judged) {
    if (&other != &*best && other.fit.structure >= settings_.min_structure_agreement &&
        distinct(other.fit.T_to_from, best->fit.T_to_from, pivot) &&
        other.fit.similarity() >= settings_.max_rival_share * best->fit.similarity()) {
      std::ostringstream reason;
      reason << "virtual robot: ambiguous: a distinct hypothesis scores "
             << other.fit.similarity() / best->fit.similarity() << " of the best";
      result.reason = reason.str();
      return result;
    }
  }
  const double turned_share = rotationRivalShare(from, to, *best, pivot, settings_);
  if (turned_share >= settings_.max_rival_share) {
    std::ostringstream reason;
    reason << "virtual robot: ambiguous: the fit turned by a right angle scores " << turned_share
           << " of the best";
    result.reason = reason.str();
    return result;
  }
  // A last, finer fit: the hypotheses' fit steps 0.25°.
  const LocalFit polished =
      fitNear(from, to, best->fit.T_to_from, {kPolishShiftM, kPolishTurnRad, kPolishStepRad});
  result.accepted = true;
  result.T_to_from = polished.T_to_from;
  result.verification = polished.verification;
  result.entropy = scoreOverlap(from, to, result.T_to_from).entropy_bits;
  return result;
}

}  // namespace mrslam::fusion
