#include "mrslam/fusion/merge/wall_alignment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "mrslam/fusion/merge/reason_text.hpp"

namespace mrslam::fusion {

namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kLeastField = 0.01;  // f below this counts as 0 (d beyond 3σ)

using Level = WallField::Level;
using Cells = std::vector<Eigen::Vector2d>;

// A float image of `cols` × `rows` (rows `stride` floats apart) at `cell`, bilinear between
// cells; 0 off the image, whose last row and column count as off it.
inline double bilinearAt(const float* data, std::size_t stride, int cols, int rows,
                         const Eigen::Vector2d& cell) {
  const int x0 = floorToInt(cell.x());
  const int y0 = floorToInt(cell.y());
  if (x0 < 0 || y0 < 0 || x0 + 1 >= cols || y0 + 1 >= rows) {
    return 0.0;
  }
  const double fx = cell.x() - x0;
  const double fy = cell.y() - y0;
  const float* low = data + static_cast<std::size_t>(y0) * stride + static_cast<std::size_t>(x0);
  const float* high = low + stride;
  return (1.0 - fy) * ((1.0 - fx) * low[0] + fx * low[1]) +
         fy * ((1.0 - fx) * high[0] + fx * high[1]);
}

// The walls and the known cells of a map by the classes of block 8 (occupied at least
// occupied_threshold, free at most free_threshold, unknown between).
Cells classify(const GridMap& map, const SimilaritySettings& classes, cv::Mat& known) {
  Cells walls;
  known = cv::Mat(map.geometry.height, map.geometry.width, CV_8U, cv::Scalar(0));
  for (int y = 0; y < map.geometry.height; ++y) {
    std::uint8_t* row = known.ptr<std::uint8_t>(y);
    for (int x = 0; x < map.geometry.width; ++x) {
      const int value = map.at(x, y);
      if (classes.isOccupied(value)) {
        walls.emplace_back(x, y);
      }
      row[x] = classes.isKnown(value) ? 1 : 0;
    }
  }
  return walls;
}

// f = exp(-d² / 2σ²) of every known cell, d its distance to the nearest wall: each wall raises
// the cells around it to its own f (the nearest wall's is the largest) where that reaches
// kLeastField; 0 farther away and on unknown cells.
cv::Mat likelihoodField(const cv::Mat& known, const Cells& walls, double sigma_cells) {
  struct Weight {
    int dx;
    int dy;
    float f;
    std::ptrdiff_t offset;  // dy rows and dx columns in the (continuous) images
  };
  const int reach = static_cast<int>(std::ceil(3.0 * sigma_cells));
  std::vector<Weight> kernel;
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const double f = std::exp(-(dx * dx + dy * dy) / (2.0 * sigma_cells * sigma_cells));
      if (f >= kLeastField) {
        kernel.push_back(
            {dx, dy, static_cast<float>(f), static_cast<std::ptrdiff_t>(dy) * known.cols + dx});
      }
    }
  }
  cv::Mat field(known.size(), CV_32F, cv::Scalar(0.0f));
  for (const Eigen::Vector2d& wall : walls) {
    const int x = static_cast<int>(wall.x());
    const int y = static_cast<int>(wall.y());
    if (x >= reach && y >= reach && x + reach < known.cols && y + reach < known.rows) {
      // Inside by `reach`: every cell of the kernel is on the map.
      const std::uint8_t* known_at = known.ptr<std::uint8_t>(y) + x;
      float* field_at = field.ptr<float>(y) + x;
      for (const Weight& weight : kernel) {
        if (known_at[weight.offset] != 0) {
          field_at[weight.offset] = std::max(field_at[weight.offset], weight.f);
        }
      }
      continue;
    }
    for (const Weight& weight : kernel) {
      const int u = x + weight.dx;
      const int v = y + weight.dy;
      if (u >= 0 && v >= 0 && u < known.cols && v < known.rows &&
          known.ptr<std::uint8_t>(v)[u] != 0) {
        float& cell = field.ptr<float>(v)[u];
        cell = std::max(cell, weight.f);
      }
    }
  }
  return field;
}

