#include "sampled_comparison.hpp"

#include <opencv2/imgproc.hpp>

namespace mrslam::fusion {

namespace {

// A tile's cells lie within 7.5 √2 ≈ 10.6 cells of its centre and land, rounded, within 11.4
// cells of where the centre lands: inside the tiles around the centre's when a tile is 16 cells.
constexpr int kTileCells = 16;

}  // namespace

SampledComparison::SampledComparison(const GridMap& from, const GridMap& to,
                                     const SimilaritySettings& classes)
    : tables_(classes), to_(codeImage(to, 0, tables_)) {
  const int columns = (from.geometry.width + kTileCells - 1) / kTileCells;
  const int rows = (from.geometry.height + kTileCells - 1) / kTileCells;
  std::vector<std::vector<CellSample>> by_tile(static_cast<std::size_t>(columns * rows));
  for (const CellSample& known : knownCells(from, tables_)) {
    if (known.x % 2 == 0 && known.y % 2 == 0) {
      by_tile[static_cast<std::size_t>((known.y / kTileCells) * columns + known.x / kTileCells)]
          .push_back(known);
    }
  }
  for (std::size_t k = 0; k < by_tile.size(); ++k) {
    if (by_tile[k].empty()) {
      continue;
    }
    const int tx = static_cast<int>(k) % columns;
    const int ty = static_cast<int>(k) / columns;
    const double half = 0.5 * (kTileCells - 1);
    tiles_.push_back({Eigen::Vector2d(tx * kTileCells + half, ty * kTileCells + half),
                      samples_.size(), samples_.size() + by_tile[k].size()});
    samples_.insert(samples_.end(), by_tile[k].begin(), by_tile[k].end());
  }
  // `to`'s tiles with a known cell, a tile of margin around the map, then each with its
  // neighbours.
  const int to_columns = (to.geometry.width + kTileCells - 1) / kTileCells;
  const int to_rows = (to.geometry.height + kTileCells - 1) / kTileCells;
  cv::Mat known_tiles(to_rows + 2, to_columns + 2, CV_8U, cv::Scalar(0));
  for (int y = 0; y < to.geometry.height; ++y) {
    for (int x = 0; x < to.geometry.width; ++x) {
      if (to.at(x, y) != GridMap::kUnknown) {
        known_tiles.at<std::uint8_t>(y / kTileCells + 1, x / kTileCells + 1) = 1;
      }
    }
  }
  cv::dilate(known_tiles, near_known_tiles_, cv::Mat::ones(3, 3, CV_8U));
}

bool SampledComparison::nearKnownTile(const Eigen::Vector2d& cell) const {
  const int column = floorToInt(cell.x() / kTileCells) + 1;
  const int row = floorToInt(cell.y() / kTileCells) + 1;
  return column >= 0 && row >= 0 && column < near_known_tiles_.cols &&
         row < near_known_tiles_.rows && near_known_tiles_.ptr<std::uint8_t>(row)[column] != 0;
}

const std::vector<CellSample>& SampledComparison::landingSamples(
    const GridTransform& T_to_from) const {
  landing_.clear();
  for (const Tile& tile : tiles_) {
    if (nearKnownTile(T_to_from.apply(tile.centre))) {
      landing_.insert(landing_.end(), samples_.begin() + static_cast<std::ptrdiff_t>(tile.begin),
                      samples_.begin() + static_cast<std::ptrdiff_t>(tile.end));
    }
  }
  return landing_;
}

double SampledComparison::disagreementRate(const GridTransform& T_to_from) const {
  return 1.0 -
         verificationIndex(compareAt(landingSamples(T_to_from), to_, T_to_from, tables_, false));
}

bool SampledComparison::disagreesMoreThan(const GridTransform& T_to_from, double rate) const {
  return disagreementRateExceeds(landingSamples(T_to_from), to_, T_to_from, tables_, rate);
}

}  // namespace mrslam::fusion
