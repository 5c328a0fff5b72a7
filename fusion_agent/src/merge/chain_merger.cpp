#include "mrslam/fusion/merge/chain_merger.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "mrslam/fusion/merge/dissimilarity.hpp"
#include "mrslam/fusion/merge/global_search.hpp"
#include "mrslam/fusion/merge/random_walk.hpp"

namespace mrslam::fusion {

ChainMerger::ChainMerger(std::vector<std::unique_ptr<MapMerger>> steps, ChainSettings settings,
                         const SeedMergerSettings& judge)
    : steps_(std::move(steps)), settings_(settings), judge_(judge) {
  if (steps_.empty()) {
    throw std::invalid_argument("a merge chain needs at least one step");
  }
}

MergeResult ChainMerger::merge(const GridMap& from, const GridMap& to) {
  std::string reasons;
  int trials = 0;
  MergeResult last;
  std::vector<GridTransform> earlier;  // transforms earlier steps refused for a slide alone
  for (const auto& step : steps_) {
    MergeResult result = step->merge(from, to);
    trials += result.trials;
    if (result.accepted && !earlier.empty()) {
      judgeAgainstEarlier(from, to, earlier, result);
    }
    if (result.accepted && settings_.sweep_rivals) {
      judgeAgainstSweep(from, to, result);
    }
    if (result.accepted) {
      result.trials = trials;
      if (settings_.refine_psi) {
        refineByPsi(from, to, settings_, result);
      }
      return result;
    }
    reasons += (reasons.empty() ? "" : "; ") + step->name() + ": " + result.reason;
    if (settings_.slid_rivals && result.refusal == MergeRefusal::kTranslation) {
      earlier.push_back(result.T_to_from);
    }
    last = std::move(result);
  }
  last.method = name();
  last.trials = trials;
  last.reason = reasons;
  return last;
}

void ChainMerger::judgeAgainstEarlier(const GridMap& from, const GridMap& to,
                                      const std::vector<GridTransform>& earlier,
                                      MergeResult& result) {
  const double share = judge_.rivalShareAgainst(from, to, result.T_to_from, earlier);
  if (share > judge_.settings().max_rival_share) {
    std::ostringstream shareText;
    shareText.precision(3);
    shareText << share;
    result.accepted = false;
    result.reason = "a transform an earlier step refused explains the overlap almost as well (" +
                    shareText.str() + " of this one)";
  }
}

void ChainMerger::judgeAgainstSweep(const GridMap& from, const GridMap& to, MergeResult& result) {
  GlobalSearchSettings sweep;
  sweep.rotation_step_rad = settings_.sweep_step_deg * M_PI / 180.0;
  sweep.only_rotations_rad = {result.T_to_from.theta_rad};
  sweep.peaks_per_rotation = settings_.sweep_peaks;
  sweep.kept_hypotheses = settings_.sweep_peaks;
  sweep.free_agreement_hypotheses = 0;
  sweep.coarse_cells = settings_.sweep_coarse_cells;
  std::vector<GridTransform> peaks;
  for (const GlobalHypothesis& peak : globalSearch(from, to, sweep, judge_.settings().similarity)) {
    peaks.push_back(peak.T_to_from);
  }
  if (judge_.cleanerRivalAmong(from, to, result.T_to_from, peaks)) {
    result.accepted = false;
    result.reason =
        "a transform elsewhere at the same rotation explains the overlap more cleanly (a building "
        "that repeats)";
  }
}

namespace {

double verificationAt(const GridMap& from, const CodeImage& to, const GridTransform& T_to_from,
                      const ComparisonTables& tables) {
  return verificationIndex(compareAt(knownCells(from, tables), to, T_to_from, tables, false));
}

}  // namespace

void refineByPsi(const GridMap& from, const GridMap& to, const ChainSettings& settings,
                 MergeResult& result) {
  const SimilaritySettings similarity;
  RandomWalkSettings walk;
  walk.step_cells = 0.5;
  walk.step_rad = 0.25 * M_PI / 180.0;
  const RandomWalkResult refined =
      randomWalk(prepareDissimilarity(from, similarity), prepareDissimilarity(to, similarity),
                 result.T_to_from, walk);
  const Eigen::Vector2d centre(0.5 * from.geometry.width, 0.5 * from.geometry.height);
  const double shift = (refined.T_to_from.apply(centre) - result.T_to_from.apply(centre)).norm();
  const double turn = std::abs(wrapAngle(refined.T_to_from.theta_rad - result.T_to_from.theta_rad));
  if (shift > settings.max_refinement_cells || turn > settings.max_refinement_rad) {
    return;
  }
  const ComparisonTables tables(similarity);
  const CodeImage to_codes = codeImage(to, 2, tables);
  const double refined_v = verificationAt(from, to_codes, refined.T_to_from, tables);
  if (refined_v >= verificationAt(from, to_codes, result.T_to_from, tables)) {
    result.T_to_from = refined.T_to_from;
    result.verification = refined_v;
    result.method += "+psi";
  }
}

ChainSettings loadChainSettings(const Config& chain) {
  ChainSettings s;
  s.refine_psi = chain.getBool("refine_psi", s.refine_psi);
  s.slid_rivals = chain.getBool("slid_rivals", s.slid_rivals);
  s.sweep_rivals = chain.getBool("sweep_rivals", s.sweep_rivals);
  s.sweep_step_deg = chain.getDouble("sweep_step_deg", s.sweep_step_deg, {0.1, 10.0});
  s.sweep_peaks = static_cast<int>(chain.getInt("sweep_peaks", s.sweep_peaks, {1, 100}));
  s.sweep_coarse_cells =
      static_cast<int>(chain.getInt("sweep_coarse_cells", s.sweep_coarse_cells, {1, 16}));
  return s;
}

std::vector<std::string> parseChainSteps(const std::string& steps) {
  std::vector<std::string> names;
  std::stringstream text(steps);
  std::string name;
  while (std::getline(text, name, ',')) {
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    if (name.empty()) {
      continue;
    }
    if (name == "chain") {
      throw std::invalid_argument("a merge chain cannot hold a chain");
    }
    if (std::find(names.begin(), names.end(), name) != names.end()) {
      throw std::invalid_argument("merge chain step '" + name + "' is given twice");
    }
    names.push_back(name);
  }
  if (names.empty()) {
    throw std::invalid_argument("a merge chain needs at least one step");
  }
  return names;
}

}  // namespace mrslam::fusion