Cells evenSample(const Cells& cells, int count) {
  if (count <= 0 || cells.size() <= static_cast<std::size_t>(count)) {
    return cells;
  }
  Cells sample;
  const double stride = static_cast<double>(cells.size()) / count;
  for (int i = 0; i < count; ++i) {
    sample.push_back(cells[static_cast<std::size_t>(i * stride)]);
  }
  return sample;
}

// The centre of `from`'s walls that T_to_from lands on `to`'s known cells (of all its walls when
// none does): the window turns about it.
Eigen::Vector2d overlapPivot(const WallField& from, const WallField& to,
                             const GridTransform& T_to_from) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int count = 0;
  const CellMapping to_of(T_to_from);
  for (const Eigen::Vector2d& wall : from.walls()) {
    if (to.isKnown(to_of(wall))) {
      sum += wall;
      ++count;
    }
  }
  if (count == 0) {
    for (const Eigen::Vector2d& wall : from.walls()) {
      sum += wall;
    }
    count = static_cast<int>(from.walls().size());
  }
  return sum / std::max(1, count);
}

// The walls of `own` that some transform of the window can carry onto known cells of `other`:
// a transform of the window moves a wall at r cells from the pivot (in `own`'s cells) at most
// max_shift + r · max_turn from where T_other_own puts it.
Cells reachableWalls(const WallField& own, const WallField& other, const GridTransform& T_other_own,
                     const Eigen::Vector2d& pivot_own, const WallAlignmentSettings& settings) {
  const double max_turn = settings.max_turn_deg * kDegToRad;
  Cells reachable;
  const CellMapping other_of(T_other_own);
  for (const Eigen::Vector2d& wall : own.walls()) {
    const double margin = settings.max_shift_cells + (wall - pivot_own).norm() * max_turn + 1.0;
    if (other.knownWithin(other_of(wall), margin)) {
      reachable.push_back(wall);
    }
  }
  return reachable;
}

// A transform of the window: the accepted one turned by `turn` about the pivot, then shifted.
struct Offset {
  double turn = 0.0;
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();
};

// An offset and W there (of either field's level, as the caller says).
struct ScoredOffset {
  Offset offset;
  double score = 0.0;
};

// The scored walls of both maps at both levels and the window's parametrisation.
class OffsetScorer {
 public:
  OffsetScorer(const WallField& from, const WallField& to, const GridTransform& T_to_from,
               const WallAlignmentSettings& settings)
      : from_(from), to_(to), T_(T_to_from) {
    pivot_ = overlapPivot(from, to, T_to_from);
    landed_ = T_.apply(pivot_);
    const Cells from_walls = reachableWalls(from, to, T_to_from, pivot_, settings);
    const Cells to_walls = reachableWalls(to, from, T_to_from.inverse(), landed_, settings);
    from_walls_ = {evenSample(from_walls, settings.coarse_walls),
                   evenSample(from_walls, settings.max_walls)};
    to_walls_ = {evenSample(to_walls, settings.coarse_walls),
                 evenSample(to_walls, settings.max_walls)};
  }

  GridTransform transform(const Offset& offset) const {
    GridTransform T;
    T.theta_rad = T_.theta_rad + offset.turn;
    GridTransform turn_only;
    turn_only.theta_rad = T.theta_rad;
    T.t_cells = landed_ + offset.shift - turn_only.apply(pivot_);
    return T;
  }

  /// W of `level` at every shift of `shifts` for one turn (the walls turned once).
  std::vector<double> scores(double turn, const Cells& shifts, Level level) const {
    const Turned& turned = turnedWalls(turn, level);
    std::vector<double> result;
    result.reserve(shifts.size());
    for (const Eigen::Vector2d& shift : shifts) {
      result.push_back(to_.sumAt(turned.from, shift, level) +
                       from_.sumAt(turned.to, -turned.unturn.apply(shift), level));
    }
    return result;
  }
  /// W of the narrow field at one offset. Each offset is summed once: the climbs step back onto
  /// offsets scored before, and climbs from several starts meet.
  double score(const Offset& offset) const {
    for (const ScoredOffset& known : scored_) {
      if (known.offset.turn == offset.turn && known.offset.shift == offset.shift) {
        return known.score;
      }
    }
    const double value = scores(offset.turn, {offset.shift}, Level::kFine).front();
    scored_.push_back({offset, value});
    return value;
  }

