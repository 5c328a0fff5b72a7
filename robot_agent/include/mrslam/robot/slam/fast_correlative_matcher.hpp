#pragma once
// Branch-and-bound scan matching for loop closure (Hess, Kohler, Rapp, Andor, "Real-Time Loop
// Closure in 2D LIDAR SLAM", ICRA 2016, section V, algorithms 2 and 3):
//  1. Search window (V.A): around the guess ξ0, the translations (j_x·r, j_y·r) with
//     |j| ≤ w_xy = ⌈W_xy / r⌉ and the rotations j_θ·δθ with |j_θ| ≤ ⌈W_θ / δθ⌉, δθ from the
//     farthest point (eq. 7, see angularSearchStep). The score of a candidate is the mean over
//     the points of the probability of the cell each falls in (unknown or outside: p_min).
//  2. Precomputation (V.C), once per finished submap: for each height h = 0 … depth − 1 a grid
//       M_h(x, y) = max { M(x', y') : x ≤ x' < x + 2^h, y ≤ y' < y + 2^h },
//     built from M_{h−1} as the max of its four cells (x, y), (x + 2^(h−1), y), ... . A
//     candidate at height h stands for the 2^h × 2^h translations (j_x … j_x + 2^h − 1, ...) of one
//     rotation, and scoring it on M_h bounds the score of every one of them. Probabilities are
//     stored as bytes, [p_min, p_max] → 0 … 255 (unknown: 0); the grids are padded by
//     2^(depth−1) − 1 cells below so a candidate left of the map still sees what it bounds.
//  3. For each rotation the points are rotated once and put in their cells (V.B, algorithm 2);
//     a candidate's translation then shifts those cells by whole cells.
//  4. Branch and bound (V.B, algorithm 3), depth first: the candidates of height depth − 1 that
//     tile the window, best bound first; a candidate whose bound is ≤ the best score so far
//     (initially min_score) is pruned with all that follow it; an inner candidate is split into
//     its (up to) four children at height h − 1, which are scored and visited best first; a
//     leaf (h = 0) whose score beats the best becomes the best. The result is the best candidate
//     of the exhaustive search over the same discretisation (on equal scores, one of them).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "mrslam/common/se2.hpp"
#include "mrslam/robot/slam/probability_grid.hpp"

namespace mrslam::robot::slam {

struct FastCorrelativeSettings {
  double linear_search_window_m = 7.0;                   ///< W_xy: ± this in x and in y
  double angular_search_window_rad = 30.0 * M_PI / 180;  ///< W_θ: ± this; ≥ π searches all turns
  int branch_and_bound_depth = 7;  ///< number of precomputed grids, heights 0 … depth − 1
};

struct FastMatch {
  SE2 T_submap_robot;
  double score = 0.0;  ///< mean probability of the points' cells (unknown: p_min), as stored
};

class FastCorrelativeMatcher {
 public:
  /// Precomputes the grids of `grid` (a finished submap; no reference to it is kept). Throws
  /// std::invalid_argument for negative or non-finite windows or a depth outside 1 … 16.
  FastCorrelativeMatcher(const ProbabilityGrid& grid, const FastCorrelativeSettings& settings);

  /// Best candidate of the window around T_submap_robot_guess scoring above min_score; nullopt
  /// when there are no points or no candidate scores above min_score.
  std::optional<FastMatch> match(const SE2& T_submap_robot_guess,
                                 const std::vector<Eigen::Vector2d>& points_robot,
                                 double min_score) const;
  /// As match, with the window ±linear_window_m, ±angular_window_rad instead of the settings'
  /// (the precomputed grids do not depend on the window: any window may be searched).
  std::optional<FastMatch> match(const SE2& T_submap_robot_guess,
                                 const std::vector<Eigen::Vector2d>& points_robot, double min_score,
                                 double linear_window_m, double angular_window_rad) const;

  /// As match, over every translation that puts the robot in the grid and every rotation.
  std::optional<FastMatch> matchFullSubmap(const std::vector<Eigen::Vector2d>& points_robot,
                                           double min_score) const;

  /// Mean stored probability (height 0) of the cells of T_submap_robot · points; p_min when
  /// there are no points.
  double score(const SE2& T_submap_robot, const std::vector<Eigen::Vector2d>& points_robot) const;

  /// Stored value of precomputed grid `height` at a cell of the original grid (any cell; outside
  /// the padded grids: p_min), as a probability.
  double precomputed(int height, const Eigen::Vector2i& cell) const;

  int depth() const { return settings_.branch_and_bound_depth; }
  /// Bytes of the precomputed grids.
  std::size_t memoryBytes() const;
  const FastCorrelativeSettings& settings() const { return settings_; }

 private:
  struct Candidate;
  struct Search;

  std::optional<FastMatch> search(const SE2& T_submap_centre, int window_cells_x,
                                  int window_cells_y, double angular_window_rad,
                                  const std::vector<Eigen::Vector2d>& points_robot,
                                  double min_score) const;
  void descend(const Search& search, Candidate* candidates, std::size_t count, int height,
               Candidate* best) const;
  std::vector<Candidate> initialCandidates(const Search& search) const;
  std::int64_t boundOf(const Search& search, const Candidate& candidate, int height) const;
  void scoreAndSort(const Search& search, Candidate* candidates, std::size_t count,
                    int height) const;
  Eigen::Vector2i paddedCellOf(const Eigen::Vector2d& point_submap) const;
  std::uint8_t valueAt(int height, const Eigen::Vector2i& padded_cell) const;
  double probabilityOf(double mean_value) const;
  std::int64_t sumThreshold(double min_score, std::size_t point_count) const;
  void precompute(const ProbabilityGrid& grid);

  const FastCorrelativeSettings settings_;
  double resolution_m_ = 0.05;
  double min_probability_ = 0.1;
  double max_probability_ = 0.9;
  Eigen::Vector2i origin_cell_{0, 0};  ///< lattice index of original grid cell (0, 0)
  int width_ = 0;                      ///< of the original grid
  int height_ = 0;
  int pad_ = 0;  ///< 2^(depth−1) − 1 cells below the original grid's
  int padded_width_ = 0;
  int padded_height_ = 0;
  std::vector<std::vector<std::uint8_t>> grids_;  ///< M_h, row-major, padded
};

}  // namespace mrslam::robot::slam
