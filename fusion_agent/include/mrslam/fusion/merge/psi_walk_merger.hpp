#pragma once
// Carpin's ψ random walk as a merger of its own (seed 002, Algorithm 3 started from hypotheses):
// the exhaustive search's best distinct transforms (exhaustive_search.hpp) are the starts; from
// each of the first `starts` a random walk lowers ψ (dissimilarity.hpp, random_walk.hpp); the
// walks' ends, lowest ψ first, are judged by the seed pipeline's own acceptance
// (SeedMerger::judgeHypotheses), so that it accepts no transform the seed pipeline would refuse
// had it proposed it, and an accepted one is aligned last like every merger's.
//
// ψ sums over every cell of both maps; the walk takes an even sample of at most `max_cells` of
// each class of each map (the distance maps stay whole), so that a walk costs a few milliseconds
// instead of the half second of every cell of two 400 × 400 maps.

#include <string>
#include <vector>

#include "mrslam/common/config.hpp"
#include "mrslam/fusion/merge/dissimilarity.hpp"
#include "mrslam/fusion/merge/exhaustive_search.hpp"
#include "mrslam/fusion/merge/random_walk.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion {

struct PsiWalkSettings {
  ExhaustiveSearchSettings search;  ///< the starts' search (the `exhaustive:` keys' defaults)
  int starts = 4;                   ///< walks, from the search's best hypotheses in turn
  int max_cells = 4000;             ///< cells of each class of each map in ψ (an even sample)
  RandomWalkSettings walk;          ///< the walk: steps, their shrinking, its seed
};

/// Reads a `psi_walk:` section (every key optional): starts, max_cells, and the walk's
/// iterations, step_cells, step_deg, min_step_cells, min_step_deg, patience, shrink and seed;
/// throws ConfigError for a bad value.
PsiWalkSettings loadPsiWalkSettings(const Config& config);

/// `map` prepared for ψ with at most `max_cells` cells of each class (an even sample).
DissimilarityMap sampledDissimilarity(const GridMap& map, const SimilaritySettings& classes,
                                      int max_cells);

class PsiWalkMerger : public MapMerger {
 public:
  explicit PsiWalkMerger(PsiWalkSettings settings = {}, const SeedMergerSettings& judge = {});
  MergeResult merge(const GridMap& from, const GridMap& to) override;
  std::string name() const override { return "psi_walk"; }
  void shareSearchInputs(const std::shared_ptr<SearchInputsCache>& cache) override {
    judge_.shareSearchInputs(cache);
  }

  /// The walks' ends from the search's first `starts` hypotheses, lowest ψ first.
  std::vector<GridTransform> walkedHypotheses(const GridMap& from, const GridMap& to) const;

 private:
  PsiWalkSettings settings_;
  SeedMerger judge_;  ///< judges the walks' ends; its similarity settings class ψ's cells
};

}  // namespace mrslam::fusion
