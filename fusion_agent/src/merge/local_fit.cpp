// The local fit of a transform to two maps (local_fit.hpp).

#include "mrslam/fusion/merge/local_fit.hpp"

#include <algorithm>
#include <cmath>

#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {

namespace {

constexpr int kSampledCellsPerClass = 2500;  ///< samples of each class for the search

Eigen::Vector2d centroidOf(const std::vector<CellSample>& cells) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const CellSample& cell : cells) {
    sum += Eigen::Vector2d(cell.x, cell.y);
  }
  return cells.empty() ? sum : Eigen::Vector2d(sum / static_cast<double>(cells.size()));
}

std::vector<CellSample> occupiedOf(const std::vector<CellSample>& cells,
                                   const ComparisonTables& tables) {
  std::vector<CellSample> occupied;
  std::copy_if(cells.begin(), cells.end(), std::back_inserter(occupied),
               [&](const CellSample& cell) { return tables.isOccupied(cell.code); });
  return occupied;
}

}  // namespace

GridTransform turnedAbout(const GridTransform& T_to_from, const Eigen::Vector2d& pivot,
                          double delta_rad) {
  GridTransform turned = T_to_from;
  turned.theta_rad = T_to_from.theta_rad + delta_rad;
  turned.t_cells = T_to_from.apply(pivot) - (turned.apply(pivot) - turned.t_cells);
  return turned;
}

LocalFit fitNear(const GridMap& from, const GridMap& to, const GridTransform& start,
                 const LocalFitSettings& settings) {
  const ComparisonTables tables{SimilaritySettings{}};
  const std::vector<CellSample> known_from = knownCells(from, tables);
  const std::vector<CellSample> known_to = knownCells(to, tables);
  const std::vector<CellSample> samples =
      sampleKnownCells(known_from, tables, kSampledCellsPerClass, kSampledCellsPerClass);
  const int reach =
      std::max(1, static_cast<int>(std::ceil(settings.max_shift_m / to.geometry.resolution_m)));
  const CodeImage to_image = codeImage(to, reach + 2, tables);
  const Eigen::Vector2d pivot = centroidOf(samples);
  // Block 8 at every turn within the bound: the largest agr - dis wins.
  LocalFit fit;
  long long best_similarity = 0;
  bool first = true;
  const double step = std::max(settings.turn_step_rad, 1e-4);
  const int turns = static_cast<int>(std::floor(settings.max_turn_rad / step));
  for (int k = -turns; k <= turns; ++k) {
    const GridTransform turned = turnedAbout(start, pivot, k * step);
    const TranslationSearch search = searchTranslation(samples, to_image, turned, reach, tables,
                                                       /*with_entropy=*/false);
    if (first || search.at_best_similarity.similarity() > best_similarity) {
      first = false;
      best_similarity = search.at_best_similarity.similarity();
      fit.T_to_from = search.best_similarity;
    }
  }
  // Block 9 over every known cell, and the walls of each map against the other's.
  const Agreement full = compareAt(known_from, to_image, fit.T_to_from, tables, false);
  fit.verification = verificationIndex(full);
  fit.overlap_cells = static_cast<std::size_t>(full.overlap());
  const CodeImage from_image = codeImage(from, reach + 2, tables);
  fit.structure = std::min(
      structureAgreement(occupiedOf(known_from, tables), to_image, fit.T_to_from, tables).index(),
      structureAgreement(occupiedOf(known_to, tables), from_image, fit.T_to_from.inverse(), tables)
          .index());
  return fit;
}

}  // namespace mrslam::fusion
