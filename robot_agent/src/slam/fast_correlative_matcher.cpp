#include "mrslam/robot/slam/fast_correlative_matcher.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>

#include "mrslam/robot/slam/correlative_matcher.hpp"

namespace mrslam::robot::slam {

namespace {

constexpr int kMaxDepth = 16;
constexpr double kLevels = 255.0;  ///< stored value of p_max (p_min and unknown: 0)
// Cells beyond ±2^29 are far outside any grid; clamping there keeps whole-cell shifts of the
// window from overflowing an int, whatever the guess.
constexpr double kFarCell = 536870912.0;

void check(const FastCorrelativeSettings& s) {
  const auto valid = [](double value) { return std::isfinite(value) && value >= 0.0; };
  if (!valid(s.linear_search_window_m) || !valid(s.angular_search_window_rad)) {
    throw std::invalid_argument("fast correlative matcher: windows must be finite and >= 0");
  }
  if (s.branch_and_bound_depth < 1 || s.branch_and_bound_depth > kMaxDepth) {
    throw std::invalid_argument("fast correlative matcher: depth must lie in 1 ... 16");
  }
}

/// ⌈window / step⌉, forgiving the rounding of a window that is a whole number of steps.
int stepsIn(double window, double step) {
  return static_cast<int>(std::ceil(window / step - 1e-9));
}

std::uint8_t quantised(float p, double p_min, double p_max) {
  if (p <= 0.0f) {
    return 0;  // unknown
  }
  const double fraction = std::clamp((p - p_min) / (p_max - p_min), 0.0, 1.0);
  return static_cast<std::uint8_t>(std::lround(fraction * kLevels));
}

}  // namespace

struct FastCorrelativeMatcher::Candidate {
  int rotation = -1;  ///< index into Search::rotations; -1: none yet
  int jx = 0;         ///< translation in cells from the window's centre
  int jy = 0;
  std::int64_t sum = 0;  ///< sum of stored values (a bound above height 0)
};

struct FastCorrelativeMatcher::Search {
  SE2 T_submap_centre;
  int wx = 0;  ///< |j_x| ≤ wx
  int wy = 0;
  std::vector<double> rotations;
  std::vector<std::vector<Eigen::Vector2i>> cells;   ///< per rotation, padded cells (step 3)
  std::vector<std::vector<std::ptrdiff_t>> offsets;  ///< ... as offsets into a padded grid
  std::vector<Eigen::Vector2i> low;                  ///< per rotation, the cells' smallest x, y
  std::vector<Eigen::Vector2i> high;                 ///< ... and largest
};

FastCorrelativeMatcher::FastCorrelativeMatcher(const ProbabilityGrid& grid,
                                               const FastCorrelativeSettings& settings)
    : settings_(settings) {
  check(settings_);
  resolution_m_ = grid.resolution();
  min_probability_ = grid.settings().min_probability;
  max_probability_ = grid.settings().max_probability;
  origin_cell_ = grid.originCell();
  width_ = grid.width();
  height_ = grid.height();
  pad_ = (1 << (depth() - 1)) - 1;
  padded_width_ = width_ + pad_;
  padded_height_ = height_ + pad_;
  precompute(grid);
}

// Step 2: M_0 is the quantised grid; M_h the max of four cells of M_{h−1}, 2^(h−1) apart.
void FastCorrelativeMatcher::precompute(const ProbabilityGrid& grid) {
  const std::size_t size =
      static_cast<std::size_t>(padded_width_) * static_cast<std::size_t>(padded_height_);
  grids_.assign(static_cast<std::size_t>(depth()), std::vector<std::uint8_t>(size, 0));
  const std::vector<float>& cells = grid.cells();
  std::vector<std::uint8_t>& base = grids_[0];
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const std::size_t from = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                               static_cast<std::size_t>(x);
      base[static_cast<std::size_t>(y + pad_) * static_cast<std::size_t>(padded_width_) +
           static_cast<std::size_t>(x + pad_)] =
          quantised(cells[from], min_probability_, max_probability_);
    }
  }
  for (int h = 1; h < depth(); ++h) {
    const int s = 1 << (h - 1);
    const std::vector<std::uint8_t>& below = grids_[static_cast<std::size_t>(h - 1)];
    std::vector<std::uint8_t>& level = grids_[static_cast<std::size_t>(h)];
    const auto at = [&](int u, int v) {
      return static_cast<std::size_t>(v) * static_cast<std::size_t>(padded_width_) +
             static_cast<std::size_t>(u);
    };
    for (int v = 0; v < padded_height_; ++v) {
      const bool rows_inside = v + s < padded_height_;
      for (int u = 0; u < padded_width_; ++u) {
        if (rows_inside && u + s < padded_width_) {
          level[at(u, v)] = std::max(std::max(below[at(u, v)], below[at(u + s, v)]),
                                     std::max(below[at(u, v + s)], below[at(u + s, v + s)]));
        } else {
          level[at(u, v)] = std::max({valueAt(h - 1, {u, v}), valueAt(h - 1, {u + s, v}),
                                      valueAt(h - 1, {u, v + s}), valueAt(h - 1, {u + s, v + s})});
        }
      }
    }
  }
}

