#include "mrslam/robot/slam/probability_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mrslam::robot::slam {

namespace {

float oddsOf(double p) {
  return static_cast<float>(p / (1.0 - p));
}

bool isProbability(double p) {
  return p > 0.0 && p < 1.0;
}

void check(const ProbabilityGridSettings& s) {
  if (!(s.resolution_m > 0.0) || !std::isfinite(s.resolution_m)) {
    throw std::invalid_argument("probability grid: resolution must be > 0");
  }
  if (!isProbability(s.hit_probability) || !isProbability(s.miss_probability) ||
      !isProbability(s.min_probability) || !isProbability(s.max_probability)) {
    throw std::invalid_argument("probability grid: probabilities must lie in (0, 1)");
  }
  if (s.hit_probability <= 0.5 || s.miss_probability >= 0.5) {
    throw std::invalid_argument("probability grid: hit must be > 0.5 and miss < 0.5");
  }
  if (s.min_probability >= s.max_probability) {
    throw std::invalid_argument("probability grid: min_probability must be < max_probability");
  }
}

// Grows a span [low, high) of cells by whole chunks so it covers [want_low, want_high].
constexpr int kMinChunkCells = 32;

}  // namespace

ProbabilityGrid::ProbabilityGrid(const ProbabilityGridSettings& settings)
    : settings_(settings),
      hit_odds_(oddsOf(settings.hit_probability)),
      miss_odds_(oddsOf(settings.miss_probability)) {
  check(settings_);
}

Eigen::Vector2i ProbabilityGrid::cellOf(const Eigen::Vector2d& point_m) const {
  const double r = settings_.resolution_m;
  return Eigen::Vector2i(static_cast<int>(std::floor(point_m.x() / r)),
                         static_cast<int>(std::floor(point_m.y() / r))) -
         origin_cell_;
}

Eigen::Vector2d ProbabilityGrid::centreOf(const Eigen::Vector2i& cell) const {
  const Eigen::Vector2i lattice = cell + origin_cell_;
  return (lattice.cast<double>() + Eigen::Vector2d::Constant(0.5)) * settings_.resolution_m;
}

std::size_t ProbabilityGrid::knownCellCount() const {
  return static_cast<std::size_t>(
      std::count_if(probability_.begin(), probability_.end(), [](float p) { return p > 0.0f; }));
}

void ProbabilityGrid::shrinkToKnown() {
  Eigen::Vector2i low(width_, height_);
  Eigen::Vector2i high(-1, -1);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      if (probability_[index({x, y})] > 0.0f) {
        low = low.cwiseMin(Eigen::Vector2i(x, y));
        high = high.cwiseMax(Eigen::Vector2i(x, y));
      }
    }
  }
  std::vector<std::uint32_t>().swap(touched_);
  if (high.x() < 0) {
    std::vector<float>().swap(probability_);
    width_ = 0;
    height_ = 0;
    return;
  }
  const int new_width = high.x() - low.x() + 1;
  const int new_height = high.y() - low.y() + 1;
  std::vector<float> probability(static_cast<std::size_t>(new_width) * new_height);
  for (int y = 0; y < new_height; ++y) {
    std::copy_n(probability_.begin() + static_cast<std::ptrdiff_t>(index({low.x(), low.y() + y})),
                new_width, probability.begin() + static_cast<std::ptrdiff_t>(y) * new_width);
  }
  probability_.swap(probability);
  width_ = new_width;
  height_ = new_height;
  origin_cell_ += low;
}

void ProbabilityGrid::ensureMarks() {
  if (touched_.size() != probability_.size()) {
    touched_.assign(probability_.size(), 0);  // after shrinkToKnown: no cell marked this scan
  }
}

