#pragma once
// Blocks 8 and 9 of the seed merge: translation tuning by the similarity index, verification.
//
// 1. Cells are compared by class: occupied (occupancy ≥ occupied_threshold), free
//    (≤ free_threshold), unknown otherwise. A cell of `from` mapped by T_to_from (rounded to the
//    nearest cell of `to`) agrees when both cells are known and of one class and disagrees when
//    both are known and of different classes; unknown cells count for neither.
// 2. Similarity index = agr - dis (block 8): the translation is tuned by evaluating it for every
//    integer shift within ±δ cells of the approximate translation and keeping the best.
// 3. Verification index V = agr / (agr + dis) (block 9).
// 4. Map entropy (block 9): a cell of occupancy probability p (clamped to [1-c, c]) has entropy
//    h(p) = -p log2 p - (1-p) log2 (1-p); a map's entropy is the sum over its known cells. The
//    merged map fuses the cells known in both by adding log-odds and keeps the others, so its
//    entropy is H(from) + H(to) + Σ_overlap [h(fused) - h(p_from) - h(p_to)]: agreeing cells
//    lower it, disagreeing cells raise it. The entropy minimum over the same ±δ shifts must
//    fall where the similarity index is best, or the merge is refused (seed_merger.hpp).
// 5. Structure agreement (our addition, see StructureAgreement).
// Comparisons run on cell samples of `from` against a padded code image of `to`, with the
// per-pair answers in lookup tables, so a shift costs two table reads per sample.

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/core.hpp>
#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"

namespace mrslam::fusion {

/// Settings of blocks 8 and 9 (cell classes and entropy).
struct SimilaritySettings {
  int occupied_threshold = 65;   ///< occupancy ≥ this (percent): occupied class
  int free_threshold = 35;       ///< occupancy ≤ this: free class; between: counts as unknown
  double cell_certainty = 0.95;  ///< c: occupancy probabilities are clamped to [1-c, c]

  /// The class of an occupancy value (-1 unknown, else 0..100).
  bool isOccupied(int value) const { return value >= occupied_threshold; }
  bool isFree(int value) const { return value >= 0 && value <= free_threshold; }
  bool isKnown(int value) const { return isFree(value) || isOccupied(value); }
};

/// Code of a cell: its occupancy 0..100, or kUnknownCode.
constexpr std::uint8_t kUnknownCode = 101;
constexpr int kCodeCount = 102;

/// Per pair of cell codes: similarity (+1, -1, 0) and entropy change of the merge.
class ComparisonTables {
 public:
  explicit ComparisonTables(const SimilaritySettings& settings);
  int similarity(std::uint8_t from, std::uint8_t to) const { return similarity_[index(from, to)]; }
  double entropyChange(std::uint8_t from, std::uint8_t to) const {
    return entropy_change_[index(from, to)];
  }
  double cellEntropy(std::uint8_t code) const { return cell_entropy_[code]; }
  bool isKnown(std::uint8_t code) const { return class_[code] != 0; }
  bool isOccupied(std::uint8_t code) const { return class_[code] == 2; }
  /// 0 unknown, 1 free, 2 occupied.
  int classOf(std::uint8_t code) const { return class_[code]; }
  /// agr (low 32 bits) and dis (high 32 bits) of a pair of classes, at 3 · from + to.
  std::uint64_t packedAgreement(int pair) const { return packed_[static_cast<std::size_t>(pair)]; }