std::uint8_t FastCorrelativeMatcher::valueAt(int height, const Eigen::Vector2i& padded) const {
  if (padded.x() < 0 || padded.y() < 0 || padded.x() >= padded_width_ ||
      padded.y() >= padded_height_) {
    return 0;
  }
  return grids_[static_cast<std::size_t>(height)]
               [static_cast<std::size_t>(padded.y()) * static_cast<std::size_t>(padded_width_) +
                static_cast<std::size_t>(padded.x())];
}

Eigen::Vector2i FastCorrelativeMatcher::paddedCellOf(const Eigen::Vector2d& point_submap) const {
  const auto lattice = [this](double metres) {
    return static_cast<int>(std::clamp(std::floor(metres / resolution_m_), -kFarCell, kFarCell));
  };
  return {lattice(point_submap.x()) - origin_cell_.x() + pad_,
          lattice(point_submap.y()) - origin_cell_.y() + pad_};
}

double FastCorrelativeMatcher::probabilityOf(double mean_value) const {
  return min_probability_ + (max_probability_ - min_probability_) * mean_value / kLevels;
}

double FastCorrelativeMatcher::precomputed(int height, const Eigen::Vector2i& cell) const {
  if (height < 0 || height >= depth()) {
    throw std::out_of_range("fast correlative matcher: no such height");
  }
  return probabilityOf(valueAt(height, cell + Eigen::Vector2i::Constant(pad_)));
}

std::size_t FastCorrelativeMatcher::memoryBytes() const {
  std::size_t bytes = 0;
  for (const std::vector<std::uint8_t>& level : grids_) {
    bytes += level.size() * sizeof(std::uint8_t);
  }
  return bytes;
}

double FastCorrelativeMatcher::score(const SE2& T_submap_robot,
                                     const std::vector<Eigen::Vector2d>& points_robot) const {
  if (points_robot.empty()) {
    return min_probability_;
  }
  std::int64_t sum = 0;
  for (const Eigen::Vector2d& point : points_robot) {
    sum += valueAt(0, paddedCellOf(T_submap_robot * point));
  }
  return probabilityOf(static_cast<double>(sum) / static_cast<double>(points_robot.size()));
}

// The largest sum whose mean probability is ≤ min_score (-1 when none is): a candidate must beat
// it.
std::int64_t FastCorrelativeMatcher::sumThreshold(double min_score, std::size_t point_count) const {
  const auto count = static_cast<double>(point_count);
  const auto top = static_cast<std::int64_t>(kLevels * count);
  const auto mean = [&](std::int64_t sum) {
    return probabilityOf(static_cast<double>(sum) / count);
  };
  const double estimate =
      (min_score - min_probability_) / (max_probability_ - min_probability_) * kLevels * count;
  std::int64_t sum =
      static_cast<std::int64_t>(std::floor(std::clamp(estimate, -1.0, static_cast<double>(top))));
  while (sum < top && mean(sum + 1) <= min_score) {
    ++sum;
  }
  while (sum >= 0 && mean(sum) > min_score) {
    --sum;
  }
  return sum;
}