 private:
  static std::size_t index(Level level) { return level == Level::kCoarse ? 0 : 1; }
  static void moveInto(const Cells& cells, const GridTransform& T, Cells& result) {
    result.resize(cells.size());
    const CellMapping mapped(T);
    for (std::size_t i = 0; i < cells.size(); ++i) {
      result[i] = mapped(cells[i]);
    }
  }

  // The walls of both maps at one turn and no shift. The last kTurnsKept turns' are kept: a step
  // of the pattern search tries the turns on either side and then shifts at its own.
  struct Turned {
    double turn = std::numeric_limits<double>::quiet_NaN();  // NaN: an empty slot, never matched
    Level level = Level::kCoarse;
    Cells from;  // from_'s walls in to_'s cells
    Cells to;    // to_'s walls in from_'s cells
    GridTransform unturn;
  };
  static constexpr std::size_t kTurnsKept = 4;
  const Turned& turnedWalls(double turn, Level level) const {
    for (const Turned& kept : turned_) {
      if (kept.turn == turn && kept.level == level) {
        return kept;
      }
    }
    Turned& slot = turned_[next_slot_];
    next_slot_ = (next_slot_ + 1) % kTurnsKept;
    const GridTransform at_zero = transform({turn, Eigen::Vector2d::Zero()});
    slot.turn = turn;
    slot.level = level;
    moveInto(from_walls_[index(level)], at_zero, slot.from);
    moveInto(to_walls_[index(level)], at_zero.inverse(), slot.to);
    slot.unturn = GridTransform();
    slot.unturn.theta_rad = -at_zero.theta_rad;
    return slot;
  }

  const WallField& from_;
  const WallField& to_;
  mutable std::array<Turned, kTurnsKept> turned_;  // filled in turn
  mutable std::size_t next_slot_ = 0;
  mutable std::vector<ScoredOffset> scored_;  // every offset score() summed, in turn
  GridTransform T_;
  Eigen::Vector2d pivot_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d landed_ = Eigen::Vector2d::Zero();
  std::array<Cells, 2> from_walls_;  // coarse, fine
  std::array<Cells, 2> to_walls_;
};

// Whether two offsets of the coarse grid lie apart by more than one grid step in turn or shift.
bool apartOnGrid(const Offset& a, const Offset& b, const WallAlignmentSettings& settings) {
  const double turn_steps = std::abs(a.turn - b.turn) / (settings.coarse_turn_step_deg * kDegToRad);
  const double shift_steps =
      (a.shift - b.shift).cwiseAbs().maxCoeff() / settings.coarse_shift_cells;
  return turn_steps > 1.5 || shift_steps > 1.5;
}