 private:
  static std::size_t index(std::uint8_t from, std::uint8_t to) {
    return static_cast<std::size_t>(from) * kCodeCount + to;
  }
  std::array<std::uint8_t, kCodeCount> class_{};  // 0 unknown, 1 free, 2 occupied
  std::array<std::uint64_t, 9> packed_{};
  std::array<double, kCodeCount> cell_entropy_{};
  std::vector<std::int8_t> similarity_;
  std::vector<float> entropy_change_;
};

/// A cell of map `from` to compare.
struct CellSample {
  int x = 0;
  int y = 0;
  std::uint8_t code = kUnknownCode;
};

/// static_cast<int>(std::floor(v)) for |v| < 2^31, without a call into libm: the cell a
/// coordinate falls in, as every placement of samples rounds.
inline int floorToInt(double v) {
  const int truncated = static_cast<int>(v);
  return v < truncated ? truncated - 1 : truncated;
}

/// std::lround(v) (halves away from zero) for |v| < 2^30, without a call into libm: v minus its
/// truncation is exact, so the comparison with one half is too. Anything else (NaN included)
/// gives INT_MIN, a cell off every grid.
inline int roundToInt(double v) {
  if (!(std::abs(v) < 1073741824.0)) {
    return std::numeric_limits<int>::min();
  }
  const int truncated = static_cast<int>(v);
  const double fraction = v - static_cast<double>(truncated);
  // Summed as 0 or 1 rather than chosen: no branch on the fraction, which falls either way.
  return truncated + static_cast<int>(fraction >= 0.5) - static_cast<int>(fraction <= -0.5);
}

/// The cell (column, row) where a cell of `from` lands in `to` under T_to_from: floor(T p + 0.5)
/// in each coordinate, as every placement of samples rounds. Cells taken row by row reuse the
/// products of their row.
class CellRounding {
 public:
  explicit CellRounding(const GridTransform& T_to_from)
      : c_(std::cos(T_to_from.theta_rad)),
        s_(std::sin(T_to_from.theta_rad)),
        tx_(T_to_from.t_cells.x() + 0.5),
        ty_(T_to_from.t_cells.y() + 0.5) {}
  cv::Point landing(int x, int y) {
    if (y != row_) {
      row_ = y;
      s_row_ = s_ * row_;
      c_row_ = c_ * row_;
    }
    return {floorToInt(c_ * x - s_row_ + tx_), floorToInt(s_ * x + c_row_ + ty_)};
  }

 private:
  double c_;
  double s_;
  double tx_;
  double ty_;
  int row_ = std::numeric_limits<int>::min();
  double s_row_ = 0.0;
  double c_row_ = 0.0;
};

/// Every known cell of a map (known: of class free or occupied).
std::vector<CellSample> knownCells(const GridMap& map, const ComparisonTables& tables);

/// The mean (column, row) of the cells of a map that hold a value (not GridMap::kUnknown); zero
/// when none does. Where errors of a transform are measured, about the map's known part.
Eigen::Vector2d knownCentroid(const GridMap& map);

/// An even, deterministic sample of a map's known cells: up to `occupied_count` occupied cells
/// and up to `free_count` free cells, each picked at equal steps along the row-major order.
std::vector<CellSample> sampleKnownCells(const std::vector<CellSample>& known,
                                         const ComparisonTables& tables, int occupied_count,
                                         int free_count);

/// sampleKnownCells() several times over one list of known cells: the cells of each class are
/// listed once, and each sample then costs only its picks. `known` must outlive the sampler.
class KnownCellSampler {
 public:
  KnownCellSampler(const std::vector<CellSample>& known, const ComparisonTables& tables);
  /// The same cells, in the same order, as sampleKnownCells(known, tables, occupied_count,
  /// free_count).
  std::vector<CellSample> sample(int occupied_count, int free_count) const;

 private:
  /// Positions in `known` of the class's picks (`cells`: the class's positions, in order).
  static std::vector<std::size_t> picks(const std::vector<std::size_t>& cells, int count);

