#pragma once
// Blocks 1 and 2 of the seed merge: edges of the occupied structure.
//
// 1. Edge detection: the occupied cells become a binary image (255 occupied, 0 otherwise),
//    smoothed by a Gaussian against cell noise, then OpenCV's Canny marks the edges.
// 2. Edge smoothing: Canny outlines both faces of a wall. A horizontal scan of every row and a
//    vertical scan of every column walk the edge cells that face across the scan line: the face
//    of a wall entering occupancy ("rising", the smoothed occupancy grows along the scan) and the
//    face leaving it ("falling"). A horizontal scan takes the edge cells whose occupancy gradient
//    is within ~55° of horizontal, a vertical scan those within ~55° of vertical.
//    - A rising face followed by a falling face more than 1 and less than dt cells on: the two
//      faces of one obstacle; both are replaced by their middle cell.
//    - Adjacent cells (1 apart) are both kept.
//    - Faces dt or more apart, or in the other order (free space between two obstacles), are
//      distinct obstacles and are kept.
//    Edge cells that no scan pairs (wall ends, faces of obstacles thicker than dt) stay.
//    Pairing by face (the sign of the gradient) rather than by any two edge cells keeps the scan
//    from merging the facing sides of two walls across a corridor narrower than dt.
//
// Images index cells as image(row = cy, col = cx): row 0 is the grid's bottom row.

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "mrslam/common/grid_map.hpp"

namespace mrslam::fusion {

/// Settings of blocks 1 and 2.
struct EdgeSettings {
  int occupied_threshold = 65;     ///< a cell of occupancy ≥ this (percent) is structure
  double smoothing_sigma = 1.0;    ///< σ (cells) of the Gaussian noise smoothing before Canny
  double canny_low = 40.0;         ///< Canny hysteresis low threshold (on 0..255 images)
  double canny_high = 120.0;       ///< Canny hysteresis high threshold
  int edge_merge_distance_dt = 8;  ///< dt: faces closer than this (cells) bound one obstacle
};

/// Block 1's output.
struct DetectedEdges {
  cv::Mat smoothed;  ///< the Gaussian-smoothed occupied image (CV_8U)
  cv::Mat edges;     ///< Canny's edges (CV_8U, 255 on edges)
};

/// The occupied cells of a map: CV_8U, 255 where occupancy ≥ threshold, else 0.
cv::Mat occupiedImage(const GridMap& map, int occupied_threshold);

/// Block 1: Gaussian smoothing then Canny.
DetectedEdges detectEdges(const cv::Mat& occupied, const EdgeSettings& settings);

/// Face of an edge cell along one scan line.
enum class Face : std::int8_t { kNone = 0, kRising = 1, kFalling = -1 };

/// One line of a scan: the middle cells it adds and the face cells it pairs (and so removes).
struct ScanLineResult {
  std::vector<bool> middles;
  std::vector<bool> paired;
};

/// Block 2 on one scan line.
ScanLineResult smoothScanLine(const std::vector<Face>& faces, int edge_merge_distance_dt);

/// Block 2: middle-point edge smoothing by horizontal and vertical scans (CV_8U, 255 on edges).
cv::Mat smoothEdges(const DetectedEdges& detected, int edge_merge_distance_dt);

/// All non-zero cells of a CV_8U image as (x = column, y = row), row-major order.
std::vector<cv::Point> nonZeroCells(const cv::Mat& image);

}  // namespace mrslam::fusion
