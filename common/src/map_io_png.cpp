// Map pictures: one pixel per cell, y up, trajectories drawn over the cells.
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>

#include "mrslam/common/map_io.hpp"

namespace mrslam {
namespace {

constexpr int kUnknownGrey = 128;
constexpr int kSubpixelBits = 4;  ///< fixed-point fraction bits of the polyline vertices

/// Pixel coordinates (column, row; pixel centres at integers) of a map-frame point, fixed point.
cv::Point toPixel(const GridGeometry& g, const Eigen::Vector2d& point_m) {
  const double scale = 1 << kSubpixelBits;
  const double column = (point_m.x() - g.origin_m.x()) / g.resolution_m - 0.5;
  const double row = g.height - 0.5 - (point_m.y() - g.origin_m.y()) / g.resolution_m;
  return cv::Point(static_cast<int>(std::lround(column * scale)),
                   static_cast<int>(std::lround(row * scale)));
}

/// The picture of saveMapPng as a BGR image.
cv::Mat renderMap(const GridMap& map, const std::vector<MapOverlay>& overlays) {
  const GridGeometry& g = map.geometry;
  cv::Mat image(g.height, g.width, CV_8UC3);
  for (int row = 0; row < g.height; ++row) {
    auto* out = image.ptr<cv::Vec3b>(row);
    const int cy = g.height - 1 - row;  // y up: the top row holds the largest y
    for (int cx = 0; cx < g.width; ++cx) {
      const int v = map.at(cx, cy);
      const int shade =
          v == GridMap::kUnknown ? kUnknownGrey : occupancyToShade(static_cast<std::int8_t>(v));
      out[cx] = cv::Vec3b(static_cast<std::uint8_t>(shade), static_cast<std::uint8_t>(shade),
                          static_cast<std::uint8_t>(shade));
    }
  }
  for (const MapOverlay& overlay : overlays) {
    const cv::Vec3b cell_colour(static_cast<std::uint8_t>(overlay.bgr.x()),
                                static_cast<std::uint8_t>(overlay.bgr.y()),
                                static_cast<std::uint8_t>(overlay.bgr.z()));
    for (const Eigen::Vector2i& cell : overlay.cells) {
      if (g.contains(cell.x(), cell.y())) {
        image.at<cv::Vec3b>(g.height - 1 - cell.y(), cell.x()) = cell_colour;
      }
    }
  }
  for (const MapOverlay& overlay : overlays) {
    if (overlay.trajectory_m.empty()) {
      continue;
    }
    std::vector<cv::Point> points;
    points.reserve(overlay.trajectory_m.size());
    for (const Eigen::Vector2d& point : overlay.trajectory_m) {
      if (point.allFinite()) {
        points.push_back(toPixel(g, point));
      }
    }
    const cv::Scalar colour(overlay.bgr.x(), overlay.bgr.y(), overlay.bgr.z());
    if (points.size() == 1) {
      points.push_back(points.front());  // a one-point trajectory shows as a dot
    }
    cv::polylines(image, points, false, colour, 1, cv::LINE_8, kSubpixelBits);
  }
  return image;
}

}  // namespace

void saveMapPng(const GridMap& map, const std::string& png_path,
                const std::vector<MapOverlay>& overlays) {
  if (!map.isValid() || map.geometry.cellCount() == 0) {
    throw MapIoError(png_path + ": refusing to save an invalid or empty map");
  }
  const cv::Mat image = renderMap(map, overlays);
  bool written = false;
  try {
    written = cv::imwrite(png_path, image);
  } catch (const cv::Exception& error) {
    throw MapIoError(png_path + ": cannot write (" + error.what() + ")");
  }
  if (!written) {
    throw MapIoError(png_path + ": cannot write");
  }
}

std::vector<std::uint8_t> encodeMapPng(const GridMap& map,
                                       const std::vector<MapOverlay>& overlays) {
  if (!map.isValid() || map.geometry.cellCount() == 0) {
    throw MapIoError("refusing to encode an invalid or empty map");
  }
  std::vector<std::uint8_t> png;
  if (!cv::imencode(".png", renderMap(map, overlays), png)) {
    throw MapIoError("PNG encoding failed");
  }
  return png;
}

}  // namespace mrslam