std::int64_t FastCorrelativeMatcher::boundOf(const Search& search, const Candidate& candidate,
                                             int height) const {
  const auto rotation = static_cast<std::size_t>(candidate.rotation);
  const Eigen::Vector2i shift(candidate.jx, candidate.jy);
  const Eigen::Vector2i low = search.low[rotation] + shift;
  const Eigen::Vector2i high = search.high[rotation] + shift;
  std::int64_t sum = 0;
  if (low.x() >= 0 && low.y() >= 0 && high.x() < padded_width_ && high.y() < padded_height_) {
    // Every cell inside the grid: no bounds check per point.
    const std::uint8_t* base = grids_[static_cast<std::size_t>(height)].data() +
                               static_cast<std::ptrdiff_t>(shift.y()) * padded_width_ + shift.x();
    for (const std::ptrdiff_t offset : search.offsets[rotation]) {
      sum += base[offset];
    }
    return sum;
  }
  for (const Eigen::Vector2i& cell : search.cells[rotation]) {
    sum += valueAt(height, cell + shift);
  }
  return sum;
}

void FastCorrelativeMatcher::scoreAndSort(const Search& search, Candidate* candidates,
                                          std::size_t count, int height) const {
  for (std::size_t i = 0; i < count; ++i) {
    candidates[i].sum = boundOf(search, candidates[i], height);
  }
  // Insertion sort, best first: a split has at most four children; the first line is sorted once.
  for (std::size_t i = 1; i < count; ++i) {
    const Candidate moving = candidates[i];
    std::size_t j = i;
    for (; j > 0 && candidates[j - 1].sum < moving.sum; --j) {
      candidates[j] = candidates[j - 1];
    }
    candidates[j] = moving;
  }
}

// Step 4, first line: the top-height candidates tiling the window, for every rotation.
std::vector<FastCorrelativeMatcher::Candidate> FastCorrelativeMatcher::initialCandidates(
    const Search& search) const {
  const int stride = 1 << (depth() - 1);
  std::vector<Candidate> candidates;
  for (int rotation = 0; rotation < static_cast<int>(search.rotations.size()); ++rotation) {
    for (int jy = -search.wy; jy <= search.wy; jy += stride) {
      for (int jx = -search.wx; jx <= search.wx; jx += stride) {
        candidates.push_back(Candidate{rotation, jx, jy, 0});
      }
    }
  }
  for (Candidate& candidate : candidates) {
    candidate.sum = boundOf(search, candidate, depth() - 1);
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.sum > b.sum; });
  return candidates;
}

// Step 4: candidates sorted best first; `best` holds the score to beat.
void FastCorrelativeMatcher::descend(const Search& search, Candidate* candidates, std::size_t count,
                                     int height, Candidate* best) const {
  for (std::size_t i = 0; i < count; ++i) {
    const Candidate& candidate = candidates[i];
    if (candidate.sum <= best->sum) {
      return;  // this and every later bound cannot beat the best
    }
    if (height == 0) {
      *best = candidate;  // the later ones score no more
      return;
    }
    const int half = 1 << (height - 1);
    std::array<Candidate, 4> children;
    std::size_t child_count = 0;
    for (int dy = 0; dy <= half; dy += half) {
      for (int dx = 0; dx <= half; dx += half) {
        if (candidate.jx + dx <= search.wx && candidate.jy + dy <= search.wy) {
          children[child_count++] =
              Candidate{candidate.rotation, candidate.jx + dx, candidate.jy + dy, 0};
        }
      }
    }
    scoreAndSort(search, children.data(), child_count, height - 1);
    descend(search, children.data(), child_count, height - 1, best);
  }
}

