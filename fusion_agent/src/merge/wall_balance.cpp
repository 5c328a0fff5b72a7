#include "mrslam/fusion/merge/wall_balance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>

namespace mrslam::fusion {

namespace {

// The balance of `from` read through T_from_to at the cells origin + (column, row) of `to` for
// an image of `size`, where `needed` is non-zero; 0 elsewhere and off `from`'s padded image.
cv::Mat readThrough(const CodeImage& from, const cv::Mat& balance_from,
                    const GridTransform& T_from_to, const cv::Point& origin,
                    const cv::Mat& needed) {
  cv::Mat read_through(needed.size(), CV_8S, cv::Scalar(0));
  CellRounding rounding(T_from_to);
  const int high_x = from.codes.cols - from.pad - 1;
  const int high_y = from.codes.rows - from.pad - 1;
  for (int row = 0; row < needed.rows; ++row) {
    const std::uint8_t* wanted = needed.ptr<std::uint8_t>(row);
    std::int8_t* out = read_through.ptr<std::int8_t>(row);
    const int qy = origin.y + row;
    for (int column = 0; column < needed.cols; ++column) {
      if (wanted[column] == 0) {
        continue;
      }
      const cv::Point cell = rounding.landing(origin.x + column, qy);
      if (cell.x >= -from.pad && cell.y >= -from.pad && cell.x <= high_x && cell.y <= high_y) {
        out[column] = balance_from.at<std::int8_t>(cell.y + from.pad, cell.x + from.pad);
      }
    }
  }
  return read_through;
}

constexpr int kLanes = 16;  // columns summed at once by windowSumsOfNarrowWindows

// windowSums for step 1 and windows at most kLanes wide: a centre whose kLanes columns from the
// window's left lie on the image adds them all at once (a fixed count the compiler turns into
// vector adds; the columns past the window are summed and dropped), the others cell by cell.
std::vector<long long> windowSumsOfNarrowWindows(const cv::Mat& values,
                                                 const std::vector<cv::Point>& centres, int reach) {
  const int count = 2 * reach + 1;
  std::vector<std::int32_t> wide(static_cast<std::size_t>(count * kLanes), 0);
  std::vector<std::int32_t> sums(static_cast<std::size_t>(count * count), 0);
  for (const cv::Point& centre : centres) {
    const int left = centre.x - reach;
    const int top = centre.y - reach;
    if (left >= 0 && top >= 0 && left + kLanes <= values.cols && top + count <= values.rows) {
      for (int row = 0; row < count; ++row) {
        const std::int8_t* cells = values.ptr<std::int8_t>(top + row) + left;
        std::int32_t* out = wide.data() + row * kLanes;
        for (int lane = 0; lane < kLanes; ++lane) {
          out[lane] += cells[lane];
        }
      }
      continue;
    }
    for (int row = 0; row < count; ++row) {
      const int y = top + row;
      if (y < 0 || y >= values.rows) {
        continue;
      }
      const std::int8_t* cells = values.ptr<std::int8_t>(y);
      std::int32_t* out = sums.data() + row * count;
      for (int column = 0; column < count; ++column) {
        const int x = left + column;
        if (x >= 0 && x < values.cols) {
          out[column] += cells[x];
        }
      }
    }
  }
  std::vector<long long> result(sums.size());
  for (int row = 0; row < count; ++row) {
    for (int column = 0; column < count; ++column) {
      const std::size_t k = static_cast<std::size_t>(row * count + column);
      result[k] =
          static_cast<long long>(sums[k]) + wide[static_cast<std::size_t>(row * kLanes + column)];
    }
  }
  return result;
}

}  // namespace

std::vector<long long> windowSums(const cv::Mat& values, const std::vector<cv::Point>& centres,
                                  int reach, int step) {
  step = std::max(1, step);
  if (step == 1 && 2 * reach + 1 <= kLanes) {
    return windowSumsOfNarrowWindows(values, centres, reach);
  }
  const int count = 2 * reach / step + 1;  // offsets -reach, -reach + step, ... up to reach
  const int span = (count - 1) * step + 1;
  std::vector<std::int32_t> sums(static_cast<std::size_t>(count * count), 0);
  for (const cv::Point& centre : centres) {
    const int left = centre.x - reach;
    const int top = centre.y - reach;
    const bool inside =
        left >= 0 && top >= 0 && left + span <= values.cols && top + span <= values.rows;
    for (int row = 0; row < count; ++row) {
      const int y = top + row * step;
      if (!inside && (y < 0 || y >= values.rows)) {
        continue;
      }
      const std::int8_t* cells = values.ptr<std::int8_t>(y);
      std::int32_t* out = sums.data() + row * count;
      for (int column = 0; column < count; ++column) {
        const int x = left + column * step;
        if (inside || (x >= 0 && x < values.cols)) {
          out[column] += cells[x];
        }
      }
    }
  }
  return {sums.begin(), sums.end()};
}

cv::Mat wallBalanceImage(const CodeImage& image) {
  cv::Mat balance(image.classes.size(), CV_8S, cv::Scalar(0));
  for (int y = 0; y < balance.rows; ++y) {
    const std::uint8_t* classes = image.classes.ptr<std::uint8_t>(y);
    const std::uint8_t* near = image.near_occupied.ptr<std::uint8_t>(y);
    std::int8_t* out = balance.ptr<std::int8_t>(y);
    for (int x = 0; x < balance.cols; ++x) {
      out[x] = classes[x] == 0 ? 0 : (near[x] != 0 ? 1 : -1);
    }
  }
  return balance;
}

std::vector<long long> wallBalancesAfterShifts(const std::vector<CellSample>& samples,
                                               const CodeImage& to, const cv::Mat& balance_to,
                                               const GridTransform& T_to_from, int reach,
                                               const ComparisonTables& tables) {
  // Each wall sample's cell in the padded image of `to` at the unshifted transform; a shift
  // moves every cell by the same whole cells.
  CellRounding rounding(T_to_from);
  std::vector<cv::Point> centres;
  centres.reserve(samples.size());
  for (const CellSample& sample : samples) {
    if (tables.isOccupied(sample.code)) {
      centres.push_back(rounding.landing(sample.x, sample.y) + cv::Point(to.pad, to.pad));
    }
  }
  return windowSums(balance_to, centres, reach, 1);
}

std::vector<long long> wallBalancesOfInverseShifts(const std::vector<CellSample>& samples_to,
                                                   const CodeImage& from,
                                                   const cv::Mat& balance_from,
                                                   const GridTransform& T_to_from, int reach,
                                                   const ComparisonTables& tables) {
  // (T shifted by d)⁻¹ q = T⁻¹ (q - d): the balance of `from` read through T⁻¹ at every cell of
  // `to` the shifted samples reach, then window sums around the samples, offsets reversed.
  std::vector<cv::Point> walls;
  cv::Rect bounds;
  for (const CellSample& sample : samples_to) {
    if (tables.isOccupied(sample.code)) {
      walls.emplace_back(sample.x, sample.y);
      bounds = walls.size() == 1 ? cv::Rect(walls.back(), cv::Size(1, 1))
                                 : (bounds | cv::Rect(walls.back(), cv::Size(1, 1)));
    }
  }
  const int side = 2 * reach + 1;
  if (walls.empty()) {
    return std::vector<long long>(static_cast<std::size_t>(side * side), 0);
  }
  const cv::Point origin = bounds.tl() - cv::Point(reach, reach);
  for (cv::Point& wall : walls) {
    wall -= origin;
  }
  // Only the cells within ±reach of a wall are summed: those are read.
  cv::Mat needed(bounds.height + 2 * reach, bounds.width + 2 * reach, CV_8U, cv::Scalar(0));
  for (const cv::Point& wall : walls) {
    needed.at<std::uint8_t>(wall) = 1;
  }
  cv::dilate(needed, needed, cv::Mat::ones(side, side, CV_8U));
  const cv::Mat read_through = readThrough(from, balance_from, T_to_from.inverse(), origin, needed);
  std::vector<long long> by_offset = windowSums(read_through, walls, reach, 1);
  std::reverse(by_offset.begin(), by_offset.end());  // offset -d is shift d
  return by_offset;
}

}  // namespace mrslam::fusion
