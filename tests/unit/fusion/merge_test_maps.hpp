#pragma once
// Test-only helpers of the seed merge tests and merge_bench: a small loader for the shared map
// files and a seeded generator of known-answer cases (two overlapping crops of one real map, one
// of them rotated). The project's own map loaders and case generator live elsewhere; these stay
// private to the merge tests so that they do not depend on them.

#include <Eigen/Core>
#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <sstream>
#include <string>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"

namespace mrslam::fusion::merge_test {

/// Carpin's ASCII maps (0 occupied, 127 unknown, 255 free) and map_server PGMs (0 occupied,
/// 205 unknown, 254 free); the file's top row becomes the grid's top row. Empty map on failure.
inline GridMap loadMap(const std::string& path) {
  cv::Mat image;
  if (path.size() > 4 && path.substr(path.size() - 4) == ".txt") {
    std::ifstream file(path);
    std::string line;
    std::vector<std::vector<int>> rows;
    while (std::getline(file, line)) {
      std::istringstream values(line);
      rows.emplace_back();
      for (int value = 0; values >> value;) {
        rows.back().push_back(value);
      }
      if (rows.back().empty()) {
        rows.pop_back();
      }
    }
    if (rows.empty()) {
      return {};
    }
    image = cv::Mat(static_cast<int>(rows.size()), static_cast<int>(rows[0].size()), CV_8U);
    for (int r = 0; r < image.rows; ++r) {
      for (int c = 0; c < image.cols; ++c) {
        image.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(
            rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)]);
      }
    }
  } else {
    image = cv::imread(path, cv::IMREAD_GRAYSCALE);
  }
  GridGeometry geometry;
  geometry.width = image.cols;
  geometry.height = image.rows;
  GridMap map(geometry, GridMap::kUnknown);
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      const int grey = image.at<std::uint8_t>(r, c);
      map.at(c, image.rows - 1 - r) =
          grey <= 64 ? GridMap::kOccupied : (grey >= 250 ? GridMap::kFree : GridMap::kUnknown);
    }
  }
  return map;
}

/// Two overlapping crops of one map with the true transform between them.
struct KnownCase {
  GridMap from;             ///< the rotated crop
  GridMap to;               ///< the axis-aligned crop
  GridTransform T_to_from;  ///< the truth
  double overlap = 0.0;     ///< shared known cells / known cells of the smaller crop
  Eigen::Vector2d overlap_centre_from = Eigen::Vector2d::Zero();  ///< where errors are measured
};

inline bool isKnown(const GridMap& map, int x, int y) {
  return map.geometry.contains(x, y) && map.at(x, y) != GridMap::kUnknown;
}

/// The overlap of two windows in source cells: known cells inside both over the known cells of
/// the one with fewer; `shared_centre` gets the centre of the shared cells in `from` cells.
inline double windowOverlap(const GridMap& source, const Eigen::Vector2i& corner, int size,
                            const Eigen::Vector2d& centre_from, double theta,
                            Eigen::Vector2d* shared_centre = nullptr) {
  const Eigen::Matrix2d rotation =
      (Eigen::Matrix2d() << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta))
          .finished();
  const Eigen::Vector2d half(0.5 * (size - 1), 0.5 * (size - 1));
  const auto inFrom = [&](int mx, int my, Eigen::Vector2d& p) {
    p = rotation.transpose() * (Eigen::Vector2d(mx, my) - centre_from) + half;
    return p.minCoeff() >= -0.5 && p.maxCoeff() < size - 0.5;
  };
  std::size_t in_to = 0;
  std::size_t in_from = 0;
  std::size_t shared = 0;
  Eigen::Vector2d shared_sum = Eigen::Vector2d::Zero();
  Eigen::Vector2d p;
  for (int y = 0; y < size; ++y) {  // the to window, axis-aligned
    for (int x = 0; x < size; ++x) {
      if (isKnown(source, corner.x() + x, corner.y() + y)) {
        ++in_to;
        if (inFrom(corner.x() + x, corner.y() + y, p)) {
          ++shared;
          shared_sum += p;
        }
      }
    }
  }
  const int reach = static_cast<int>(std::ceil(0.71 * size)) + 1;  // the turned window's extent
  for (int my = static_cast<int>(centre_from.y()) - reach; my <= centre_from.y() + reach; ++my) {
    for (int mx = static_cast<int>(centre_from.x()) - reach; mx <= centre_from.x() + reach; ++mx) {
      in_from += isKnown(source, mx, my) && inFrom(mx, my, p) ? 1 : 0;
    }
  }
  if (shared_centre != nullptr) {
    *shared_centre = shared > 0 ? Eigen::Vector2d(shared_sum / static_cast<double>(shared)) : half;
  }
  const std::size_t smaller = std::min(in_to, in_from);
  return smaller > 0 ? static_cast<double>(shared) / static_cast<double>(smaller) : 0.0;
}

