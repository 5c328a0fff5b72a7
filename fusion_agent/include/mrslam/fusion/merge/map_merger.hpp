#pragma once
// The interface of every map merger: two occupancy grids in, the rigid transform between them
// (or the reason there is none) out. Mergers know nothing of DDS, files or robots.
//
// Cell coordinates: (column, row) of a GridMap, row 0 at the bottom (smallest y); integer values
// are cell centres. A GridTransform maps cell coordinates of map `from` to cell coordinates of
// map `to`: p_to = R(theta) * p_from + t.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/common/se2.hpp"
#include "mrslam/fusion/merge/block_times.hpp"

namespace mrslam::fusion {

/// A rigid transform between the cell coordinates of two grids.
struct GridTransform {
  double theta_rad = 0.0;
  Eigen::Vector2d t_cells = Eigen::Vector2d::Zero();

  Eigen::Vector2d apply(const Eigen::Vector2d& cell_from) const {
    const double c = std::cos(theta_rad);
    const double s = std::sin(theta_rad);
    return Eigen::Vector2d(c * cell_from.x() - s * cell_from.y(),
                           s * cell_from.x() + c * cell_from.y()) +
           t_cells;
  }
  GridTransform inverse() const {
    GridTransform inverse;
    inverse.theta_rad = -theta_rad;
    const double c = std::cos(theta_rad);
    const double s = std::sin(theta_rad);
    inverse.t_cells =
        -Eigen::Vector2d(c * t_cells.x() + s * t_cells.y(), -s * t_cells.x() + c * t_cells.y());
    return inverse;
  }
};

/// Whether two transforms are equal bit for bit (the same turn and shift, not merely close).
inline bool sameTransform(const GridTransform& a, const GridTransform& b) {
  return a.theta_rad == b.theta_rad && a.t_cells == b.t_cells;
}

/// GridTransform::apply() with the rotation's cosine and sine taken once, for loops over many cells
/// (the same result, bit for bit).
class CellMapping {
 public:
  explicit CellMapping(const GridTransform& T)
      : c_(std::cos(T.theta_rad)), s_(std::sin(T.theta_rad)), t_cells_(T.t_cells) {}
  Eigen::Vector2d operator()(const Eigen::Vector2d& cell_from) const {
    return Eigen::Vector2d(c_ * cell_from.x() - s_ * cell_from.y(),
                           s_ * cell_from.x() + c_ * cell_from.y()) +
           t_cells_;
  }

 private:
  double c_;
  double s_;
  Eigen::Vector2d t_cells_;
};

/// The metric transform T_to_from between the two maps' frames (both grids at one resolution):
/// the pose of map `from`'s frame in map `to`'s frame.
SE2 gridTransformToMetric(const GridTransform& T_to_from_cells, const GridGeometry& from,
                          const GridGeometry& to);
/// The inverse: cell transform from a metric T_to_from.
GridTransform metricToGridTransform(const SE2& T_to_from, const GridGeometry& from,
                                    const GridGeometry& to);

/// Cells per block of a search over two maps: `block_cells` (at least 1), or larger so that the
/// longest side of either map makes at most `max_blocks` blocks (0: no limit). The searches'
/// work grows with a power of the side; their coarse answers are refined at full resolution.
int blockCellsForSize(const GridMap& from, const GridMap& to, int block_cells, int max_blocks);

/// Which of block 9's tests refused a merge's transform (SeedMerger's acceptance, which the
/// exhaustive and virtual-robot mergers share); kUnspecified when accepted or refused elsewhere.
enum class MergeRefusal {
  kUnspecified,
  kOverlap,        ///< too few known cells in the overlap
  kVerification,   ///< V below its bar
  kStructure,      ///< overlapping walls do not meet walls
  kEntropy,        ///< the entropy minimum lies away from the best similarity
  kTranslation,    ///< the overlap does not fix the translation (a slide scores almost as well)
  kRival,          ///< another transform elsewhere explains the overlap almost as well
  kRotation,       ///< the overlap's walls meet as well turned (the wall alignment's turn check)
  kDissimilarity,  ///< Carpin's ψ over the overlap above its bar (the virtual robot's check)
};

/// What a merge found, or why it refused.
struct MergeResult {
  bool accepted = false;
  GridTransform T_to_from;    ///< valid when accepted
  double verification = 0.0;  ///< V = agr / (agr + dis) of the overlap at T_to_from
  double entropy = 0.0;       ///< map entropy of the merged pair at T_to_from
  int trials = 0;             ///< segment pairs (or hypotheses) tried
  std::string method;         ///< the merger (or chain step) that produced the result
  std::string reason;         ///< why it refused; empty when accepted
  /// When refused by block 9's acceptance: the test that refused T_to_from.
  MergeRefusal refusal = MergeRefusal::kUnspecified;
  /// The wall alignment's turn check at T_to_from: the share of the walls' agreement kept turned
  /// (wallTurnShare); 0 where the check did not run.
  double wall_turn_share = 0.0;
  /// The hypotheses the merger's own search found before judging them (the exhaustive search's,
  /// best first; empty for the others): a chain weighs them as alternatives to what it accepts.
  std::vector<GridTransform> hypotheses;
};

class SearchInputsCache;

class MapMerger {
 public:
  virtual ~MapMerger() = default;
  /// Finds T_to_from between two maps of the same resolution, with no prior on it.
  virtual MergeResult merge(const GridMap& from, const GridMap& to) = 0;
  virtual std::string name() const = 0;
  /// A merger judged by the seed pipeline's acceptance keeps that judge's inputs of a pair of
  /// maps in `cache` (seed_merger.hpp): a chain hands one to its steps and its own judge, all
  /// built from the same `seed:` settings. The others ignore it.
  virtual void shareSearchInputs(const std::shared_ptr<SearchInputsCache>& /*cache*/) {}
  /// Where the last merge() spent its time, block by block (block_times.hpp); empty for a
  /// merger that does not time its blocks.
  virtual BlockTimes lastBlockTimes() const { return {}; }
};

}  // namespace mrslam::fusion