  const std::vector<CellSample>& known_;
  std::vector<std::size_t> occupied_;  ///< positions of the occupied cells in known_
  std::vector<std::size_t> free_;      ///< positions of the free cells
};

/// Map `to` as cell codes and classes, padded by `pad` unknown cells on every side.
struct CodeImage {
  cv::Mat codes;          ///< CV_8U, (height + 2 pad) × (width + 2 pad)
  cv::Mat classes;        ///< CV_8U, the class of each code
  cv::Mat near_occupied;  ///< CV_8U, non-zero within one cell of an occupied cell
  cv::Mat near_unknown;   ///< CV_8U, non-zero within one cell of an unknown cell (a frontier;
                          ///< the pad is unknown, so the map's edge is one too)
  int pad = 0;
};
CodeImage codeImage(const GridMap& map, int pad, const ComparisonTables& tables);

/// The sums of one comparison.
struct Agreement {
  long long agreement = 0;
  long long disagreement = 0;
  double entropy_change = 0.0;  ///< Σ over cells known in both of h(fused) - h(from) - h(to)
  long long similarity() const { return agreement - disagreement; }
  /// Cells known in both maps.
  long long overlap() const { return agreement + disagreement; }
};

/// Block 9: V = agr / (agr + dis), 0 without overlap.
double verificationIndex(const Agreement& agreement);

/// Compares samples of `from` mapped by T_to_from with map `to`.
Agreement compareAt(const std::vector<CellSample>& samples, const CodeImage& to,
                    const GridTransform& T_to_from, const ComparisonTables& tables,
                    bool with_entropy = true);

/// Whether 1 - V of the samples mapped by T_to_from exceeds `rate` (1 - V is 1 without overlap):
/// the same answer as compareAt(), which it stops early once the samples left cannot bring the
/// rate down to `rate` even if all of them agree.
bool disagreementRateExceeds(const std::vector<CellSample>& samples, const CodeImage& to,
                             const GridTransform& T_to_from, const ComparisonTables& tables,
                             double rate);

/// Structure agreement (our addition to block 9): of the occupied samples of `from` that land
/// on known cells of `to`, those with an occupied cell of `to` within one cell (`near`) and the
/// others (`far`). Free cells dominate agr and dis, so V stays high when a wrong transform
/// lays walls into open space of a large free area; this index looks at the walls alone.
///
/// A robot's free space often ends at a wall it never marked: a wall seen at a grazing angle or
/// at long range leaves free cells up to it and unknown ones behind. The other robot's walls
/// land there on free cells next to unknown ones (`frontier`, counted among `far`), which say
/// nothing against the transform; indexOffFrontier() leaves them out.
struct StructureAgreement {
  long long near = 0;
  long long far = 0;
  long long frontier = 0;  ///< of `far`: on a known cell with an unknown cell within one cell
  double index() const { return share(near, near + far); }
  double indexOffFrontier() const { return share(near, near + far - frontier); }

 private:
  static double share(long long part, long long whole) {
    return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
  }
};
StructureAgreement structureAgreement(const std::vector<CellSample>& samples, const CodeImage& to,
                                      const GridTransform& T_to_from,
                                      const ComparisonTables& tables);

/// The result of block 8.
struct TranslationSearch {
  GridTransform best_similarity;  ///< the shift of the largest agr - dis
  GridTransform least_entropy;    ///< the shift of the least entropy of the merge
  Agreement at_best_similarity;
  Agreement at_least_entropy;
  /// The best agr - dis at least kRunnerUpCells (Chebyshev) from the best shift; equal to the
  /// best when the window has no such shift. A runner-up almost as good as the best means the
  /// overlap does not fix the translation (a corridor seen along its length).
  long long runner_up_similarity = 0;
};

/// How far (cells) a shift must lie from the best to count as the runner-up.
constexpr int kRunnerUpCells = 3;

/// Block 8: every `step`-th integer shift within ±delta of T_to_from.t_cells (|shift| ≤
/// to.pad - 1). Without `with_entropy` the entropy is not summed (least_entropy is then
/// meaningless).
TranslationSearch searchTranslation(const std::vector<CellSample>& samples, const CodeImage& to,
                                    const GridTransform& T_to_from, int delta,
                                    const ComparisonTables& tables, bool with_entropy = true,
                                    int step = 1);

/// Block 9: entropy (bits) of a map's known cells.
double mapEntropy(const GridMap& map, const ComparisonTables& tables);

/// Block 9: entropy (bits) of the merged map, given the full comparison at the transform.
double mergedEntropy(double entropy_from, double entropy_to, const Agreement& full_comparison);

}  // namespace mrslam::fusion
