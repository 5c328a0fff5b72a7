#include "mrslam/fusion/merge/edges.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace mrslam::fusion {

namespace {

// An edge cell takes part in the scan along an axis when its gradient along that axis is at
// least this share of the gradient across it (tan 35°: within ~55° of the axis).
constexpr float kAcrossShare = 0.7f;

struct FaceCell {
  int position;
  Face face;
};

// Consecutive cells of one face: one face of a wall, one or two cells thick.
struct FaceRun {
  Face face;
  int first;
  int last;
  double centre() const { return 0.5 * (first + last); }
};

std::vector<FaceRun> faceRuns(const std::vector<FaceCell>& cells) {
  std::vector<FaceRun> runs;
  for (const FaceCell& cell : cells) {
    if (!runs.empty() && runs.back().face == cell.face && runs.back().last == cell.position - 1) {
      runs.back().last = cell.position;
    } else {
      runs.push_back({cell.face, cell.position, cell.position});
    }
  }
  return runs;
}

// Pairs the face runs of one scan line; calls middle(i) for every middle cell and paired(i) for
// every face cell it replaces.
template <typename Middle, typename Paired>
void pairFaces(const std::vector<FaceCell>& cells, int dt, Middle middle, Paired paired) {
  const std::vector<FaceRun> runs = faceRuns(cells);
  for (std::size_t r = 0; r + 1 < runs.size(); ++r) {
    const FaceRun& rising = runs[r];
    const FaceRun& falling = runs[r + 1];
    if (rising.face != Face::kRising || falling.face != Face::kFalling ||
        falling.first - rising.last <= 1 || falling.centre() - rising.centre() >= dt) {
      continue;
    }
    middle(static_cast<int>(std::floor(0.5 * (rising.centre() + falling.centre()) + 0.5)));
    for (const FaceRun* run : {&rising, &falling}) {
      for (int i = run->first; i <= run->last; ++i) {
        paired(i);
      }
    }
    ++r;
  }
}

// Sobel derivative of the smoothed image at an inner cell, along x (columns) or y (rows).
float sobel(const cv::Mat& image, int x, int y, bool along_x) {
  const auto at = [&](int dx, int dy) {
    return static_cast<float>(along_x ? image.at<std::uint8_t>(y + dy, x + dx)
                                      : image.at<std::uint8_t>(y + dx, x + dy));
  };
  return (at(1, -1) + 2.0f * at(1, 0) + at(1, 1)) - (at(-1, -1) + 2.0f * at(-1, 0) + at(-1, 1));
}

// The face cells of every row (horizontal scan) and every column (vertical scan), in order.
void collectFaces(const DetectedEdges& detected, std::vector<std::vector<FaceCell>>& rows,
                  std::vector<std::vector<FaceCell>>& cols) {
  const cv::Mat& edges = detected.edges;
  rows.assign(static_cast<std::size_t>(edges.rows), {});
  cols.assign(static_cast<std::size_t>(edges.cols), {});
  for (int y = 1; y + 1 < edges.rows; ++y) {
    const auto* edge = edges.ptr<std::uint8_t>(y);
    for (int x = 1; x + 1 < edges.cols; ++x) {
      if (edge[x] == 0) {
        continue;
      }
      const float gx = sobel(detected.smoothed, x, y, true);
      const float gy = sobel(detected.smoothed, x, y, false);
      if (gx != 0.0f && std::abs(gx) >= kAcrossShare * std::abs(gy)) {
        rows[static_cast<std::size_t>(y)].push_back(
            {x, gx > 0.0f ? Face::kRising : Face::kFalling});
      }
      if (gy != 0.0f && std::abs(gy) >= kAcrossShare * std::abs(gx)) {
        cols[static_cast<std::size_t>(x)].push_back(
            {y, gy > 0.0f ? Face::kRising : Face::kFalling});
      }
    }
  }
}

}  // namespace

cv::Mat occupiedImage(const GridMap& map, int occupied_threshold) {
  cv::Mat image(map.geometry.height, map.geometry.width, CV_8U, cv::Scalar(0));
  for (int y = 0; y < map.geometry.height; ++y) {
    auto* row = image.ptr<std::uint8_t>(y);
    for (int x = 0; x < map.geometry.width; ++x) {
      row[x] = map.at(x, y) >= occupied_threshold ? 255 : 0;
    }
  }
  return image;
}

DetectedEdges detectEdges(const cv::Mat& occupied, const EdgeSettings& settings) {
  DetectedEdges detected;
  cv::GaussianBlur(occupied, detected.smoothed, cv::Size(0, 0), settings.smoothing_sigma);
  cv::Canny(detected.smoothed, detected.edges, settings.canny_low, settings.canny_high, 3, true);
  return detected;
}

ScanLineResult smoothScanLine(const std::vector<Face>& faces, int edge_merge_distance_dt) {
  ScanLineResult result{std::vector<bool>(faces.size(), false),
                        std::vector<bool>(faces.size(), false)};
  std::vector<FaceCell> cells;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (faces[i] != Face::kNone) {
      cells.push_back({static_cast<int>(i), faces[i]});
    }
  }
  pairFaces(
      cells, edge_merge_distance_dt,
      [&](int i) { result.middles[static_cast<std::size_t>(i)] = true; },
      [&](int i) { result.paired[static_cast<std::size_t>(i)] = true; });
  return result;
}

cv::Mat smoothEdges(const DetectedEdges& detected, int edge_merge_distance_dt) {
  std::vector<std::vector<FaceCell>> rows;
  std::vector<std::vector<FaceCell>> cols;
  collectFaces(detected, rows, cols);
  cv::Mat keep = detected.edges.clone();
  cv::Mat middles(detected.edges.size(), CV_8U, cv::Scalar(0));
  for (std::size_t y = 0; y < rows.size(); ++y) {  // horizontal scan
    const int row = static_cast<int>(y);
    pairFaces(
        rows[y], edge_merge_distance_dt, [&](int x) { middles.at<std::uint8_t>(row, x) = 255; },
        [&](int x) { keep.at<std::uint8_t>(row, x) = 0; });
  }
  for (std::size_t x = 0; x < cols.size(); ++x) {  // vertical scan
    const int col = static_cast<int>(x);
    pairFaces(
        cols[x], edge_merge_distance_dt, [&](int y) { middles.at<std::uint8_t>(y, col) = 255; },
        [&](int y) { keep.at<std::uint8_t>(y, col) = 0; });
  }
  return keep | middles;
}

std::vector<cv::Point> nonZeroCells(const cv::Mat& image) {
  std::vector<cv::Point> cells;
  for (int y = 0; y < image.rows; ++y) {
    const auto* row = image.ptr<std::uint8_t>(y);
    for (int x = 0; x < image.cols; ++x) {
      if (row[x] != 0) {
        cells.emplace_back(x, y);
      }
    }
  }
  return cells;
}

}  // namespace mrslam::fusion