// Every turn and shift of the coarse grid, on the wide field; the best `starts` of them, each
// more than a grid step from the better ones, best first. The zero offset is scored first, so
// that the accepted transform wins ties.
std::vector<Offset> searchGrid(const OffsetScorer& scorer, const WallAlignmentSettings& settings) {
  const int turns =
      static_cast<int>(std::floor(settings.max_turn_deg / settings.coarse_turn_step_deg + 1e-9));
  const int shifts =
      static_cast<int>(std::floor(settings.max_shift_cells / settings.coarse_shift_cells + 1e-9));
  Cells grid;
  grid.emplace_back(0.0, 0.0);
  for (int i = -shifts; i <= shifts; ++i) {
    for (int j = -shifts; j <= shifts; ++j) {
      if (i != 0 || j != 0) {
        grid.emplace_back(i * settings.coarse_shift_cells, j * settings.coarse_shift_cells);
      }
    }
  }
  std::vector<ScoredOffset> points;
  for (int k = 0; k <= 2 * turns; ++k) {
    const int step = (k + 1) / 2 * (k % 2 == 1 ? 1 : -1);  // 0, 1, -1, 2, -2, ...
    const double turn = step * settings.coarse_turn_step_deg * kDegToRad;
    const std::vector<double> scores = scorer.scores(turn, grid, Level::kCoarse);
    for (std::size_t g = 0; g < grid.size(); ++g) {
      points.push_back({{turn, grid[g]}, scores[g]});
    }
  }
  std::stable_sort(points.begin(), points.end(),
                   [](const ScoredOffset& a, const ScoredOffset& b) { return a.score > b.score; });
  std::vector<Offset> starts;
  for (const ScoredOffset& point : points) {
    if (static_cast<int>(starts.size()) >= std::max(1, settings.starts)) {
      break;
    }
    const bool apart = std::all_of(starts.begin(), starts.end(), [&](const Offset& start) {
      return apartOnGrid(start, point.offset, settings);
    });
    if (apart) {
      starts.push_back(point.offset);
    }
  }
  return starts;
}

// Pattern search of the narrow field from `start`: one step up or down in each of the turn and
// the two shifts while W rises, then the steps halved, fine_steps times; the offset stays inside
// the window.
ScoredOffset searchPattern(const OffsetScorer& scorer, const WallAlignmentSettings& settings,
                           const Offset& start) {
  ScoredOffset best{start, scorer.score(start)};
  double turn_step = 0.5 * settings.coarse_turn_step_deg * kDegToRad;
  double shift_step = 0.5 * settings.coarse_shift_cells;
  const double max_turn = settings.max_turn_deg * kDegToRad;
  for (int halving = 0; halving < settings.fine_steps; ++halving) {
    for (bool moved = true; moved;) {
      moved = false;
      const Offset from = best.offset;
      const Offset steps[] = {{turn_step, {0, 0}},   {-turn_step, {0, 0}}, {0, {shift_step, 0}},
                              {0, {-shift_step, 0}}, {0, {0, shift_step}}, {0, {0, -shift_step}}};
      for (const Offset& step : steps) {
        const Offset next{from.turn + step.turn, from.shift + step.shift};
        if (std::abs(next.turn) > max_turn + 1e-12 ||
            next.shift.cwiseAbs().maxCoeff() > settings.max_shift_cells + 1e-9) {
          continue;
        }
        const double score = scorer.score(next);
        if (score > best.score) {
          best = {next, score};
          moved = true;
        }
      }
    }
    turn_step *= 0.5;
    shift_step *= 0.5;
  }
  return best;
}

}  // namespace

WallField::WallField(const GridMap& map, const SimilaritySettings& classes,
                     const WallAlignmentSettings& settings) {
  walls_ = classify(map, classes, known_);
  field_ = likelihoodField(known_, walls_, settings.sigma_cells);
  coarse_field_ = likelihoodField(known_, walls_, settings.coarse_sigma_cells);
  cv::Mat unknown;
  cv::compare(known_, 0, unknown, cv::CMP_EQ);  // 255 on unknown cells: they get distances
  cv::distanceTransform(unknown, distance_to_known_, cv::DIST_L2, cv::DIST_MASK_3);
}

double WallField::fieldAt(const Eigen::Vector2d& cell, Level level) const {
  const cv::Mat& field = fieldOf(level);
  return bilinearAt(field.ptr<float>(0), field.step1(), field.cols, field.rows, cell);
}

double WallField::sumAt(const std::vector<Eigen::Vector2d>& cells, const Eigen::Vector2d& shift,
                        Level level) const {
  const cv::Mat& field = fieldOf(level);
  const float* data = field.ptr<float>(0);
  const std::size_t stride = field.step1();
  double total = 0.0;
  for (const Eigen::Vector2d& cell : cells) {
    total += bilinearAt(data, stride, field.cols, field.rows, cell + shift);
  }
  return total;
}

