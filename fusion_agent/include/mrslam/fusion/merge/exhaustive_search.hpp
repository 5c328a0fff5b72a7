#pragma once
// Exhaustive search (ours, after the correlative branch-and-bound search of scan matching and
// global localisation): hypotheses of T_to_from from every rotation of a full turn and every
// translation, the best ones found exactly on a grid of `cell_size` cells rather than sampled. It
// finds the transforms of small overlaps that the seed pipeline never proposes.
//
// 1. `to` on a grid of `cell_size` cells (a grid cell is a wall when it holds an occupied cell,
//    free when it holds known free cells only); maps whose longest side exceeds
//    `max_grid_cells` grid cells get cells that much larger (searchCellSize: the work grows with
//    the cube of the side, the memory with its square; step 6 still ends at full resolution). Two
//    value grids: what a wall of `from` scores there, exp(-d² / 2σ²) at distance d (grid cells)
//    from `to`'s nearest wall while d ≤ `wall_reach`, else -`free_penalty` on free cells and 0 on
//    unknown ones (d exact: each wall marks the cells within the reach of it, or, where walls are
//    dense, the whole grid's distance transform); and what a free cell of `from` scores there,
//    `free_weight` on free cells, -`conflict_penalty` on walls and 0 on unknown ones. Open floor
//    of both maps agrees, walls meet walls, and either map's walls on the other's open floor cost
//    much: the truth of a small overlap has few such conflicts.
// 2. `from`'s walls and its free cells at least `free_margin` grid cells from its walls (a cell
//    of misalignment must not put them on `to`'s walls), each an even sample of at most
//    `max_points` / `max_free_points`, about the walls' centroid.
// 3. Rotations θ_k = k · step over the full turn, step = `rotation_step_cells` / r (r: the
//    largest distance of a point from the centroid, grid cells), so that no point moves more
//    than that many cells between two rotations. With `rotation_peaks` > 0 only the θ_k within
//    `rotation_window_deg` of the turns the walls suggest: the `rotation_peaks` strongest peaks
//    of the correlation of the two maps' Radon profiles (radon.hpp, of their occupied cells;
//    modulo a half turn), each with its quarter turns. Walls of one building run in few
//    directions, so the turns between two maps of it are few too; the quarter turns are searched
//    whatever the profiles say, as a room turned by a quarter is the wrong merge to rule out.
// 4. The score of (θ, t): the sum of the value grids at the rounded turned points shifted by t.
//    Branch and bound over t: a node covers 2^h × 2^h translations; its bound is the same sum on
//    the grids max-pooled over 2^h × 2^h windows (precomputed for h = 0..`depth`), never below
//    the score of any translation it covers. Nodes of every rotation at h = `depth` are
//    expanded best bound first, depth first; a node is cut when its bound cannot beat the
//    `search_hypotheses`-th best distinct leaf found so far, `min_score_share` of the wall points
//    or `min_best_share` of the best leaf. A node's points are summed in chunks, and the sum
//    stops once the points left (each at most its best value: a wall on a wall, a free cell on
//    a free cell) cannot lift any of its children above that bar: they would be cut anyway.
//    Points that land on rows of the pooled grid holding no values (0 above and below `to`) are
//    left out of the sum: each rotation's points are in row order, so those on the rows that
//    count are one range of them.
// 5. The best leaves, no two alike (within `distinct_cells` cells at `from`'s centroid and
//    `distinct_deg` degrees): the better of two alike ones is kept.
// 6. Each leaf refined at full resolution (one grid cell a map cell; σ, reach and margin scaled
//    alike): turns within one rotation step and shifts within a grid cell, then finer (the points
//    turned once per turn, for all its shifts).
// 7. With `both_ways`, steps 1-6 again with `to` moved onto `from` (inverted). All leaves are
//    ranked by the score both ways at full resolution, that of `from` onto `to` plus that of
//    `to` onto `from` (a wall of either map on the other's open floor costs alike), and the
//    `hypotheses` best, no two alike, are returned best first.
// The caller verifies them (SeedMerger::judgeHypotheses, exhaustive_merger.hpp).

#include <memory>
#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {

