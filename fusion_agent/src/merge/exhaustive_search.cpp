#include "mrslam/fusion/merge/exhaustive_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "exhaustive_grids.hpp"
#include "mrslam/fusion/merge/edges.hpp"
#include "mrslam/fusion/merge/radon.hpp"

namespace mrslam::fusion {

namespace {

using exhaustive::freeValueGrid;
using exhaustive::GridClass;
using exhaustive::PointSet;
using exhaustive::pointSet;
using exhaustive::SearchGrid;
using exhaustive::toSearchGrid;
using exhaustive::valueGrid;
using exhaustive::ValuePyramid;
using exhaustive::valuePyramid;

/// Points turned by one angle as offsets into the pyramid's rows, in memory order, so that the
/// points on a range of rows are a range of the offsets: every |column offset| is below half the
/// stride (the pad exceeds the points' radius). `row_starts[k]` is the index of the first point
/// on a row at or above `first_row + k` (the last entry: the count), so that a range of rows is
/// found without a search.
struct TurnedPoints {
  std::vector<std::ptrdiff_t> offsets;
  std::ptrdiff_t first_row = 0;
  std::vector<std::size_t> row_starts;

  /// The offsets of the points whose row offset lies within [first, last].
  std::pair<const std::ptrdiff_t*, const std::ptrdiff_t*> onRows(std::ptrdiff_t first,
                                                                 std::ptrdiff_t last) const {
    const auto start = [this](std::ptrdiff_t row) {
      const std::ptrdiff_t k = std::clamp<std::ptrdiff_t>(
          row - first_row, 0, static_cast<std::ptrdiff_t>(row_starts.size()) - 1);
      return row_starts[static_cast<std::size_t>(k)];
    };
    const std::size_t begin = start(first);
    const std::size_t end = std::max(begin, start(last + 1));
    return {offsets.data() + begin, offsets.data() + end};
  }
  std::pair<const std::ptrdiff_t*, const std::ptrdiff_t*> all() const {
    return {offsets.data(), offsets.data() + offsets.size()};
  }
};

/// Step 3: one rotation's turned points (turnedPoints).
struct Rotation {
  double theta = 0.0;
  TurnedPoints walls;
  TurnedPoints free;
};

/// Fills `turned.first_row` and `turned.row_starts` from its sorted offsets.
void indexRows(std::ptrdiff_t stride, TurnedPoints& turned) {
  // The row of an offset y · stride + x with |x| < stride / 2, rounded down.
  const std::ptrdiff_t half = stride / 2;
  const auto rowOf = [&](std::ptrdiff_t offset) {
    const std::ptrdiff_t shifted = offset + half;
    return shifted >= 0 ? shifted / stride : -((-shifted + stride - 1) / stride);
  };
  if (turned.offsets.empty()) {
    turned.row_starts = {0};
    return;
  }
  turned.first_row = rowOf(turned.offsets.front());
  const std::ptrdiff_t last_row = rowOf(turned.offsets.back());
  // The rows rise with the sorted offsets: one walk along them finds each row's start.
  std::size_t i = 0;
  for (std::ptrdiff_t row = turned.first_row; row <= last_row + 1; ++row) {
    while (i < turned.offsets.size() && rowOf(turned.offsets[i]) < row) {
      ++i;
    }
    turned.row_starts.push_back(i);
  }
}

TurnedPoints turnedPoints(const std::vector<Eigen::Vector2d>& points, double theta, int stride) {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  TurnedPoints turned;
  turned.offsets.reserve(points.size());
  for (const Eigen::Vector2d& p : points) {
    const std::ptrdiff_t x = roundToInt(c * p.x() - s * p.y());
    const std::ptrdiff_t y = roundToInt(s * p.x() + c * p.y());
    turned.offsets.push_back(y * stride + x);
  }
  std::sort(turned.offsets.begin(), turned.offsets.end());
  indexRows(stride, turned);
  return turned;
}

/// Whether `theta` lies within `window` of one of `turns` (always, when there are none).
bool nearAny(double theta, const std::vector<double>& turns, double window) {
  return turns.empty() || std::any_of(turns.begin(), turns.end(), [&](double turn) {
           return std::abs(std::remainder(theta - turn, 2.0 * M_PI)) <= window;
         });
}

/// The rotations θ_k of the full turn, those near `turns` only when it holds any.
std::vector<Rotation> rotations(const PointSet& set, int stride, double step_cells,
                                const std::vector<double>& turns, double window) {
  const double step = set.radius > step_cells ? step_cells / set.radius : M_PI / 2.0;
  const int count = std::max(4, static_cast<int>(std::ceil(2.0 * M_PI / step)));
  std::vector<Rotation> kept;
  for (int k = 0; k < count; ++k) {
    Rotation rotation;
    rotation.theta = 2.0 * M_PI * k / count;
    if (!nearAny(rotation.theta, turns, window)) {
      continue;
    }
    rotation.walls = turnedPoints(set.walls, rotation.theta, stride);
    rotation.free = turnedPoints(set.free, rotation.theta, stride);
    kept.push_back(std::move(rotation));
  }
  return kept;
}

/// A node of the branch and bound: rotation, the low corner of its translations (grid cells of
/// `to`, where `from`'s centroid lands), its level and bound.
struct Node {
  int rotation = 0;
  int tx = 0;
  int ty = 0;
  int level = 0;
  double bound = 0.0;
};

/// The best distinct leaves found so far, best first (step 5).
class KeptLeaves {
 public:
  KeptLeaves(const ExhaustiveSearchSettings& settings, double floor)
      : count_(static_cast<std::size_t>(settings.search_hypotheses)),
        cells_(settings.distinct_cells),
        rad_(settings.distinct_deg * M_PI / 180.0),
        floor_(floor),
        best_share_(settings.min_best_share) {}
  /// The score a leaf must beat: the last kept one's when all are found, and never less than
  /// the floor or min_best_share of the best.
  double threshold() const {
    return kept_.size() < count_ ? floor() : std::max(floor(), kept_.back().score);
  }
  /// `place`: where `from`'s centroid lands in `to`, map cells.
  void offer(const ExhaustiveHypothesis& leaf, const Eigen::Vector2d& place);
  std::vector<ExhaustiveHypothesis> best() const {
    std::vector<ExhaustiveHypothesis> result;
    for (const Entry& entry : kept_) {
      result.push_back(entry.hypothesis);
    }
    return result;
  }

