#include "mrslam/fusion/merge/random_walk.hpp"

#include <algorithm>
#include <random>

namespace mrslam::fusion {

RandomWalkResult randomWalk(const DissimilarityMap& from, const DissimilarityMap& to,
                            const GridTransform& start, const RandomWalkSettings& settings) {
  std::mt19937_64 random(settings.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  RandomWalkResult result;
  result.T_to_from = start;
  result.psi = dissimilarity(from, to, start);
  result.start_psi = result.psi;
  double step_cells = settings.step_cells;
  double step_rad = settings.step_rad;
  int refused_in_a_row = 0;
  for (int i = 0; i < settings.iterations; ++i) {
    GridTransform tried = result.T_to_from;
    tried.theta_rad += step_rad * gauss(random);
    tried.t_cells += step_cells * Eigen::Vector2d(gauss(random), gauss(random));
    const double psi = dissimilarity(from, to, tried);
    if (psi < result.psi) {
      result.T_to_from = tried;
      result.psi = psi;
      ++result.accepted_steps;
      refused_in_a_row = 0;
      continue;
    }
    if (++refused_in_a_row >= settings.patience) {
      step_cells = std::max(settings.min_step_cells, step_cells * settings.shrink);
      step_rad = std::max(settings.min_step_rad, step_rad * settings.shrink);
      refused_in_a_row = 0;
    }
  }
  return result;
}

}  // namespace mrslam::fusion