void ProbabilityGrid::ensureContains(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m) {
  if (!min_m.allFinite() || !max_m.allFinite()) {
    throw std::out_of_range("probability grid: non-finite extent");
  }
  constexpr double kMaxCoordinate = 1e7;  // cells beyond ±1e7 m are a broken pose, not a map
  if (min_m.cwiseAbs().maxCoeff() > kMaxCoordinate ||
      max_m.cwiseAbs().maxCoeff() > kMaxCoordinate) {
    throw std::out_of_range("probability grid: extent beyond 1e7 m");
  }
  const double r = settings_.resolution_m;
  const Eigen::Vector2i want_low(static_cast<int>(std::floor(min_m.x() / r)),
                                 static_cast<int>(std::floor(min_m.y() / r)));
  const Eigen::Vector2i want_high(static_cast<int>(std::floor(max_m.x() / r)),
                                  static_cast<int>(std::floor(max_m.y() / r)));
  if (width_ > 0) {
    const Eigen::Vector2i low = origin_cell_;
    const Eigen::Vector2i high = origin_cell_ + Eigen::Vector2i(width_ - 1, height_ - 1);
    if ((want_low.array() >= low.array()).all() && (want_high.array() <= high.array()).all()) {
      return;
    }
  }
  Eigen::Vector2i new_low = want_low;
  Eigen::Vector2i new_high = want_high;
  if (width_ > 0) {
    const Eigen::Vector2i low = origin_cell_;
    const Eigen::Vector2i high = origin_cell_ + Eigen::Vector2i(width_ - 1, height_ - 1);
    const Eigen::Vector2i chunk = Eigen::Vector2i(std::max(kMinChunkCells, width_ / 2),
                                                  std::max(kMinChunkCells, height_ / 2));
    for (int axis = 0; axis < 2; ++axis) {
      new_low[axis] = want_low[axis] < low[axis] ? std::min(want_low[axis], low[axis] - chunk[axis])
                                                 : low[axis];
      new_high[axis] = want_high[axis] > high[axis]
                           ? std::max(want_high[axis], high[axis] + chunk[axis])
                           : high[axis];
    }
  } else {
    new_low.array() -= kMinChunkCells;
    new_high.array() += kMinChunkCells;
  }
  ensureMarks();
  const int new_width = new_high.x() - new_low.x() + 1;
  const int new_height = new_high.y() - new_low.y() + 1;
  std::vector<float> probability(static_cast<std::size_t>(new_width) * new_height, 0.0f);
  std::vector<std::uint32_t> touched(probability.size(), 0);
  const Eigen::Vector2i shift = origin_cell_ - new_low;
  for (int y = 0; y < height_; ++y) {
    const std::size_t from = static_cast<std::size_t>(y) * width_;
    const std::size_t to = static_cast<std::size_t>(y + shift.y()) * new_width + shift.x();
    std::copy_n(probability_.begin() + from, width_, probability.begin() + to);
    std::copy_n(touched_.begin() + from, width_, touched.begin() + to);
  }
  probability_.swap(probability);
  touched_.swap(touched);
  width_ = new_width;
  height_ = new_height;
  origin_cell_ = new_low;
}

void ProbabilityGrid::update(const Eigen::Vector2i& cell, float odds_factor) {
  const std::size_t i = index(cell);
  if (touched_[i] == scan_number_) {
    return;
  }
  touched_[i] = scan_number_;
  const float p = probability_[i];
  const float odds = (p > 0.0f ? p / (1.0f - p) : 1.0f) * odds_factor;
  const float updated = odds / (1.0f + odds);
  probability_[i] = std::clamp(updated, static_cast<float>(settings_.min_probability),
                               static_cast<float>(settings_.max_probability));
}

// Cells from `from` towards `to` on a Bresenham line, each updated as a miss; `to` itself only
// when include_end.
void ProbabilityGrid::traceMisses(const Eigen::Vector2i& from, const Eigen::Vector2i& to,
                                  bool include_end) {
  int x = from.x();
  int y = from.y();
  const int dx = std::abs(to.x() - x);
  const int dy = -std::abs(to.y() - y);
  const int sx = x < to.x() ? 1 : -1;
  const int sy = y < to.y() ? 1 : -1;
  int error = dx + dy;
  while (x != to.x() || y != to.y()) {
    update({x, y}, miss_odds_);
    const int twice = 2 * error;
    if (twice >= dy) {
      error += dy;
      x += sx;
    }
    if (twice <= dx) {
      error += dx;
      y += sy;
    }
  }
  if (include_end) {
    update(to, miss_odds_);
  }
}

void ProbabilityGrid::insertScan(const Eigen::Vector2d& origin_m,
                                 const std::vector<Eigen::Vector2d>& hits,
                                 const std::vector<Eigen::Vector2d>& misses) {
  if (!origin_m.allFinite()) {
    return;
  }
  Eigen::Vector2d low = origin_m;
  Eigen::Vector2d high = origin_m;
  for (const auto* points : {&hits, &misses}) {
    for (const Eigen::Vector2d& p : *points) {
      if (p.allFinite()) {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
      }
    }
  }
  ensureContains(low, high);
  ensureMarks();
  ++scan_number_;
  if (scan_number_ == 0) {  // wrapped: forget the old marks so none equals the new number
    std::fill(touched_.begin(), touched_.end(), 0);
    scan_number_ = 1;
  }
  const Eigen::Vector2i origin_cell = cellOf(origin_m);
  for (const Eigen::Vector2d& hit : hits) {
    if (hit.allFinite()) {
      update(cellOf(hit), hit_odds_);
    }
  }
  for (const Eigen::Vector2d& hit : hits) {
    if (hit.allFinite()) {
      traceMisses(origin_cell, cellOf(hit), false);
    }
  }
  for (const Eigen::Vector2d& miss : misses) {
    if (miss.allFinite()) {
      traceMisses(origin_cell, cellOf(miss), true);
    }
  }
}

}  // namespace mrslam::robot::slam
