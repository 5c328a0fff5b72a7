#include "mrslam/fusion/merge/segments.hpp"

#include <algorithm>
#include <cmath>

namespace mrslam::fusion {

namespace {

constexpr double kMostBackwardStep = -0.3;  // cosine: steps turning by more than ~107° are refused
constexpr int kSmoothingRadius = 2;         // moving average of 5 cells along the chain

double wrapAngle(double angle) {
  return std::remainder(angle, 2.0 * M_PI);
}

Eigen::Vector2d toVector(cv::Point p) {
  return Eigen::Vector2d(p.x, p.y);
}

std::vector<Eigen::Vector2d> smoothChain(const std::vector<cv::Point>& chain) {
  const int size = static_cast<int>(chain.size());
  std::vector<Eigen::Vector2d> smoothed(chain.size());
  for (int i = 0; i < size; ++i) {
    const int radius = std::min({kSmoothingRadius, i, size - 1 - i});
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (int j = i - radius; j <= i + radius; ++j) {
      sum += toVector(chain[static_cast<std::size_t>(j)]);
    }
    smoothed[static_cast<std::size_t>(i)] = sum / (2 * radius + 1);
  }
  return smoothed;
}

// Points at arc length 0, 1, …, count-1 along a polyline; empty when it is too short.
std::vector<Eigen::Vector2d> resample(const std::vector<Eigen::Vector2d>& polyline, int count) {
  std::vector<Eigen::Vector2d> points;
  if (polyline.empty()) {
    return points;
  }
  points.push_back(polyline.front());
  double travelled = 0.0;  // arc length at polyline[i]
  for (std::size_t i = 0; i + 1 < polyline.size() && static_cast<int>(points.size()) < count; ++i) {
    const Eigen::Vector2d step = polyline[i + 1] - polyline[i];
    const double length = step.norm();
    while (length > 0.0 && static_cast<int>(points.size()) < count &&
           static_cast<double>(points.size()) <= travelled + length) {
      const double along = (static_cast<double>(points.size()) - travelled) / length;
      points.push_back(polyline[i] + along * step);
    }
    travelled += length;
  }
  if (static_cast<int>(points.size()) < count) {
    points.clear();
  }
  return points;
}

}  // namespace

FittedLine fitLine(const std::vector<Eigen::Vector2d>& points, std::size_t first,
                   std::size_t count) {
  FittedLine line;
  if (count == 0) {
    return line;
  }
  for (std::size_t i = first; i < first + count; ++i) {
    line.centroid += points[i];
  }
  line.centroid /= static_cast<double>(count);
  double sxx = 0.0;
  double syy = 0.0;
  double sxy = 0.0;
  for (std::size_t i = first; i < first + count; ++i) {
    const Eigen::Vector2d d = points[i] - line.centroid;
    sxx += d.x() * d.x();
    syy += d.y() * d.y();
    sxy += d.x() * d.y();
  }
  double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  if (angle < 0.0) {
    angle += M_PI;
  }
  line.angle_rad = angle >= M_PI ? angle - M_PI : angle;
  return line;
}

EdgeFollower::EdgeFollower(const cv::Mat& edges, int gap_jump_cells)
    : edges_(edges), gap_jump_cells_(std::max(1, gap_jump_cells)), stamps_(edges.total(), 0) {}

bool EdgeFollower::isFreshEdge(int x, int y) const {
  if (x < 0 || y < 0 || x >= edges_.cols || y >= edges_.rows) {
    return false;
  }
  return edges_.at<std::uint8_t>(y, x) != 0 &&
         stamps_[static_cast<std::size_t>(y) * static_cast<std::size_t>(edges_.cols) +
                 static_cast<std::size_t>(x)] != stamp_;
}

void EdgeFollower::visit(cv::Point cell) {
  stamps_[static_cast<std::size_t>(cell.y) * static_cast<std::size_t>(edges_.cols) +
          static_cast<std::size_t>(cell.x)] = stamp_;
}

std::optional<cv::Point> EdgeFollower::nextCell(cv::Point current,
                                                const Eigen::Vector2d& direction) const {
  for (int radius = 1; radius <= gap_jump_cells_; ++radius) {
    std::optional<cv::Point> best;
    double best_score = -1e9;
    for (int dy = -radius; dy <= radius; ++dy) {
      for (int dx = -radius; dx <= radius; ++dx) {
        if (std::max(std::abs(dx), std::abs(dy)) != radius ||
            !isFreshEdge(current.x + dx, current.y + dy)) {
          continue;
        }
        const Eigen::Vector2d step(dx, dy);
        const double cosine = direction.isZero() ? 0.0 : direction.dot(step.normalized());
        const double score = cosine - 0.01 * step.norm();
        if (cosine >= kMostBackwardStep && score > best_score) {
          best_score = score;
          best = cv::Point(current.x + dx, current.y + dy);
        }
      }
    }
    if (best) {
      return best;
    }
  }
  return std::nullopt;
}

std::vector<cv::Point> EdgeFollower::walk(cv::Point from, cv::Point direction_hint,
                                          double length_cells) {
  std::vector<cv::Point> steps;
  cv::Point current = from;
  double length = 0.0;
  while (length < length_cells) {
    const cv::Point behind = steps.size() >= 3 ? steps[steps.size() - 3]
                                               : (steps.empty() ? from - direction_hint : from);
    Eigen::Vector2d direction = toVector(current - behind);
    if (!direction.isZero()) {
      direction.normalize();
    }
    const std::optional<cv::Point> next = nextCell(current, direction);
    if (!next) {
      break;
    }
    for (int dy = -1; dy <= 1; ++dy) {  // side cells of a thick edge would lead back
      for (int dx = -1; dx <= 1; ++dx) {
        const cv::Point side(current.x + dx, current.y + dy);
        if (isFreshEdge(side.x, side.y) && std::abs(side.x - next->x) <= 1 &&
            std::abs(side.y - next->y) <= 1) {
          visit(side);
        }
      }
    }
    visit(*next);
    length += toVector(*next - current).norm();
    steps.push_back(*next);
    current = *next;
  }
  return steps;
}

std::vector<cv::Point> EdgeFollower::follow(cv::Point start, double length_cells) {
  ++stamp_;
  visit(start);
  std::vector<cv::Point> forward = walk(start, cv::Point(0, 0), length_cells);
  double length = 0.0;
  cv::Point previous = start;
  for (const cv::Point& cell : forward) {
    length += toVector(cell - previous).norm();
    previous = cell;
  }
  std::vector<cv::Point> chain;
  if (length < length_cells && !forward.empty()) {
    const cv::Point away = start - forward.front();  // walk backwards, away from the first step
    std::vector<cv::Point> backward = walk(start, away, length_cells - length);
    chain.assign(backward.rbegin(), backward.rend());
  }
  chain.push_back(start);
  chain.insert(chain.end(), forward.begin(), forward.end());
  return chain;
}

std::optional<Segment> makeSegment(const std::vector<cv::Point>& chain,
                                   const SegmentSettings& settings) {
  const int n = settings.segment_points_n;
  const int k = settings.turn_chord_k;
  Segment segment;
  segment.points = resample(smoothChain(chain), n);
  if (segment.points.empty() || n <= 2 * k) {
    return std::nullopt;
  }
  segment.line = fitLine(segment.points, 0, segment.points.size());
  const Eigen::Vector2d normal(-std::sin(segment.line.angle_rad), std::cos(segment.line.angle_rad));
  for (const Eigen::Vector2d& p : segment.points) {
    segment.distances.push_back(std::abs(normal.dot(p - segment.line.centroid)));
  }
  for (int i = k; i < n - k; ++i) {
    const Eigen::Vector2d before = segment.points[static_cast<std::size_t>(i)] -
                                   segment.points[static_cast<std::size_t>(i - k)];
    const Eigen::Vector2d after = segment.points[static_cast<std::size_t>(i + k)] -
                                  segment.points[static_cast<std::size_t>(i)];
    segment.turns.push_back(
        wrapAngle(std::atan2(after.y(), after.x()) - std::atan2(before.y(), before.x())));
  }
  return segment;
}

}  // namespace mrslam::fusion