 private:
  struct Entry {
    ExhaustiveHypothesis hypothesis;
    Eigen::Vector2d place;
    double score = 0.0;
  };
  double floor() const {
    return kept_.empty() ? floor_ : std::max(floor_, best_share_ * kept_.front().score);
  }
  bool alike(const Entry& entry, const ExhaustiveHypothesis& leaf,
             const Eigen::Vector2d& place) const {
    return std::abs(std::remainder(entry.hypothesis.T_to_from.theta_rad - leaf.T_to_from.theta_rad,
                                   2.0 * M_PI)) < rad_ &&
           (entry.place - place).norm() < cells_;
  }
  std::size_t count_;
  double cells_;
  double rad_;
  double floor_;
  double best_share_;
  std::vector<Entry> kept_;
};

void KeptLeaves::offer(const ExhaustiveHypothesis& leaf, const Eigen::Vector2d& place) {
  if (leaf.score <= threshold()) {
    return;
  }
  for (const Entry& entry : kept_) {
    if (alike(entry, leaf, place) && entry.score >= leaf.score) {
      return;
    }
  }
  kept_.erase(std::remove_if(kept_.begin(), kept_.end(),
                             [&](const Entry& entry) { return alike(entry, leaf, place); }),
              kept_.end());
  const Entry entry{leaf, place, leaf.score};
  kept_.insert(std::upper_bound(kept_.begin(), kept_.end(), entry,
                                [](const Entry& a, const Entry& b) { return a.score > b.score; }),
               entry);
  while (kept_.size() > count_ || (!kept_.empty() && kept_.back().score <= floor())) {
    kept_.pop_back();
  }
}

/// The most one point can score: a wall on a wall (exp(0)), a free cell on a free cell.
struct PointCaps {
  float wall = 1.0f;
  float free = 0.0f;
};

/// Points summed between two looks at whether the bounds can still beat the threshold.
constexpr std::size_t kBoundChunk = 32;
/// Float sums may round a little above the partial sums' caps: prune only clearly below.
constexpr float kPruneMargin = 1e-3f;

/// A node's bound is the sum of the pyramid's values at its corner plus each point's offset;
/// this sums four corners at once: corner, corner + right, corner + up, corner + right + up
/// (indices into `values`), starting from `sums`. It stops early, returning false, once each of the
/// four sums plus `cap` per point left and `after` is at most `threshold` (`sums` then hold those
/// caps: still upper bounds).
bool sumAtFour(const float* values, std::ptrdiff_t corner, std::ptrdiff_t right, std::ptrdiff_t up,
               std::pair<const std::ptrdiff_t*, const std::ptrdiff_t*> offsets, float cap,
               float after, float threshold, float* sums) {
  float sum0 = sums[0];
  float sum1 = sums[1];
  float sum2 = sums[2];
  float sum3 = sums[3];
  const std::ptrdiff_t* const first = offsets.first;
  const auto count = static_cast<std::size_t>(offsets.second - offsets.first);
  for (std::size_t begin = 0; begin < count; begin += kBoundChunk) {
    const std::size_t end = std::min(count, begin + kBoundChunk);
    for (std::size_t i = begin; i < end; ++i) {
      const float* at = values + (corner + first[i]);
      sum0 += at[0];
      sum1 += at[right];
      sum2 += at[up];
      sum3 += at[up + right];
    }
    const float rest = cap * static_cast<float>(count - end) + after;
    if (std::max({sum0, sum1, sum2, sum3}) + rest < threshold - kPruneMargin) {
      sums[0] = sum0 + rest;
      sums[1] = sum1 + rest;
      sums[2] = sum2 + rest;
      sums[3] = sum3 + rest;
      return false;
    }
  }
  sums[0] = sum0;
  sums[1] = sum1;
  sums[2] = sum2;
  sums[3] = sum3;
  return true;
}

class BranchAndBound {
 public:
  BranchAndBound(const ValuePyramid& pyramid, const std::vector<Rotation>& rotations,
                 const PointSet& set, int cell_size, const PointCaps& caps, bool stop_early,
                 KeptLeaves& kept)
      : pyramid_(pyramid),
        rotations_(rotations),
        set_(set),
        cell_size_(cell_size),
        caps_(caps),
        stop_early_(stop_early),
        kept_(kept) {}