bool WallField::isKnown(const Eigen::Vector2d& cell) const {
  const int x = floorToInt(cell.x() + 0.5);
  const int y = floorToInt(cell.y() + 0.5);
  return x >= 0 && y >= 0 && x < known_.cols && y < known_.rows &&
         known_.ptr<std::uint8_t>(y)[x] != 0;
}

bool WallField::knownWithin(const Eigen::Vector2d& cell, double cells) const {
  const int x = floorToInt(cell.x() + 0.5);
  const int y = floorToInt(cell.y() + 0.5);
  if (x < 0 || y < 0 || x >= known_.cols || y >= known_.rows) {
    return false;  // off the map: only the map's own cells are looked at
  }
  return distance_to_known_.ptr<float>(y)[x] <= cells;
}

WallAgreement wallAgreement(const WallField& from, const WallField& to,
                            const GridTransform& T_to_from) {
  WallAgreement agreement;
  const CellMapping to_of(T_to_from);
  const CellMapping from_of(T_to_from.inverse());
  for (const Eigen::Vector2d& wall : from.walls()) {
    const Eigen::Vector2d landed = to_of(wall);
    agreement.score += to.fieldAt(landed, Level::kFine);
    agreement.counted += to.isKnown(landed) ? 1 : 0;
  }
  for (const Eigen::Vector2d& wall : to.walls()) {
    const Eigen::Vector2d landed = from_of(wall);
    agreement.score += from.fieldAt(landed, Level::kFine);
    agreement.counted += from.isKnown(landed) ? 1 : 0;
  }
  return agreement;
}

namespace {

// Whether at least `least` walls of either map land on the other's known cells (the count of
// wallAgreement, stopped once it is reached).
bool landsEnoughWalls(const WallField& from, const WallField& to, const GridTransform& T_to_from,
                      int least) {
  int counted = 0;
  const auto count = [&](const WallField& own, const WallField& other, const GridTransform& T) {
    const CellMapping other_of(T);
    for (const Eigen::Vector2d& wall : own.walls()) {
      counted += other.isKnown(other_of(wall)) ? 1 : 0;
      if (counted >= least) {
        return true;
      }
    }
    return false;
  };
  return least <= 0 || count(from, to, T_to_from) || count(to, from, T_to_from.inverse());
}

}  // namespace

WallPeaks wallPeaks(const WallField& from, const WallField& to, const GridTransform& T_to_from,
                    const WallAlignmentSettings& settings) {
  if (!landsEnoughWalls(from, to, T_to_from, settings.min_walls)) {
    return {T_to_from, T_to_from};
  }
  const OffsetScorer scorer(from, to, T_to_from, settings);
  const double at_start = scorer.score({});
  const auto placed = [&](const ScoredOffset& best) {
    return best.score > at_start ? scorer.transform(best.offset) : T_to_from;
  };
  const std::vector<Offset> starts = searchGrid(scorer, settings);
  ScoredOffset highest{{}, at_start};
  WallPeaks peaks;
  for (std::size_t i = 0; i < starts.size(); ++i) {
    const ScoredOffset climbed = searchPattern(scorer, settings, starts[i]);
    if (i == 0) {
      peaks.first = placed(climbed);
    }
    if (climbed.score > highest.score) {
      highest = climbed;
    }
  }
  peaks.highest = placed(highest);
  return peaks;
}

GridTransform alignWalls(const WallField& from, const WallField& to, const GridTransform& T_to_from,
                         const WallAlignmentSettings& settings) {
  return wallPeaks(from, to, T_to_from, settings).highest;
}

double wallTurnShare(const WallField& from, const WallField& to, const GridTransform& T_to_from,
                     const WallAlignmentSettings& settings) {
  const WallAgreement at = wallAgreement(from, to, T_to_from);
  if (at.counted < settings.min_walls || at.score <= 0.0) {
    return 0.0;
  }
  const Eigen::Vector2d pivot = overlapPivot(from, to, T_to_from);
  const Eigen::Vector2d landed = T_to_from.apply(pivot);
  WallAlignmentSettings shifts_only = settings;
  shifts_only.max_turn_deg = 0.0;
  shifts_only.max_shift_cells = settings.turn_check_shift_cells;
  double largest = 0.0;
  for (const double sign : {-1.0, 1.0}) {
    GridTransform turned = T_to_from;
    turned.theta_rad += sign * settings.turn_check_deg * kDegToRad;
    GridTransform turn_only;
    turn_only.theta_rad = turned.theta_rad;
    turned.t_cells = landed - turn_only.apply(pivot);
    const GridTransform placed = alignWalls(from, to, turned, shifts_only);
    largest = std::max(largest, wallAgreement(from, to, placed).score / at.score);
  }
  return largest;
}

