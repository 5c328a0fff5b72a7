#pragma once
// A submap's probability grid (Hess et al., ICRA 2016, section IV): each cell holds the
// probability that it is occupied, or is unknown. A scan updates its end-point cells as hits and
// the cells its beams cross as misses, each cell at most once per scan, by the odds rule
//   odds(M_new(x)) = clamp(odds(M_old(x)) · odds(p_hit or p_miss)),  odds(p) = p / (1 − p).
// The grid grows as the robot explores. Cells sit on a lattice of the submap frame: cell (i, j)
// covers [i·r, (i+1)·r) × [j·r, (j+1)·r) of the lattice, offset by the grid's origin cell.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace mrslam::robot::slam {

struct ProbabilityGridSettings {
  double resolution_m = 0.05;      ///< cell size
  double hit_probability = 0.55;   ///< p_hit of a beam's end cell
  double miss_probability = 0.49;  ///< p_miss of a cell a beam crosses
  double min_probability = 0.1;    ///< clamp: keeps a cell able to change
  double max_probability = 0.9;
};

class ProbabilityGrid {
 public:
  /// Throws std::invalid_argument when the settings are out of range (resolution ≤ 0,
  /// probabilities outside (0, 1), p_hit ≤ 0.5, p_miss ≥ 0.5, min ≥ max).
  explicit ProbabilityGrid(const ProbabilityGridSettings& settings);

  const ProbabilityGridSettings& settings() const { return settings_; }
  double resolution() const { return settings_.resolution_m; }
  int width() const { return width_; }
  int height() const { return height_; }
  /// Lattice index of grid cell (0, 0).
  const Eigen::Vector2i& originCell() const { return origin_cell_; }

  /// Grid cell holding a submap-frame point (may lie outside the grid).
  Eigen::Vector2i cellOf(const Eigen::Vector2d& point_m) const;
  /// Submap-frame centre of a grid cell.
  Eigen::Vector2d centreOf(const Eigen::Vector2i& cell) const;
  bool contains(const Eigen::Vector2i& cell) const {
    return cell.x() >= 0 && cell.y() >= 0 && cell.x() < width_ && cell.y() < height_;
  }

  /// Occupancy probability of a cell; `unknown` where it was never observed or lies outside.
  float probability(const Eigen::Vector2i& cell, float unknown = 0.5f) const {
    if (!contains(cell)) {
      return unknown;
    }
    const float p = probability_[index(cell)];
    return p > 0.0f ? p : unknown;
  }
  bool isKnown(const Eigen::Vector2i& cell) const {
    return contains(cell) && probability_[index(cell)] > 0.0f;
  }
  std::size_t knownCellCount() const;

  /// Inserts one scan seen from `origin_m`: `hits` are end points on obstacles, `misses` are ends
  /// of beams that saw nothing within range (they only clear the cells up to them). All in the
  /// submap frame. Each cell changes at most once per call; a hit wins over a miss. Non-finite
  /// points (and a non-finite origin) are left out: range data never holds them. Throws
  /// std::out_of_range for points beyond ±1e7 m.
  void insertScan(const Eigen::Vector2d& origin_m, const std::vector<Eigen::Vector2d>& hits,
                  const std::vector<Eigen::Vector2d>& misses);

  /// Grows the grid so the box [min_m, max_m] lies inside it (existing cells keep their
  /// lattice places). Throws std::out_of_range for non-finite corners.
  void ensureContains(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m);

  /// Crops the grid to the smallest box holding every known cell (cells keep their lattice
  /// places; an empty grid becomes 0 × 0) and frees the per-scan marks: a finished submap's
  /// memory. Later insertions still work.
  void shrinkToKnown();

  /// Row-major probabilities (0 = unknown), width() × height(), row y = cell y.
  const std::vector<float>& cells() const { return probability_; }

 private:
  std::size_t index(const Eigen::Vector2i& cell) const {
    return static_cast<std::size_t>(cell.y()) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(cell.x());
  }
  void ensureMarks();
  void update(const Eigen::Vector2i& cell, float odds_factor);
  void traceMisses(const Eigen::Vector2i& from, const Eigen::Vector2i& to, bool include_end);

  ProbabilityGridSettings settings_;
  float hit_odds_;
  float miss_odds_;
  int width_ = 0;
  int height_ = 0;
  Eigen::Vector2i origin_cell_{0, 0};
  std::vector<float> probability_;
  std::vector<std::uint32_t> touched_;  ///< scan number that last changed each cell
  std::uint32_t scan_number_ = 0;
};

}  // namespace mrslam::robot::slam