  /// The nodes of `level` (each `top` translations a side) of one rotation whose corners lie in
  /// [x_begin, x_end) × [y_begin, y_end), row by row; their bounds four at a time.
  void addTopNodes(int rotation, int x_begin, int x_end, int y_begin, int y_end, int top, int level,
                   std::vector<Node>& nodes) const {
    const int columns = (x_end - x_begin + top - 1) / top;
    const int rows = (y_end - y_begin + top - 1) / top;
    std::vector<double> bounds(static_cast<std::size_t>((columns + 1) * (rows + 1)));
    for (int row = 0; row < rows; row += 2) {
      for (int column = 0; column < columns; column += 2) {
        double four[4];
        const Node corner{rotation, x_begin + column * top, y_begin + row * top, level + 1, 0.0};
        childBounds(corner, top, kept_.threshold(), four);
        for (int i = 0; i < 4; ++i) {
          bounds[static_cast<std::size_t>((row + (i >> 1)) * (columns + 1) + column + (i & 1))] =
              four[i];
        }
      }
    }
    for (int row = 0; row < rows; ++row) {
      for (int column = 0; column < columns; ++column) {
        nodes.push_back({rotation, x_begin + column * top, y_begin + row * top, level,
                         bounds[static_cast<std::size_t>(row * (columns + 1) + column)]});
      }
    }
  }

