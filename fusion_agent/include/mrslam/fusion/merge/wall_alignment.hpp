#pragma once
// The last step of every accepted map-based merge: the walls of the two maps aligned both ways.
//
// The acceptance (block 9) decides whether a transform is right; the transform it judged comes
// from searches on whole cells and quarter degrees (block 8, the exhaustive search's grid), and
// at small overlaps it can end a cell or two and about a degree from where the walls meet. The
// alignment moves it, within a small window, to the best two-way wall agreement:
//
//   W(T) = Σ_{p ∈ walls(from)} f_to(T p) + Σ_{q ∈ walls(to)} f_from(T⁻¹ q),
//   f(x) = exp(-d(x)² / 2σ²) on known cells, 0 on unknown ones,
//
// where d(x) is the distance from cell x to the nearest wall of that map (a likelihood field,
// read with bilinear interpolation so that the transform is found between cells). A wall landing
// in the other map's unknown space adds nothing. Counting both directions keeps the walls of `to`
// inside the overlap from being ignored, which a one-way fit can do by sliding `from`'s walls
// along a corridor.
//
// The window: the accepted transform turned by up to ±max_turn_deg about the centre of `from`'s
// walls that land on `to`'s known cells, and shifted by up to ±max_shift_cells. Only walls that
// some transform of the window can carry onto the other map's known cells are scored (an even
// sample of at most coarse_walls or max_walls of them per map). The search: every turn of the
// window in coarse_turn_step_deg steps with every shift in coarse_shift_cells steps, on a wider
// field (coarse_sigma_cells); then a pattern search of the narrow field from each of the `starts`
// best grid points (each more than a grid step from the better ones), its steps halved fine_steps
// times, and the highest climb kept. The result is the accepted transform unless W of the narrow
// field is higher there. Several starts: W can have two basins a degree or two apart in the
// window, the wide field favouring one while the narrow one is higher in the other (four near
// misses of the 40 case sets, each 1.3-1.7° off, ended at the truth). After acceptance
// (alignAccepted) the aligned transform is kept only where V does not drop: on 1013 accepted
// known-answer merges, V dropped at 6 of the 9 the alignment moved away from the truth and at 15 of
// the 373 it moved towards it.
//
// The turn check: a transform whose walls meet as well turned by 3° (the shift found again) is a
// guess of the rotation. It runs where the alignment ends and where the climb from the grid's best
// point ends: a guessed rotation at either peak refuses. Of the 517 merges the chain accepted on
// three known-answer case sets, the one wrong (2.6 cells, 1.4° off: an overlap that is a thin strip
// of wall stubs along a window edge) kept 0.962 of W turned by 3°; of the right ones, three kept
// 0.966-1.02 and the next 0.93.

#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {

struct WallAlignmentSettings {
  bool enabled = true;                ///< align every accepted transform (false: returned as found)
  double sigma_cells = 0.5;           ///< σ of the likelihood field f, cells
  double max_turn_deg = 1.5;          ///< the window: turns within ±this of the accepted transform
  double max_shift_cells = 2.5;       ///< ... and shifts within ±this
  double coarse_sigma_cells = 1.0;    ///< σ of the coarse grid's field
  double coarse_turn_step_deg = 0.5;  ///< grid step of the turns
  double coarse_shift_cells = 1.0;    ///< grid step of the shifts
  int coarse_walls = 300;             ///< walls of each map on the coarse grid (an even sample)
  int fine_steps = 4;                 ///< halvings of the pattern search's steps after the grid
  int starts = 3;        ///< pattern searches from the best grid points, each a grid step apart
  int max_walls = 1000;  ///< walls of each map in the pattern search (an even sample above this)
  int min_walls = 20;    ///< fewer walls on the other's known cells (both ways): left as found
  /// The turn check after the alignment: the aligned transform turned by ±turn_check_deg about the
  /// pivot, each with its best shift within ±turn_check_shift_cells, must keep less than
  /// max_turn_share of W, or the walls of the overlap do not fix the rotation (1 or more: off).
  double turn_check_deg = 3.0;
  double turn_check_shift_cells = 3.0;
  double max_turn_share = 0.95;
};

