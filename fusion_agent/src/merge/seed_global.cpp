// Step 10 of seed_merger.hpp: the global search's coarse transforms (global_search.hpp) refined
// at full resolution, so that block 8's ±δ search and the rotation polish start close enough.
//
// For each coarse transform: rotations within half a sweep step plus one polish step of it, in
// `global_polish_step` steps, each turned about the centre of `from`'s known cells; at each, the
// translations within ±`coarse_cells` in steps of 2 cells and then ±1 cell around the best;
// the transform of the best coarse score (CoarseScorer) is the hypothesis.

#include <cmath>

#include "mrslam/fusion/merge/approximate_pose.hpp"
#include "mrslam/fusion/merge/global_search.hpp"
#include "seed_stages.hpp"

namespace mrslam::fusion::seed {

namespace {

Hypothesis refineCoarse(const GridTransform& coarse, const CoarseScorer& scorer,
                        const SearchInputs& inputs, const SeedMergerSettings& settings) {
  const double step = settings.global_polish_step_rad;
  const int turns = static_cast<int>(std::ceil(0.5 * settings.global.rotation_step_rad / step));
  const Eigen::Vector2d placed_pivot = coarse.apply(inputs.pivot_from);
  Hypothesis best{coarse, -2.0, Stage::kGlobalSearch};
  for (int i = -turns; i <= turns; ++i) {
    GridTransform turned;
    turned.theta_rad = coarse.theta_rad + i * step;
    turned.t_cells = translationFromCentroids(turned.theta_rad, inputs.pivot_from, placed_pivot);
    const Hypothesis at_turn =
        bestShift(turned, settings.global.coarse_cells, 2, scorer, Stage::kGlobalSearch);
    if (at_turn.coarse_score > best.coarse_score) {
      best = at_turn;
    }
  }
  const Hypothesis fine = bestShift(best.T_to_from, 1, 1, scorer, Stage::kGlobalSearch);
  return fine.coarse_score > best.coarse_score ? fine : best;
}

}  // namespace

GlobalHypotheses globalHypotheses(const GridMap& from, const GridMap& to,
                                  const CoarseScorer& scorer, const SearchInputs& inputs,
                                  const SeedMergerSettings& settings) {
  GlobalHypotheses hypotheses;
  for (const GlobalHypothesis& coarse :
       globalSearch(from, to, settings.global, settings.similarity)) {
    (coarse.by_free_agreement ? hypotheses.by_free_agreement : hypotheses.by_walls)
        .push_back(refineCoarse(coarse.T_to_from, scorer, inputs, settings));
  }
  return hypotheses;
}

}  // namespace mrslam::fusion::seed