  /// The bounds of the four children of `node` (corners tx, tx + half; ty, ty + half), in one
  /// pass over the points. False when each is sure to be at most `threshold`: the pass stopped
  /// early and `bounds` hold upper bounds at most `threshold` (the children would be pruned).
  bool childBounds(const Node& node, int half, double threshold, double* bounds) const {
    const std::ptrdiff_t row = node.ty + pyramid_.row_pad;
    const std::ptrdiff_t corner = row * pyramid_.stride + (node.tx + pyramid_.pad);
    const std::ptrdiff_t up = static_cast<std::ptrdiff_t>(half) * pyramid_.stride;
    const Rotation& turned = rotations_[static_cast<std::size_t>(node.rotation)];
    const auto h = static_cast<std::size_t>(node.level - 1);
    const auto limit =
        stop_early_ ? static_cast<float>(threshold) : -std::numeric_limits<float>::infinity();
    // Only the points whose rows (or rows + half) hold values of level h add anything.
    const std::ptrdiff_t first_row = pyramid_.first_valued_row[h] - row - half;
    const std::ptrdiff_t last_row = pyramid_.last_valued_row - row;
    const auto onRows = [&](const TurnedPoints& points) {
      return stop_early_ ? points.onRows(first_row, last_row) : points.all();
    };
    const auto walls = onRows(turned.walls);
    const auto free = onRows(turned.free);
    const float free_cap = caps_.free * static_cast<float>(free.second - free.first);
    float sums[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const bool open =
        sumAtFour(pyramid_.walls[h].data(), corner, half, up, walls, caps_.wall, free_cap, limit,
                  sums) &&
        sumAtFour(pyramid_.free[h].data(), corner, half, up, free, caps_.free, 0.0f, limit, sums);
    for (int i = 0; i < 4; ++i) {
      bounds[i] = static_cast<double>(sums[i]);
    }
    return open;
  }

  void expand(const Node& node) {
    if (node.bound <= kept_.threshold()) {
      return;
    }
    if (node.level == 0) {
      offerLeaf(node);
      return;
    }
    const int half = 1 << (node.level - 1);
    double bounds[4];
    if (!childBounds(node, half, kept_.threshold(), bounds)) {
      return;  // every child at or below the threshold
    }
    Node children[4];
    for (int i = 0; i < 4; ++i) {
      children[i] = {node.rotation, node.tx + (i & 1) * half, node.ty + (i >> 1) * half,
                     node.level - 1, bounds[i]};
    }
    std::sort(std::begin(children), std::end(children),
              [](const Node& a, const Node& b) { return a.bound > b.bound; });
    for (const Node& child : children) {
      expand(child);
    }
  }

 private:
  /// The map-cell transform of a leaf: grid cell g of `from` lands on R (g - centroid) + t.
  void offerLeaf(const Node& node) {
    const double theta = rotations_[static_cast<std::size_t>(node.rotation)].theta;
    const double c = std::cos(theta);
    const double s = std::sin(theta);
    const double h = 0.5 * (cell_size_ - 1);
    const Eigen::Vector2d anchor = Eigen::Vector2d::Constant(h) + cell_size_ * set_.centroid;
    ExhaustiveHypothesis leaf;
    leaf.T_to_from.theta_rad = std::remainder(theta, 2.0 * M_PI);
    const Eigen::Vector2d place =
        cell_size_ * Eigen::Vector2d(node.tx, node.ty) + Eigen::Vector2d::Constant(h);
    leaf.T_to_from.t_cells =
        place - Eigen::Vector2d(c * anchor.x() - s * anchor.y(), s * anchor.x() + c * anchor.y());
    leaf.score = node.bound;
    kept_.offer(leaf, place);
  }

  const ValuePyramid& pyramid_;
  const std::vector<Rotation>& rotations_;
  const PointSet& set_;
  int cell_size_;
  PointCaps caps_;
  bool stop_early_;
  KeptLeaves& kept_;
};

/// The best score over turns of T_to_from about `pivot` within ±`turn` (in `steps` steps a side)
/// and shifts within ±`shift` cells (T_to_from itself when none scores more). `score_turn(θ)`
/// gives the score of the turn θ at a translation (a callable of t_cells): what a turn's shifts
/// share is computed once.
template <typename ScoreTurn>
ExhaustiveHypothesis bestNear(const ScoreTurn& score_turn, const GridTransform& T_to_from,
                              const Eigen::Vector2d& pivot, double turn, int steps, int shift) {
  ExhaustiveHypothesis best{T_to_from, score_turn(T_to_from.theta_rad)(T_to_from.t_cells)};
  const Eigen::Vector2d landed = T_to_from.apply(pivot);
  for (int k = -steps; k <= steps; ++k) {
    GridTransform turned;
    turned.theta_rad = T_to_from.theta_rad + turn * k / std::max(1, steps);
    const double c = std::cos(turned.theta_rad);
    const double s = std::sin(turned.theta_rad);
    const Eigen::Vector2d base =
        landed - Eigen::Vector2d(c * pivot.x() - s * pivot.y(), s * pivot.x() + c * pivot.y());
    const auto score_at = score_turn(turned.theta_rad);
    for (int dy = -shift; dy <= shift; ++dy) {
      for (int dx = -shift; dx <= shift; ++dx) {
        turned.t_cells = base + Eigen::Vector2d(dx, dy);
        const double value = score_at(turned.t_cells);
        if (value > best.score) {
          best = {turned, value};
        }
      }
    }
  }
  best.T_to_from.theta_rad = std::remainder(best.T_to_from.theta_rad, 2.0 * M_PI);
  return best;
}

/// Step 6: the score at full resolution (one grid cell a map cell, σ, reach and margin scaled
/// alike), for the last steps of a hypothesis.
class FineScorer {
 public:
  /// `from` and `to` on grids of one map cell (toSearchGrid with cell size 1).
  FineScorer(const SearchGrid& from, const SearchGrid& to, const ExhaustiveSearchSettings& settings)
      : grid_to_(to) {
    ExhaustiveSearchSettings fine = settings;
    const int cell_size = std::max(1, settings.cell_size);
    fine.cell_size = 1;
    fine.wall_sigma *= cell_size;
    fine.wall_reach *= cell_size;
    fine.free_margin = std::max(1, settings.free_margin * cell_size);
    walls_ = valueGrid(grid_to_, 0, 0, grid_to_.width, grid_to_.height, fine);
    free_ = freeValueGrid(grid_to_, 0, 0, grid_to_.width, grid_to_.height, fine);
    points_ = pointSet(from, fine);
  }