namespace {

// The turn check: `result` refused when its walls meet as well turned (wallTurnShare) at
// `highest` or at `first`.
void refuseUnlessTurnFixed(const WallField& from, const WallField& to,
                           const WallAlignmentSettings& settings, const GridTransform& highest,
                           const GridTransform& first, MergeResult& result) {
  if (settings.max_turn_share >= 1.0) {
    return;
  }
  double share = wallTurnShare(from, to, highest, settings);
  if (!sameTransform(first, highest)) {
    share = std::max(share, wallTurnShare(from, to, first, settings));
  }
  result.wall_turn_share = share;
  if (share >= settings.max_turn_share) {
    result.accepted = false;
    result.refusal = MergeRefusal::kRotation;
    result.reason = "the walls of the overlap do not fix the rotation: turned by " +
                    reasonFigure(settings.turn_check_deg) + " degrees they meet " +
                    reasonFigure(share) + " as well";
  }
}

// An aligned transform and the agreement of all known cells there.
struct Placed {
  GridTransform T_to_from;
  Agreement full;
};

// `aligned` where V is at least as high there as at `found`, else `found`.
Placed keptWhereVHolds(const AlignmentMaps& maps, const GridTransform& aligned,
                       const GridTransform& found, const Agreement& at_found) {
  if (sameTransform(aligned, found)) {
    return {found, at_found};
  }
  const Agreement at_aligned = compareAt(maps.known_from, maps.codes_to, aligned, maps.tables);
  // The walls may pull a little off where the cells of the two maps agree best (crops resampled
  // differently, a wall doubled by pose error): the alignment never lowers V.
  if (verificationIndex(at_aligned) >= verificationIndex(at_found)) {
    return {aligned, at_aligned};
  }
  return {found, at_found};
}

}  // namespace

void alignAccepted(const GridMap& from, const GridMap& to, const WallAlignmentSettings& settings,
                   const SimilaritySettings& classes, MergeResult& result) {
  if (!settings.enabled || !result.accepted) {
    return;
  }
  const ComparisonTables tables(classes);
  const std::vector<CellSample> known_from = knownCells(from, tables);
  const CodeImage codes_to = codeImage(to, 1, tables);
  alignAccepted({WallField(from, classes, settings), WallField(to, classes, settings), tables,
                 known_from, codes_to, mapEntropy(from, tables), mapEntropy(to, tables)},
                settings, result);
}

void alignAccepted(const AlignmentMaps& maps, const WallAlignmentSettings& settings,
                   MergeResult& result) {
  if (!settings.enabled || !result.accepted) {
    return;
  }
  const WallPeaks peaks = wallPeaks(maps.field_from, maps.field_to, result.T_to_from, settings);
  const Agreement at_found =
      maps.at_found ? *maps.at_found
                    : compareAt(maps.known_from, maps.codes_to, result.T_to_from, maps.tables);
  const Placed highest = keptWhereVHolds(maps, peaks.highest, result.T_to_from, at_found);
  const Placed first = sameTransform(peaks.first, peaks.highest)
                           ? highest
                           : keptWhereVHolds(maps, peaks.first, result.T_to_from, at_found);
  result.T_to_from = highest.T_to_from;
  result.verification = verificationIndex(highest.full);
  result.entropy = mergedEntropy(maps.entropy_from, maps.entropy_to, highest.full);
  refuseUnlessTurnFixed(maps.field_from, maps.field_to, settings, highest.T_to_from,
                        first.T_to_from, result);
}

}  // namespace mrslam::fusion
