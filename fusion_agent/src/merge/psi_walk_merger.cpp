#include "mrslam/fusion/merge/psi_walk_merger.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mrslam::fusion {

namespace {

/// Every k-th cell of `cells`, k the least that leaves at most `max_cells` of them.
std::vector<Eigen::Vector2i> evenSample(const std::vector<Eigen::Vector2i>& cells, int max_cells) {
  const std::size_t limit = static_cast<std::size_t>(std::max(1, max_cells));
  if (cells.size() <= limit) {
    return cells;
  }
  const std::size_t stride = (cells.size() + limit - 1) / limit;
  std::vector<Eigen::Vector2i> sample;
  for (std::size_t i = 0; i < cells.size(); i += stride) {
    sample.push_back(cells[i]);
  }
  return sample;
}

RandomWalkSettings loadWalkSettings(const Config& config) {
  RandomWalkSettings s;
  s.iterations = static_cast<int>(config.getInt("iterations", s.iterations, {1, 100000}));
  s.step_cells = config.getDouble("step_cells", s.step_cells, {0.0, 100.0});
  s.step_rad = config.getDouble("step_deg", s.step_rad * 180.0 / M_PI, {0.0, 45.0}) * M_PI / 180.0;
  s.min_step_cells = config.getDouble("min_step_cells", s.min_step_cells, {0.0, 100.0});
  s.min_step_rad =
      config.getDouble("min_step_deg", s.min_step_rad * 180.0 / M_PI, {0.0, 45.0}) * M_PI / 180.0;
  s.patience = static_cast<int>(config.getInt("patience", s.patience, {1, 100000}));
  s.shrink = config.getDouble("shrink", s.shrink, {0.01, 1.0});
  s.seed = static_cast<std::uint64_t>(
      config.getInt("seed", static_cast<long long>(s.seed), {0, 1000000000}));
  return s;
}

}  // namespace

PsiWalkSettings loadPsiWalkSettings(const Config& config) {
  PsiWalkSettings s;
  s.starts = static_cast<int>(config.getInt("starts", s.starts, {1, 100}));
  s.max_cells = static_cast<int>(config.getInt("max_cells", s.max_cells, {10, 10000000}));
  s.walk = loadWalkSettings(config);
  return s;
}

DissimilarityMap sampledDissimilarity(const GridMap& map, const SimilaritySettings& classes,
                                      int max_cells) {
  DissimilarityMap prepared = prepareDissimilarity(map, classes);
  prepared.occupied_cells = evenSample(prepared.occupied_cells, max_cells);
  prepared.free_cells = evenSample(prepared.free_cells, max_cells);
  return prepared;
}

PsiWalkMerger::PsiWalkMerger(PsiWalkSettings settings, const SeedMergerSettings& judge)
    : settings_(std::move(settings)), judge_(judge) {}

std::vector<GridTransform> PsiWalkMerger::walkedHypotheses(const GridMap& from,
                                                           const GridMap& to) const {
  const SimilaritySettings& classes = judge_.settings().similarity;
  const std::vector<ExhaustiveHypothesis> starts =
      exhaustiveSearch(from, to, settings_.search, classes);
  if (starts.empty()) {
    return {};
  }
  const DissimilarityMap psi_from = sampledDissimilarity(from, classes, settings_.max_cells);
  const DissimilarityMap psi_to = sampledDissimilarity(to, classes, settings_.max_cells);
  std::vector<std::pair<double, GridTransform>> ends;
  const std::size_t count = std::min(starts.size(), static_cast<std::size_t>(settings_.starts));
  for (std::size_t i = 0; i < count; ++i) {
    const RandomWalkResult walked =
        randomWalk(psi_from, psi_to, starts[i].T_to_from, settings_.walk);
    ends.emplace_back(walked.psi, walked.T_to_from);
  }
  std::stable_sort(ends.begin(), ends.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<GridTransform> walked;
  for (const auto& end : ends) {
    walked.push_back(end.second);
  }
  return walked;
}

MergeResult PsiWalkMerger::merge(const GridMap& from, const GridMap& to) {
  const std::vector<GridTransform> walked = from.geometry.resolution_m == to.geometry.resolution_m
                                                ? walkedHypotheses(from, to)
                                                : std::vector<GridTransform>{};
  MergeResult result = judgeFoundHypotheses(judge_, from, to, walked, name(), "psi random walk");
  result.hypotheses = walked;
  if (result.accepted) {
    judge_.alignOnInputs(from, to, result);
  }
  return result;
}

}  // namespace mrslam::fusion
