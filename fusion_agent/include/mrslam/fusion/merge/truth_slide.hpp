#pragma once
// Whether two maps fix the translation of a placement at all, whatever the merger: the truth of a
// known-answer case (`mrslam_merge_cases --truth-slide`) or the transform a merge would return
// (the chain's last check, ChainSettings::min_slide_margin_cells).
//
// An overlap of one corridor wall and open floor, cut by the crops' edges, fits as well slid a
// few cells along the wall: no merger can tell the truth from the slid placement, and one that
// accepts either guesses. This measures that, from the maps and the placement alone: every
// placement of `from` at its rotation shifted by whole cells within ±reach is compared with `to`
// over all known cells of `from` (agreement and disagreement, as the seed acceptance counts them).
// Below, "the truth" is the placement given.
//
//   at the truth: the placement of least disagreement within one cell of the truth (the crops are
//     resampled at different turns, so the exact truth can disagree a little more than a cell
//     beside it);
//   slid: the placement of least disagreement at least min_slide cells from the truth (the larger
//     of |dx|, |dy|) that still overlaps min_overlap_share of the truth's known cells in common;
//   margin = dis(slid) - dis(at the truth): the disagreeing cells the best slide adds.
//
// A margin near zero (or below it) means the slid placement fits as cleanly over as much of the
// maps: the truth is not fixed by them. Without a slid placement that keeps the overlap, every
// slide loses it and the margin counts as fixed.

#include <Eigen/Core>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {

struct TruthSlideSettings {
  int reach = 8;                   ///< shifts within ±reach cells of the truth, each axis
  int min_slide = 3;               ///< a slid placement lies at least this far (cells, max norm)
  double min_overlap_share = 0.9;  ///< ... and overlaps at least this share of the truth's cells
  SimilaritySettings similarity;   ///< the cell classes, as the seed acceptance reads them
};

struct TruthSlide {
  Agreement at_truth;  ///< the least disagreement within one cell of the truth
  Eigen::Vector2i truth_shift = Eigen::Vector2i::Zero();  ///< ... at this shift of the truth
  bool slid_found = false;                                ///< a slid placement keeps the overlap
  Agreement slid;                                   ///< the slid placement of least disagreement
  Eigen::Vector2i slide = Eigen::Vector2i::Zero();  ///< ... at this shift of the truth, cells
  /// dis(slid) - dis(at the truth); meaningful only with slid_found.
  long long margin() const { return slid.disagreement - at_truth.disagreement; }
};

/// The slide of T_to_from (the truth of `from` in `to`'s cells) over the two maps. Throws
/// std::invalid_argument on a reach below 1 or a least slide outside 2..reach.
TruthSlide truthSlide(const GridMap& from, const GridMap& to, const GridTransform& T_to_from,
                      const TruthSlideSettings& settings = {});

}  // namespace mrslam::fusion