  /// `from`'s points (grid cells of `from`) turned by one angle about `from`'s origin: the score
  /// of that turn at any translation.
  class Turned {
   public:
    Turned(const FineScorer& scorer, double theta_rad)
        : scorer_(scorer),
          walls_(turn(scorer.points_.walls, scorer.points_.centroid, theta_rad)),
          free_(turn(scorer.points_.free, scorer.points_.centroid, theta_rad)) {}
    double operator()(const Eigen::Vector2d& t_cells) const {
      return scorer_.sum(walls_, t_cells, scorer_.walls_) +
             scorer_.sum(free_, t_cells, scorer_.free_);
    }

   private:
    static std::vector<Eigen::Vector2d> turn(const std::vector<Eigen::Vector2d>& points,
                                             const Eigen::Vector2d& centroid, double theta_rad) {
      const double c = std::cos(theta_rad);
      const double s = std::sin(theta_rad);
      std::vector<Eigen::Vector2d> turned;
      turned.reserve(points.size());
      for (const Eigen::Vector2d& point : points) {
        const Eigen::Vector2d p = point + centroid;
        turned.emplace_back(c * p.x() - s * p.y(), s * p.x() + c * p.y());
      }
      return turned;
    }
    const FineScorer& scorer_;
    std::vector<Eigen::Vector2d> walls_;
    std::vector<Eigen::Vector2d> free_;
  };

