#include "mrslam/fusion/merge/exhaustive_merger.hpp"

#include <cmath>
#include <sstream>
#include <utility>

#include "mrslam/fusion/merge/overlap_score.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {

namespace {

std::vector<GridTransform> inverses(const std::vector<GridTransform>& transforms) {
  std::vector<GridTransform> result;
  for (const GridTransform& T_to_from : transforms) {
    result.push_back(T_to_from.inverse());
  }
  return result;
}

/// The judge's settings with judged_hypotheses as its judged_candidates (unless 0).
SeedMergerSettings judgeSettings(const ExhaustiveMergerSettings& settings,
                                 SeedMergerSettings judge) {
  if (settings.judged_hypotheses > 0) {
    judge.judged_candidates = settings.judged_hypotheses;
  }
  return judge;
}

}  // namespace

ExhaustiveMerger::ExhaustiveMerger(ExhaustiveMergerSettings settings,
                                   const SeedMergerSettings& judge, std::string name)
    : settings_(settings),
      judge_(judgeSettings(settings, judge)),
      classes_(judge.similarity),
      name_(std::move(name)) {}

ExhaustiveMergerSettings strictExhaustiveMergerSettings() {
  ExhaustiveMergerSettings s;
  s.search.conflict_penalty = 20.0;
  s.search.free_penalty = 20.0;
  s.search.free_margin = 2;
  return s;
}

ExhaustiveMergerSettings loadExhaustiveMergerSettings(const Config& config,
                                                      const ExhaustiveMergerSettings& defaults) {
  ExhaustiveMergerSettings s = defaults;
  s.search = loadExhaustiveSearchSettings(config, defaults.search);
  s.judged_hypotheses =
      static_cast<int>(config.getInt("judged_hypotheses", s.judged_hypotheses, {0, 1000}));
  s.check_both_ways = config.getBool("check_both_ways", s.check_both_ways);
  s.agreement_cells = config.getDouble("agreement_cells", s.agreement_cells, {0.0, 1000.0});
  s.agreement_deg = config.getDouble("agreement_deg", s.agreement_deg, {0.0, 180.0});
  s.check_own_score = config.getBool("check_own_score", s.check_own_score);
  s.return_own_peak = config.getBool("return_own_peak", s.return_own_peak);
  s.max_turn_ambiguity = config.getDouble("max_turn_ambiguity", s.max_turn_ambiguity, {0.0, 10.0});
  s.ambiguity_turn_deg = config.getDouble("ambiguity_turn_deg", s.ambiguity_turn_deg, {0.0, 45.0});
  s.ambiguity_shift_cells =
      static_cast<int>(config.getInt("ambiguity_shift_cells", s.ambiguity_shift_cells, {0, 100}));
  s.own_score_turn_deg = config.getDouble("own_score_turn_deg", s.own_score_turn_deg, {0.0, 45.0});
  s.own_score_shift_cells =
      static_cast<int>(config.getInt("own_score_shift_cells", s.own_score_shift_cells, {0, 100}));
  return s;
}

ExhaustiveSearchSettings loadExhaustiveSearchSettings(const Config& config,
                                                      const ExhaustiveSearchSettings& defaults) {
  ExhaustiveSearchSettings s = defaults;
  s.cell_size = static_cast<int>(config.getInt("cell_size", s.cell_size, {1, 16}));
  s.max_grid_cells =
      static_cast<int>(config.getInt("max_grid_cells", s.max_grid_cells, {0, 100000}));
  s.rotation_step_cells =
      config.getDouble("rotation_step_cells", s.rotation_step_cells, {0.1, 10.0});
  s.wall_sigma = config.getDouble("wall_sigma", s.wall_sigma, {0.1, 100.0});
  s.wall_reach = config.getDouble("wall_reach", s.wall_reach, {0.0, 100.0});
  s.free_penalty = config.getDouble("free_penalty", s.free_penalty, {0.0, 1000.0});
  s.max_points = static_cast<int>(config.getInt("max_points", s.max_points, {1, 1000000}));
  s.max_free_points =
      static_cast<int>(config.getInt("max_free_points", s.max_free_points, {0, 1000000}));
  s.free_weight = config.getDouble("free_weight", s.free_weight, {0.0, 1000.0});
  s.conflict_penalty = config.getDouble("conflict_penalty", s.conflict_penalty, {0.0, 1000.0});
  s.free_margin = static_cast<int>(config.getInt("free_margin", s.free_margin, {0, 100}));
  s.depth = static_cast<int>(config.getInt("depth", s.depth, {0, 12}));
  s.hypotheses = static_cast<int>(config.getInt("hypotheses", s.hypotheses, {1, 1000}));
  s.min_score_share = config.getDouble("min_score_share", s.min_score_share, {0.0, 1.0});
  s.min_best_share = config.getDouble("min_best_share", s.min_best_share, {0.0, 1.0});
  s.distinct_cells = config.getDouble("distinct_cells", s.distinct_cells, {0.0, 10000.0});
  s.distinct_deg = config.getDouble("distinct_deg", s.distinct_deg, {0.0, 180.0});
  s.search_hypotheses =
      static_cast<int>(config.getInt("search_hypotheses", s.search_hypotheses, {1, 1000}));
  s.both_ways = config.getBool("both_ways", s.both_ways);
  s.rotation_peaks = static_cast<int>(config.getInt("rotation_peaks", s.rotation_peaks, {0, 90}));
  s.rotation_window_deg =
      config.getDouble("rotation_window_deg", s.rotation_window_deg, {0.0, 90.0});
  return s;
}