struct ExhaustiveSearchSettings {
  int cell_size = 2;                 ///< map cells per grid cell of the search
  int max_grid_cells = 320;          ///< longest side of the search grid: larger maps get larger
                                     ///< cells (0: always cell_size)
  double rotation_step_cells = 3.0;  ///< largest move of a point between two rotations, grid cells
  double wall_sigma = 1.0;           ///< σ of the wall likelihood, grid cells
  double wall_reach = 2.0;           ///< cells within this of a wall score the likelihood
  double free_penalty = 6.0;         ///< cost of a wall of `from` on `to`'s open floor
  int max_points = 400;              ///< walls of `from` scored (an even sample of them)
  int max_free_points = 300;         ///< free cells of `from` scored (an even sample of them)
  double free_weight = 0.2;          ///< score of a free cell of `from` on `to`'s free cells
  double conflict_penalty = 6.0;     ///< cost of a free cell of `from` on `to`'s walls
  int free_margin = 1;               ///< free cells of `from` this near its walls are not scored
  int depth = 5;                     ///< the coarsest node covers 2^depth translations a side
  bool stop_early = true;            ///< stop a node's sums once it cannot beat the bar, and
                                     ///< leave out the points on rows of no values (false: every
                                     ///< point summed, the same result; tests and bench)
  int search_hypotheses = 16;        ///< best distinct leaves kept by each way's search
  bool both_ways = true;             ///< search `to` onto `from` too
  int hypotheses = 16;               ///< best distinct transforms returned (by the score both ways)
  double min_score_share = 0.02;     ///< least score of a hypothesis, share of the wall points
  double min_best_share = 0.4;       ///< least score of a hypothesis, share of the best's
  double distinct_cells = 8.0;       ///< hypotheses closer (map cells) ...
  double distinct_deg = 3.0;         ///< ... and turned less than this (degrees) are alike
  int rotation_peaks = 2;            ///< rotations searched: near this many peaks of the walls'
                                     ///< Radon correlation (and their quarter turns); 0: all
  double rotation_window_deg = 6.0;  ///< ... within this of each (degrees)
};

/// A transform and its score (sum of the value grid over the points; at most the point count).
struct ExhaustiveHypothesis {
  GridTransform T_to_from;
  double score = 0.0;
};

/// The score of step 7 of one pair of maps (both ways, full resolution): its value grids and
/// point sets are built once, for every transform scored.
class ExhaustiveScore {
 public:
  ExhaustiveScore(const GridMap& from, const GridMap& to, const ExhaustiveSearchSettings& settings,
                  const SimilaritySettings& classes);
  ~ExhaustiveScore();
  ExhaustiveScore(const ExhaustiveScore&) = delete;
  ExhaustiveScore& operator=(const ExhaustiveScore&) = delete;

  /// The score at one transform.
  double at(const GridTransform& T_to_from) const;
  /// The transform of the best score near T_to_from: turns within ±turn_rad in `turn_steps`
  /// steps a side and shifts within ±shift_cells, then a quarter of the turn and ±1 cell around
  /// the best.
  ExhaustiveHypothesis bestNear(const GridTransform& T_to_from, double turn_rad, int turn_steps,
                                int shift_cells) const;

 private:
  struct Parts;
  std::unique_ptr<const Parts> parts_;
  friend std::vector<ExhaustiveHypothesis> exhaustiveSearch(const GridMap&, const GridMap&,
                                                            const ExhaustiveScore&,
                                                            const ExhaustiveSearchSettings&,
                                                            const SimilaritySettings&);
};

/// The grid cell of steps 1-5 for this pair: `cell_size`, or larger when the longest side of
/// either map would exceed `max_grid_cells` grid cells.
int searchCellSize(const GridMap& from, const GridMap& to,
                   const ExhaustiveSearchSettings& settings);

/// Steps 1-7: the best distinct transforms of `from` onto `to`, best first (empty when either
/// map has no occupied cell); `score` is the pair's score of step 7.
std::vector<ExhaustiveHypothesis> exhaustiveSearch(const GridMap& from, const GridMap& to,
                                                   const ExhaustiveScore& score,
                                                   const ExhaustiveSearchSettings& settings,
                                                   const SimilaritySettings& classes);
/// The same with a score of its own.
std::vector<ExhaustiveHypothesis> exhaustiveSearch(const GridMap& from, const GridMap& to,
                                                   const ExhaustiveSearchSettings& settings,
                                                   const SimilaritySettings& classes);

/// Step 3's turns of `from` onto `to` the walls suggest (radians, each peak and its quarter turns);
/// empty when `rotation_peaks` is 0 or either map has no occupied cell (every rotation searched).
std::vector<double> suggestedTurns(const GridMap& from, const GridMap& to,
                                   const ExhaustiveSearchSettings& settings,
                                   const SimilaritySettings& classes);

/// The score of step 7 (both ways, full resolution) at one transform.
double exhaustiveScore(const GridMap& from, const GridMap& to, const GridTransform& T_to_from,
                       const ExhaustiveSearchSettings& settings, const SimilaritySettings& classes);

}  // namespace mrslam::fusion