std::optional<FastMatch> FastCorrelativeMatcher::search(
    const SE2& T_submap_centre, int window_cells_x, int window_cells_y, double angular_window_rad,
    const std::vector<Eigen::Vector2d>& points_robot, double min_score) const {
  if (points_robot.empty()) {
    return std::nullopt;
  }
  Search search;
  search.T_submap_centre = T_submap_centre;
  search.wx = window_cells_x;
  search.wy = window_cells_y;
  search.rotations =
      rotationOffsets(angular_window_rad, angularSearchStep(resolution_m_, points_robot));
  for (const double dtheta : search.rotations) {  // step 3
    const SE2 T_submap_rotated(T_submap_centre.x(), T_submap_centre.y(),
                               T_submap_centre.theta() + dtheta);
    std::vector<Eigen::Vector2i>& cells = search.cells.emplace_back();
    std::vector<std::ptrdiff_t>& offsets = search.offsets.emplace_back();
    cells.reserve(points_robot.size());
    offsets.reserve(points_robot.size());
    Eigen::Vector2i low = Eigen::Vector2i::Constant(std::numeric_limits<int>::max());
    Eigen::Vector2i high = Eigen::Vector2i::Constant(std::numeric_limits<int>::min());
    const Eigen::Matrix2d R = T_submap_rotated.rotation();
    const Eigen::Vector2d t = T_submap_rotated.translation();
    for (const Eigen::Vector2d& point : points_robot) {
      const Eigen::Vector2i cell = paddedCellOf(R * point + t);
      cells.push_back(cell);
      offsets.push_back(static_cast<std::ptrdiff_t>(cell.y()) * padded_width_ + cell.x());
      low = low.cwiseMin(cell);
      high = high.cwiseMax(cell);
    }
    search.low.push_back(low);
    search.high.push_back(high);
  }
  Candidate best;
  best.sum = sumThreshold(min_score, points_robot.size());
  std::vector<Candidate> candidates = initialCandidates(search);
  descend(search, candidates.data(), candidates.size(), depth() - 1, &best);
  if (best.rotation < 0) {
    return std::nullopt;
  }
  const double r = resolution_m_;
  const SE2 T_submap_robot(
      T_submap_centre.x() + best.jx * r, T_submap_centre.y() + best.jy * r,
      T_submap_centre.theta() + search.rotations[static_cast<std::size_t>(best.rotation)]);
  const double mean = static_cast<double>(best.sum) / static_cast<double>(points_robot.size());
  return FastMatch{T_submap_robot, probabilityOf(mean)};
}

std::optional<FastMatch> FastCorrelativeMatcher::match(
    const SE2& T_submap_robot_guess, const std::vector<Eigen::Vector2d>& points_robot,
    double min_score) const {
  return match(T_submap_robot_guess, points_robot, min_score, settings_.linear_search_window_m,
               settings_.angular_search_window_rad);
}

std::optional<FastMatch> FastCorrelativeMatcher::match(
    const SE2& T_submap_robot_guess, const std::vector<Eigen::Vector2d>& points_robot,
    double min_score, double linear_window_m, double angular_window_rad) const {
  if (!std::isfinite(linear_window_m) || linear_window_m < 0.0 ||
      !std::isfinite(angular_window_rad) || angular_window_rad < 0.0) {
    throw std::invalid_argument("fast correlative matcher: windows must be finite and >= 0");
  }
  const int w = stepsIn(linear_window_m, resolution_m_);
  return search(T_submap_robot_guess, w, w, angular_window_rad, points_robot, min_score);
}

// The window's centre is the grid's; ±(half the grid + 1 cell) covers every cell of it.
std::optional<FastMatch> FastCorrelativeMatcher::matchFullSubmap(
    const std::vector<Eigen::Vector2d>& points_robot, double min_score) const {
  const Eigen::Vector2d centre =
      (origin_cell_.cast<double>() +
       0.5 * Eigen::Vector2d(static_cast<double>(width_), static_cast<double>(height_))) *
      resolution_m_;
  return search(SE2(centre.x(), centre.y(), 0.0), width_ / 2 + 1, height_ / 2 + 1, M_PI,
                points_robot, min_score);
}

}  // namespace mrslam::robot::slam