std::vector<GridTransform> ExhaustiveMerger::hypotheses(const GridMap& from,
                                                        const GridMap& to) const {
  return hypotheses(from, to, ExhaustiveScore(from, to, settings_.search, classes_));
}

std::vector<GridTransform> ExhaustiveMerger::hypotheses(const GridMap& from, const GridMap& to,
                                                        const ExhaustiveScore& score) const {
  std::vector<GridTransform> found;
  for (const ExhaustiveHypothesis& hypothesis :
       exhaustiveSearch(from, to, score, settings_.search, classes_)) {
    found.push_back(hypothesis.T_to_from);
  }
  return found;
}

MergeResult ExhaustiveMerger::merge(const GridMap& from, const GridMap& to) {
  times_.clear();
  BlockClock clock;
  const ExhaustiveScore score(from, to, settings_.search, classes_);
  addBlockTime(times_, "prepare", clock.lapMs());
  const std::vector<GridTransform> found =
      timeBlock(times_, "search", [&] { return hypotheses(from, to, score); });
  MergeResult result = timeBlock(times_, "judge", [&] {
    return judgeFoundHypotheses(judge_, from, to, found, name(), "exhaustive search");
  });
  result.hypotheses = found;
  if (!result.accepted) {
    return result;
  }
  const Eigen::Vector2d pivot = knownCentroid(from);
  if (ownPeakNeeded()) {
    timeBlock(times_, "own_peak", [&] { applyOwnPeakChecks(from, to, score, pivot, result); });
  }
  if (result.accepted && settings_.check_both_ways) {
    timeBlock(times_, "other_way", [&] { checkTheOtherWay(from, to, found, pivot, result); });
  }
  timeBlock(times_, "alignment", [&] { judge_.alignOnInputs(from, to, result); });
  return result;
}

void ExhaustiveMerger::refuseUnlessAgreeing(const Eigen::Vector2d& centre,
                                            const GridTransform& other, const std::string& what,
                                            MergeResult& result) const {
  const double cells = (other.apply(centre) - result.T_to_from.apply(centre)).norm();
  const double deg =
      std::abs(std::remainder(other.theta_rad - result.T_to_from.theta_rad, 2.0 * M_PI)) * 180.0 /
      M_PI;
  if (cells > settings_.agreement_cells || deg > settings_.agreement_deg) {
    std::ostringstream reason;
    reason << "exhaustive search: " << what << " lies " << cells << " cells and " << deg
           << " degrees from the accepted transform";
    result.accepted = false;
    result.reason = reason.str();
  }
}

void ExhaustiveMerger::refuseUnlessTurnFixed(const ExhaustiveScore& score,
                                             const Eigen::Vector2d& centre,
                                             const ExhaustiveHypothesis& peak,
                                             MergeResult& result) const {
  const Eigen::Vector2d landed = peak.T_to_from.apply(centre);
  double largest = 0.0;
  for (const double sign : {-1.0, 1.0}) {
    GridTransform turned = peak.T_to_from;
    turned.theta_rad += sign * settings_.ambiguity_turn_deg * M_PI / 180.0;
    turned.t_cells += landed - turned.apply(centre);
    const ExhaustiveHypothesis rival =
        score.bestNear(turned, 0.0, 0, settings_.ambiguity_shift_cells);
    largest = std::max(largest, rival.score);
  }
  const double share = peak.score > 0.0 ? largest / peak.score : 1.0;
  if (share >= settings_.max_turn_ambiguity) {
    std::ostringstream reason;
    reason << "exhaustive search: the overlap does not fix the rotation: turned by "
           << settings_.ambiguity_turn_deg << " degrees it scores " << share << " of the best";
    result.accepted = false;
    result.reason = reason.str();
  }
}

bool ExhaustiveMerger::ownPeakNeeded() const {
  return settings_.check_own_score || settings_.max_turn_ambiguity < 1.0 ||
         settings_.return_own_peak;
}

void ExhaustiveMerger::applyOwnPeakChecks(const GridMap& from, const GridMap& to,
                                          const ExhaustiveScore& score,
                                          const Eigen::Vector2d& pivot, MergeResult& result) const {
  constexpr int kTurnSteps = 8;
  const ExhaustiveHypothesis best =
      score.bestNear(result.T_to_from, settings_.own_score_turn_deg * M_PI / 180.0, kTurnSteps,
                     settings_.own_score_shift_cells);
  if (settings_.check_own_score) {
    refuseUnlessAgreeing(pivot, best.T_to_from, "the search's own score peaks elsewhere: its best",
                         result);
  }
  if (result.accepted && settings_.max_turn_ambiguity < 1.0) {
    refuseUnlessTurnFixed(score, pivot, best, result);
  }
  if (result.accepted && settings_.return_own_peak) {
    const OverlapScore overlap = scoreOverlap(from, to, best.T_to_from);
    result.T_to_from = best.T_to_from;
    result.verification = overlap.verification();
    result.entropy = overlap.entropy_bits;
  }
}

void ExhaustiveMerger::checkTheOtherWay(const GridMap& from, const GridMap& to,
                                        const std::vector<GridTransform>& found,
                                        const Eigen::Vector2d& pivot, MergeResult& result) {
  const MergeResult other = judge_.judgeHypotheses(to, from, inverses(found));
  if (!other.accepted) {
    result.accepted = false;
    result.reason = "exhaustive search: refused the other way: " + other.reason;
    return;
  }
  refuseUnlessAgreeing(pivot, other.T_to_from.inverse(), "the other way's transform", result);
}

}  // namespace mrslam::fusion