/// Crops a size × size window at `corner` (to) and a window of the same size centred
/// `centre_from`, turned by theta (from), with the truth and the overlap.
inline KnownCase cropPair(const GridMap& source, const Eigen::Vector2i& corner, int size,
                          const Eigen::Vector2d& centre_from, double theta) {
  KnownCase known;
  GridGeometry geometry;
  geometry.width = size;
  geometry.height = size;
  known.to = GridMap(geometry, GridMap::kUnknown);
  known.from = GridMap(geometry, GridMap::kUnknown);
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  const Eigen::Vector2d half(0.5 * (size - 1), 0.5 * (size - 1));
  const Eigen::Matrix2d rotation = (Eigen::Matrix2d() << c, -s, s, c).finished();
  known.T_to_from.theta_rad = theta;
  known.T_to_from.t_cells = centre_from - rotation * half - corner.cast<double>();
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      if (isKnown(source, corner.x() + x, corner.y() + y)) {
        known.to.at(x, y) = source.at(corner.x() + x, corner.y() + y);
      }
      const Eigen::Vector2d m = rotation * (Eigen::Vector2d(x, y) - half) + centre_from;
      const int mx = static_cast<int>(std::floor(m.x() + 0.5));
      const int my = static_cast<int>(std::floor(m.y() + 0.5));
      if (isKnown(source, mx, my)) {
        known.from.at(x, y) = source.at(mx, my);
      }
    }
  }
  known.overlap =
      windowOverlap(source, corner, size, centre_from, theta, &known.overlap_centre_from);
  return known;
}

/// A random case with overlap in [low, high): random window of `size` holding ≥ 15 % known
/// cells, the other window's centre offset by up to `size` cells, a uniform turn. Tries up to
/// 500 draws; overlap 0 when none fits.
inline KnownCase randomCase(const GridMap& source, int size, double low, double high,
                            std::mt19937& random) {
  std::uniform_int_distribution<int> corner_x(0, std::max(0, source.geometry.width - size));
  std::uniform_int_distribution<int> corner_y(0, std::max(0, source.geometry.height - size));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int attempt = 0; attempt < 500; ++attempt) {
    const Eigen::Vector2i corner(corner_x(random), corner_y(random));
    const double direction = 2.0 * M_PI * unit(random);
    const double distance = size * unit(random);
    const double theta = M_PI * (2.0 * unit(random) - 1.0);
    const Eigen::Vector2d centre_to =
        corner.cast<double>() + Eigen::Vector2d::Constant(0.5 * (size - 1));
    const Eigen::Vector2d centre_from =
        centre_to + distance * Eigen::Vector2d(std::cos(direction), std::sin(direction));
    const double overlap = windowOverlap(source, corner, size, centre_from, theta);
    if (overlap < low || overlap >= high) {
      continue;
    }
    KnownCase known = cropPair(source, corner, size, centre_from, theta);
    const auto known_share = [&](const GridMap& map) {
      std::size_t count = 0;
      for (const std::int8_t value : map.cells) {
        count += value != GridMap::kUnknown ? 1 : 0;
      }
      return static_cast<double>(count) / static_cast<double>(map.cells.size());
    };
    if (known.overlap >= low && known.overlap < high && known_share(known.to) >= 0.15 &&
        known_share(known.from) >= 0.15) {
      return known;
    }
  }
  return {};
}

/// Errors of an estimate: rotation (rad) and distance (cells) at the overlap's centre.
struct PoseError {
  double rotation_rad = 0.0;
  double translation_cells = 0.0;
};

inline PoseError poseError(const GridTransform& estimate, const KnownCase& known) {
  PoseError error;
  error.rotation_rad =
      std::abs(std::remainder(estimate.theta_rad - known.T_to_from.theta_rad, 2.0 * M_PI));
  error.translation_cells =
      (estimate.apply(known.overlap_centre_from) - known.T_to_from.apply(known.overlap_centre_from))
          .norm();
  return error;
}

/// The goal of the issue: within 2 cells and 1°.
inline bool isSuccess(const PoseError& error) {
  return error.rotation_rad <= M_PI / 180.0 && error.translation_cells <= 2.0;
}

/// Free rooms of 80 × 60 cells with walls and an irregular inner wall: no shift looks like
/// another.
inline GridMap handBuiltRooms() {
  GridGeometry geometry;
  geometry.width = 80;
  geometry.height = 60;
  GridMap map(geometry, GridMap::kFree);
  for (int x = 0; x < 80; ++x) {
    map.at(x, 0) = map.at(x, 59) = GridMap::kOccupied;
  }
  for (int y = 0; y < 60; ++y) {
    map.at(0, y) = map.at(79, y) = GridMap::kOccupied;
  }
  for (int y = 10; y < 45; ++y) {
    map.at(30, y) = GridMap::kOccupied;
  }
  for (int x = 30; x < 62; ++x) {
    map.at(x, 25 + (x - 30) / 4) = GridMap::kOccupied;
  }
  return map;
}

}  // namespace mrslam::fusion::merge_test
