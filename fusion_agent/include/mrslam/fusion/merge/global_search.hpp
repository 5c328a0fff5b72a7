#pragma once
// Global search (ours, after the exhaustive correlative search of scan matching): hypotheses of
// T_to_from from every rotation of a full turn, with no segment, line or Radon peak needed. It
// finds transforms that the seed pipeline's hypotheses miss (turned 90° or 180° from the truth
// in rooms of similar sides, few verified segments in clutter).
//
// 1. Both maps are coarsened by `coarse_cells` (a coarse cell is occupied when it holds an
//    occupied cell, free when it holds known free cells only). `to` becomes the target
//    W_to = O_to - w F_to (w = `free_weight`).
// 2. For every rotation θ_k = k · `rotation_step` over the full turn (or only those within one
//    step of `only_rotations`, for a finer second sweep around the first's answers), `from`'s
//    coarse occupied and free images are turned (bilinear) onto a canvas, O_from(θ) and F_from(θ).
//    Sweeping every rotation, only those of the first quarter turn are turned: the others are
//    correlated as `to` turned back by whole quarter turns (`quarter_turns`, quarter_turns.hpp).
// 3. The score of every translation at once, by DFT:
//      s(t) = Σ_u O_from(θ)(u) W_to(u + t) - w Σ_u F_from(θ)(u) O_to(u + t),
//    walls on walls count, walls of either map on the other's known free space cost w.
// 4. The `peaks_per_rotation` strongest peaks of each rotation (no two within `peak_separation`
//    coarse cells) join one list; the `kept_hypotheses` best of it, no two alike (within
//    `coarse_cells` cells and 1.5 rotation steps), are returned, best first.
// 5. With `free_agreement_hypotheses` > 0, a second score of the same rotations adds the free
//    cells of `from` that meet free cells of `to`, times `free_agreement_weight`:
//      s_f(t) = s(t) + f Σ_u F_from(θ)(u) F_to(u + t).
//    Walls alone favour laying cluttered parts of the maps onto each other; an overlap that is
//    mostly shared open floor with few walls (a hall, a wide corridor) scores low on s and is
//    found by s_f. Its `free_agreement_hypotheses` best peaks (chosen as in step 4) follow those
//    of s, marked `by_free_agreement`.
// The answer is coarse: within about one coarse cell and half a rotation step of a true peak.
// The caller refines it (seed_global.cpp) and verifies it like any other hypothesis.

#include <memory>
#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {

struct GlobalSearchSettings {
  int coarse_cells = 4;                           ///< cells per coarse cell of the sweep
  double rotation_step_rad = 3.0 * M_PI / 180.0;  ///< step between the rotations of the sweep
  int peaks_per_rotation = 3;                     ///< correlation peaks kept per rotation
  int kept_hypotheses = 12;                       ///< best peaks over all rotations returned
  double free_weight = 0.5;                       ///< w: cost of a wall on the other's free space
  int peak_separation = 2;                        ///< coarse cells between two peaks of a rotation
  double free_agreement_weight = 0.1;  ///< step 5: gain of a free cell on the other's free cell
  int free_agreement_hypotheses = 6;   ///< step 5: best peaks of that score returned (0: off)
  std::vector<double>
      only_rotations_rad;  ///< when not empty: the sweep's rotations near these only
  /// With only_rotations_rad: turn `from` by exactly those rotations instead of the sweep's
  /// rotations within one step of them.
  bool exact_rotations = false;
  /// When every rotation is swept and their count is a multiple of 4: the images of `from` are
  /// turned and transformed for the first quarter turn only, each other rotation correlated with
  /// `to` turned back by whole quarter turns instead (a square DFT). The same scores up to
  /// rounding; false: every rotation turned and transformed on its own.
  bool quarter_turns = true;
};

/// A coarse transform and its correlation score s(t).
struct GlobalHypothesis {
  GridTransform T_to_from;
  double score = 0.0;
  bool by_free_agreement = false;  ///< a peak of s_f (step 5), not of s
};

/// Steps 1-2 of one pair (both maps coarsened, `to`'s spectra) built once for several sweeps:
/// a merge chain sweeps one pair at the accepted rotation and at its quarter turns.
class GlobalSweep {
 public:
  /// The maps prepared for sweeps with the coarse cells, free weight, free agreement (on or
  /// off) and quarter turns (used or not) of `settings`.
  GlobalSweep(const GridMap& from, const GridMap& to, const GlobalSearchSettings& settings,
              const SimilaritySettings& classes);
  ~GlobalSweep();
  GlobalSweep(GlobalSweep&&) noexcept;
  GlobalSweep& operator=(GlobalSweep&&) noexcept;

  /// globalSearch() with `settings`; throws std::invalid_argument when they differ from the
  /// constructor's in what the preparation depends on (above).
  std::vector<GlobalHypothesis> search(const GlobalSearchSettings& settings) const;

 private:
  /// What the preparation depends on.
  struct PreparedFor {
    int coarse_cells = 1;
    double free_weight = 0.0;
    bool free_agreement = false;
    bool quarter_turns = false;
  };
  static PreparedFor preparedFor(const GlobalSearchSettings& settings);

  struct Prepared;
  PreparedFor prepared_for_;
  std::unique_ptr<const Prepared> prepared_;  ///< null when either map has no occupied cell
};

/// Steps 1-5: the best coarse transforms of `from` onto `to` by s, best first, then those by s_f,
/// best first (empty when either map is empty or has no occupied cell).
std::vector<GlobalHypothesis> globalSearch(const GridMap& from, const GridMap& to,
                                           const GlobalSearchSettings& settings,
                                           const SimilaritySettings& classes);

}  // namespace mrslam::fusion
