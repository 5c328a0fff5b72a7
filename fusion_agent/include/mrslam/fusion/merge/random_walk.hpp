#pragma once
// Random-walk optimisation of Carpin's dissimilarity ψ (seed 002, Algorithm 3): from a starting
// transform, Gaussian steps in (x, y, θ) are tried and kept when they lower ψ; after `patience`
// steps in a row that do not, the step sizes shrink (down to their floors), so the walk first
// roams and then settles. Seeded: the same inputs give the same walk.

#include <cstdint>

#include "mrslam/fusion/merge/dissimilarity.hpp"

namespace mrslam::fusion {

struct RandomWalkSettings {
  int iterations = 600;                       ///< steps tried
  double step_cells = 2.0;                    ///< σ of a step in x and y (cells), at first
  double step_rad = 2.0 * M_PI / 180.0;       ///< σ of a step in θ, at first
  double min_step_cells = 0.05;               ///< floor of the x/y step
  double min_step_rad = 0.05 * M_PI / 180.0;  ///< floor of the θ step
  int patience = 30;                          ///< refused steps in a row before shrinking
  double shrink = 0.5;                        ///< step factor when patience runs out
  std::uint64_t seed = 1;
};

struct RandomWalkResult {
  GridTransform T_to_from;
  double psi = 0.0;        ///< at T_to_from
  double start_psi = 0.0;  ///< at the start
  int accepted_steps = 0;
};

/// The walk from `start`; ψ never increases along it.
RandomWalkResult randomWalk(const DissimilarityMap& from, const DissimilarityMap& to,
                            const GridTransform& start, const RandomWalkSettings& settings);

}  // namespace mrslam::fusion
