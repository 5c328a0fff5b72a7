#pragma once
// The chain's prefilter of many placements (chain_merger.cpp): every other row and column of
// `from`'s known cells (a quarter of them) against `to`'s classes, to estimate the disagreement
// rate (1 - V) of each placement cheaply. The samples are kept by 16-cell tiles of `from`: a
// placement skips every tile that lands where `to` has no known cell within a tile, as none of its
// samples could agree or disagree there, so the counts are those of every sample.

#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {

class SampledComparison {
 public:
  SampledComparison(const GridMap& from, const GridMap& to, const SimilaritySettings& classes);

  /// 1 - V of the samples placed by T_to_from; 1 when none lands on a known cell of `to`.
  double disagreementRate(const GridTransform& T_to_from) const;
  /// Whether that rate exceeds `rate` (stopping early once it must).
  bool disagreesMoreThan(const GridTransform& T_to_from, double rate) const;

  /// Every sample, tile by tile (for tests).
  const std::vector<CellSample>& samples() const { return samples_; }
  /// The samples of the tiles T_to_from can land within reach of `to`'s known cells, the others
  /// left out (for tests: the comparisons read only these).
  const std::vector<CellSample>& landingSamples(const GridTransform& T_to_from) const;

 private:
  struct Tile {
    Eigen::Vector2d centre;  // of the tile's cells, in `from`
    std::size_t begin = 0;   // its samples in samples_
    std::size_t end = 0;
  };
  /// Whether a coarse tile of `to` holding a known cell lies within one tile of the one that
  /// holds `cell` (a point of `to`).
  bool nearKnownTile(const Eigen::Vector2d& cell) const;

  ComparisonTables tables_;
  CodeImage to_;
  std::vector<CellSample> samples_;  // tile by tile
  std::vector<Tile> tiles_;
  cv::Mat near_known_tiles_;  // CV_8U, one cell a tile of `to` and a tile around: non-zero where
                              // a tile within one holds a known cell
  mutable std::vector<CellSample> landing_;  // the last landingSamples()
};

}  // namespace mrslam::fusion