  double score(const GridTransform& T_to_from) const {
    return Turned(*this, T_to_from.theta_rad)(T_to_from.t_cells);
  }

  /// The best score over turns within ±`turn` (in `steps` steps a side) about `from`'s walls'
  /// centroid and shifts within ±`shift` cells.
  ExhaustiveHypothesis refine(const GridTransform& T_to_from, double turn, int steps,
                              int shift) const {
    return bestNear([this](double theta_rad) { return Turned(*this, theta_rad); }, T_to_from,
                    points_.centroid, turn, steps, shift);
  }
  const Eigen::Vector2d& pivot() const { return points_.centroid; }

 private:
  /// The values at the turned points moved by t_cells (each rounded to its cell), summed.
  double sum(const std::vector<Eigen::Vector2d>& turned, const Eigen::Vector2d& t_cells,
             const exhaustive::LevelValues& values) const {
    double total = 0.0;
    for (const Eigen::Vector2d& point : turned) {
      const int x = roundToInt(point.x() + t_cells.x());
      const int y = roundToInt(point.y() + t_cells.y());
      if (x >= 0 && y >= 0 && x < grid_to_.width && y < grid_to_.height) {
        total += values[static_cast<std::size_t>(y) * grid_to_.width + static_cast<std::size_t>(x)];
      }
    }
    return total;
  }