/// The walls of one map and its likelihood field at two widths, prepared once per map.
class WallField {
 public:
  enum class Level { kCoarse, kFine };
  WallField(const GridMap& map, const SimilaritySettings& classes,
            const WallAlignmentSettings& settings);
  /// f of `level` at `cell`, bilinear between cells; 0 off the map.
  double fieldAt(const Eigen::Vector2d& cell, Level level) const;
  /// The sum of fieldAt(cell + shift, level) over `cells`, summed in their order.
  double sumAt(const std::vector<Eigen::Vector2d>& cells, const Eigen::Vector2d& shift,
               Level level) const;
  /// Whether the cell nearest to `cell` is known.
  bool isKnown(const Eigen::Vector2d& cell) const;
  /// Whether a known cell lies within `cells` of the cell nearest to `cell`.
  bool knownWithin(const Eigen::Vector2d& cell, double cells) const;
  /// Every wall (occupied cell) of the map.
  const std::vector<Eigen::Vector2d>& walls() const { return walls_; }

 private:
  /// The field of `level`.
  const cv::Mat& fieldOf(Level level) const {
    return level == Level::kCoarse ? coarse_field_ : field_;
  }
  std::vector<Eigen::Vector2d> walls_;
  cv::Mat field_;              // CV_32F, f of every cell (sigma_cells), 0 on unknown cells
  cv::Mat coarse_field_;       // CV_32F, the same with coarse_sigma_cells
  cv::Mat known_;              // CV_8U, non-zero where the cell is known
  cv::Mat distance_to_known_;  // CV_32F, cells to the nearest known cell
};

/// W(T_to_from) of the narrow field over every wall, and how many walls land on the other map's
/// known cells (both ways).
struct WallAgreement {
  double score = 0.0;
  int counted = 0;
};
WallAgreement wallAgreement(const WallField& from, const WallField& to,
                            const GridTransform& T_to_from);

/// Where W peaks within the window around T_to_from: the highest of the climbs from the coarse
/// grid's `starts` best distinct points, and the climb from its best point alone (T_to_from where
/// a climb ends no higher than it, and both when fewer than min_walls walls land on the other
/// map's known cells there).
struct WallPeaks {
  GridTransform highest;
  GridTransform first;
};
WallPeaks wallPeaks(const WallField& from, const WallField& to, const GridTransform& T_to_from,
                    const WallAlignmentSettings& settings);

/// The transform of the largest W within the window around T_to_from: wallPeaks().highest.
GridTransform alignWalls(const WallField& from, const WallField& to, const GridTransform& T_to_from,
                         const WallAlignmentSettings& settings);

/// The larger share of W(T_to_from) that T_to_from keeps turned by ±turn_check_deg about the
/// pivot, each turn with its best shift within ±turn_check_shift_cells; 0 when fewer than
/// min_walls walls land on the other map's known cells.
double wallTurnShare(const WallField& from, const WallField& to, const GridTransform& T_to_from,
                     const WallAlignmentSettings& settings);

/// With settings.enabled and an accepted `result`: its transform aligned (wallPeaks().highest)
/// when V (block 9, over all known cells) is at least as high there as at the transform found,
/// and V and the merged entropy taken again at the transform kept; then refused when
/// wallTurnShare() reaches max_turn_share at it or at the first climb's peak (kept alike where V
/// holds): the walls do not fix the rotation, and the reason says so. A refused result is left as
/// it is.
void alignAccepted(const GridMap& from, const GridMap& to, const WallAlignmentSettings& settings,
                   const SimilaritySettings& classes, MergeResult& result);
/// What alignAccepted() reads of the two maps, prepared by a merger that has it already.
struct AlignmentMaps {
  const WallField& field_from;                ///< with the settings and classes of the merge
  const WallField& field_to;                  ///< the same
  const ComparisonTables& tables;             ///< the classes' comparison tables
  const std::vector<CellSample>& known_from;  ///< knownCells(from, tables)
  const CodeImage& codes_to;                  ///< codeImage(to, any pad, tables)
  double entropy_from = 0.0;                  ///< mapEntropy(from, tables)
  double entropy_to = 0.0;                    ///< mapEntropy(to, tables)
  /// compareAt(known_from, codes_to, result.T_to_from, tables) when the merger has it already.
  const Agreement* at_found = nullptr;
};
/// The same from maps prepared already.
void alignAccepted(const AlignmentMaps& maps, const WallAlignmentSettings& settings,
                   MergeResult& result);

}  // namespace mrslam::fusion