  SearchGrid grid_to_;
  exhaustive::LevelValues walls_;
  exhaustive::LevelValues free_;
  PointSet points_;
};

/// Step 6 for every hypothesis, best first again.
std::vector<ExhaustiveHypothesis> refined(const std::vector<ExhaustiveHypothesis>& leaves,
                                          const FineScorer& scorer, double rotation_step,
                                          int cell_size) {
  std::vector<ExhaustiveHypothesis> result;
  for (const ExhaustiveHypothesis& leaf : leaves) {
    const ExhaustiveHypothesis coarse = scorer.refine(leaf.T_to_from, rotation_step, 4, cell_size);
    result.push_back(scorer.refine(coarse.T_to_from, 0.25 * rotation_step, 2, 1));
  }
  std::stable_sort(result.begin(), result.end(),
                   [](const ExhaustiveHypothesis& a, const ExhaustiveHypothesis& b) {
                     return a.score > b.score;
                   });
  return result;
}

/// Steps 1-6 one way: the B&B's best distinct leaves of `from` onto `to` (both on grids of
/// settings.cell_size), refined by `fine` (the full-resolution score of `from` onto `to`).
std::vector<ExhaustiveHypothesis> searchOneWay(const SearchGrid& grid_from,
                                               const SearchGrid& grid_to, const FineScorer& fine,
                                               const ExhaustiveSearchSettings& settings,
                                               const std::vector<double>& turns) {
  const int cell_size = std::max(1, settings.cell_size);
  const PointSet set = pointSet(grid_from, settings);
  if (set.walls.empty() || std::none_of(grid_to.classes.begin(), grid_to.classes.end(),
                                        [](GridClass cell) { return cell == GridClass::kWall; })) {
    return {};
  }
  const int reach = static_cast<int>(std::ceil(set.radius)) + 1;
  const int top = 1 << settings.depth;
  const ValuePyramid pyramid = valuePyramid(grid_to, 2 * reach + top + 1, settings);
  const std::vector<Rotation> turned =
      rotations(set, pyramid.stride, settings.rotation_step_cells, turns,
                settings.rotation_window_deg * M_PI / 180.0);
  KeptLeaves kept(settings, settings.min_score_share * static_cast<double>(set.walls.size()));
  const PointCaps caps{1.0f, static_cast<float>(std::max(0.0, settings.free_weight))};
  BranchAndBound search(pyramid, turned, set, cell_size, caps, settings.stop_early, kept);
  std::vector<Node> nodes;
  for (int k = 0; k < static_cast<int>(turned.size()); ++k) {
    search.addTopNodes(k, -reach, grid_to.width + reach, -reach, grid_to.height + reach, top,
                       settings.depth, nodes);
  }
  std::sort(nodes.begin(), nodes.end(),
            [](const Node& a, const Node& b) { return a.bound > b.bound; });
  for (const Node& node : nodes) {
    if (node.bound <= kept.threshold()) {
      break;
    }
    search.expand(node);
  }
  return refined(kept.best(), fine, settings.rotation_step_cells / std::max(set.radius, 1.0),
                 cell_size);
}

/// Step 7: the `count` best by the score both ways, no two alike.
std::vector<ExhaustiveHypothesis> bestBothWays(std::vector<ExhaustiveHypothesis> all,
                                               const ExhaustiveScore& score, const GridMap& from,
                                               const ExhaustiveSearchSettings& settings) {
  for (ExhaustiveHypothesis& hypothesis : all) {
    hypothesis.score = score.at(hypothesis.T_to_from);
  }
  std::stable_sort(all.begin(), all.end(),
                   [](const ExhaustiveHypothesis& a, const ExhaustiveHypothesis& b) {
                     return a.score > b.score;
                   });
  const Eigen::Vector2d centre(0.5 * from.geometry.width, 0.5 * from.geometry.height);
  std::vector<ExhaustiveHypothesis> kept;
  for (const ExhaustiveHypothesis& candidate : all) {
    const bool alike = std::any_of(kept.begin(), kept.end(), [&](const auto& other) {
      return std::abs(std::remainder(candidate.T_to_from.theta_rad - other.T_to_from.theta_rad,
                                     2.0 * M_PI)) < settings.distinct_deg * M_PI / 180.0 &&
             (candidate.T_to_from.apply(centre) - other.T_to_from.apply(centre)).norm() <
                 settings.distinct_cells;
    });
    if (!alike && static_cast<int>(kept.size()) < settings.hypotheses) {
      kept.push_back(candidate);
    }
  }
  return kept;
}

}  // namespace

struct ExhaustiveScore::Parts {
  FineScorer forward;   ///< `from` onto `to`
  FineScorer backward;  ///< `to` onto `from`
};

ExhaustiveScore::ExhaustiveScore(const GridMap& from, const GridMap& to,
                                 const ExhaustiveSearchSettings& settings,
                                 const SimilaritySettings& classes) {
  const SearchGrid grid_from = toSearchGrid(from, 1, classes);  // each map once, for both ways
  const SearchGrid grid_to = toSearchGrid(to, 1, classes);
  parts_.reset(new Parts{FineScorer(grid_from, grid_to, settings),
                         FineScorer(grid_to, grid_from, settings)});
}

ExhaustiveScore::~ExhaustiveScore() = default;

double ExhaustiveScore::at(const GridTransform& T_to_from) const {
  return parts_->forward.score(T_to_from) + parts_->backward.score(T_to_from.inverse());
}

ExhaustiveHypothesis ExhaustiveScore::bestNear(const GridTransform& T_to_from, double turn_rad,
                                               int turn_steps, int shift_cells) const {
  // at(T) with each way's points turned once per turn: `to` onto `from` by T⁻¹, turned by -θ.
  const auto both = [this](double theta_rad) {
    return [forward = FineScorer::Turned(parts_->forward, theta_rad),
            backward = FineScorer::Turned(parts_->backward, -theta_rad),
            theta_rad](const Eigen::Vector2d& t_cells) {
      GridTransform T;
      T.theta_rad = theta_rad;
      T.t_cells = t_cells;
      return forward(t_cells) + backward(T.inverse().t_cells);
    };
  };
  const Eigen::Vector2d& pivot = parts_->forward.pivot();
  const ExhaustiveHypothesis coarse =
      fusion::bestNear(both, T_to_from, pivot, turn_rad, turn_steps, shift_cells);
  return fusion::bestNear(both, coarse.T_to_from, pivot, 0.25 * turn_rad, turn_steps, 1);
}

double exhaustiveScore(const GridMap& from, const GridMap& to, const GridTransform& T_to_from,
                       const ExhaustiveSearchSettings& settings,
                       const SimilaritySettings& classes) {
  return ExhaustiveScore(from, to, settings, classes).at(T_to_from);
}

namespace {

std::vector<double> radonProfile(const GridMap& map, const SimilaritySettings& classes,
                                 const RadonSettings& radon) {
  const cv::Mat occupied = occupiedImage(map, classes.occupied_threshold);
  const std::vector<cv::Point> walls = nonZeroCells(occupied);
  if (walls.empty()) {
    return {};
  }
  return radonSpectrumOfCells(walls, occupied.size(), radon.angle_step_rad,
                              radon.profile_highpass_rad);
}

}  // namespace

std::vector<double> suggestedTurns(const GridMap& from, const GridMap& to,
                                   const ExhaustiveSearchSettings& settings,
                                   const SimilaritySettings& classes) {
  if (settings.rotation_peaks <= 0) {
    return {};
  }
  const RadonSettings radon;
  const std::vector<double> profile_from = radonProfile(from, classes, radon);
  const std::vector<double> profile_to = radonProfile(to, classes, radon);
  if (profile_from.empty() || profile_to.empty()) {
    return {};
  }
  std::vector<double> turns;
  for (const double peak :
       rotationCandidates(spectrumCorrelation(profile_from, profile_to), settings.rotation_peaks)) {
    for (int quarter = 0; quarter < 4; ++quarter) {
      turns.push_back(peak + quarter * M_PI / 2.0);
    }
  }
  return turns;
}

int searchCellSize(const GridMap& from, const GridMap& to,
                   const ExhaustiveSearchSettings& settings) {
  return blockCellsForSize(from, to, settings.cell_size, settings.max_grid_cells);
}

std::vector<ExhaustiveHypothesis> exhaustiveSearch(const GridMap& from, const GridMap& to,
                                                   const ExhaustiveScore& score,
                                                   const ExhaustiveSearchSettings& settings,
                                                   const SimilaritySettings& classes) {
  ExhaustiveSearchSettings search = settings;
  search.cell_size = searchCellSize(from, to, settings);
  const SearchGrid grid_from = toSearchGrid(from, search.cell_size, classes);  // for both ways
  const SearchGrid grid_to = toSearchGrid(to, search.cell_size, classes);
  const std::vector<double> turns = suggestedTurns(from, to, settings, classes);
  std::vector<double> turns_back;
  for (const double turn : turns) {
    turns_back.push_back(-turn);
  }
  std::vector<ExhaustiveHypothesis> all =
      searchOneWay(grid_from, grid_to, score.parts_->forward, search, turns);
  if (settings.both_ways) {
    for (ExhaustiveHypothesis& reverse :
         searchOneWay(grid_to, grid_from, score.parts_->backward, search, turns_back)) {
      reverse.T_to_from = reverse.T_to_from.inverse();
      all.push_back(reverse);
    }
  }
  if (all.empty()) {
    return {};
  }
  return bestBothWays(std::move(all), score, from, settings);
}

std::vector<ExhaustiveHypothesis> exhaustiveSearch(const GridMap& from, const GridMap& to,
                                                   const ExhaustiveSearchSettings& settings,
                                                   const SimilaritySettings& classes) {
  return exhaustiveSearch(from, to, ExhaustiveScore(from, to, settings, classes), settings,
                          classes);
}

}  // namespace mrslam::fusion
