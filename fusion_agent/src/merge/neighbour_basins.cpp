#include "mrslam/fusion/merge/neighbour_basins.hpp"

#include <algorithm>
#include <cmath>

namespace mrslam::fusion {

namespace {

constexpr double kDegToRad = M_PI / 180.0;

/// V of the samples at transforms of `from`, each turned about one pivot.
class VAtTransforms {
 public:
  /// `samples` of `from`; at() scores only transforms that keep `min_overlap_share` of their
  /// overlap at `accepted` (a basin that slides the overlap off scores V trivially high).
  VAtTransforms(const std::vector<CellSample>& samples, const CodeImage& to,
                const ComparisonTables& tables, const GridTransform& accepted,
                double min_overlap_share)
      : samples_(samples), to_(to), tables_(tables) {
    for (const CellSample& cell : samples) {
      pivot_ += Eigen::Vector2d(cell.x, cell.y);
    }
    if (!samples.empty()) {
      pivot_ /= static_cast<double>(samples.size());
    }
    const auto overlap = compareAt(samples, to, accepted, tables, false).overlap();
    least_overlap_ =
        static_cast<long long>(std::ceil(min_overlap_share * static_cast<double>(overlap)));
  }

  /// V at T_to_from, or -1 where the overlap is below the least.
  double at(const GridTransform& T_to_from) {
    ++comparisons_;
    const Agreement agreement = compareAt(samples_, to_, T_to_from, tables_, false);
    return agreement.overlap() >= least_overlap_ ? verificationIndex(agreement) : -1.0;
  }

  /// T_to_from turned by `turn_rad` about the pivot, then shifted by `shift`.
  GridTransform moved(const GridTransform& T_to_from, double turn_rad,
                      const Eigen::Vector2d& shift) const {
    GridTransform T = T_to_from;
    const Eigen::Vector2d landed = T_to_from.apply(pivot_);
    T.theta_rad += turn_rad;
    T.t_cells += landed - T.apply(pivot_) + shift;
    return T;
  }

  /// Where two transforms put the pivot apart, cells.
  double apart(const GridTransform& a, const GridTransform& b) const {
    return (a.apply(pivot_) - b.apply(pivot_)).norm();
  }

  int comparisons() const { return comparisons_; }

 private:
  const std::vector<CellSample>& samples_;
  const CodeImage& to_;
  const ComparisonTables& tables_;
  Eigen::Vector2d pivot_ = Eigen::Vector2d::Zero();
  long long least_overlap_ = 0;
  int comparisons_ = 0;
};

/// Every n-th of `cells`, n the least that keeps at most `count` of them: a sample whose classes
/// keep their shares.
std::vector<CellSample> everyNth(const std::vector<CellSample>& cells, int count) {
  const std::size_t n =
      count <= 0 ? 1 : std::max<std::size_t>(1, (cells.size() + count - 1) / count);
  std::vector<CellSample> sample;
  sample.reserve(cells.size() / n + 1);
  for (std::size_t i = 0; i < cells.size(); i += n) {
    sample.push_back(cells[i]);
  }
  return sample;
}

struct Peak {
  GridTransform T_to_from;
  double v = 0.0;
  bool climbed = false;  ///< a climb moved it from where it started
};

/// The pattern search of V from `start` (neighbour_basins.hpp).
Peak climb(VAtTransforms& v_at, const GridTransform& start, double start_v,
           const NeighbourBasinSettings& settings) {
  Peak peak{start, start_v};
  double turn = settings.climb_turn_deg * kDegToRad;
  double shift = settings.climb_shift_cells;
  const double least_turn = settings.min_climb_turn_deg * kDegToRad;
  while (turn >= least_turn) {
    const GridTransform steps[] = {v_at.moved(peak.T_to_from, turn, {0.0, 0.0}),
                                   v_at.moved(peak.T_to_from, -turn, {0.0, 0.0}),
                                   v_at.moved(peak.T_to_from, 0.0, {shift, 0.0}),
                                   v_at.moved(peak.T_to_from, 0.0, {-shift, 0.0}),
                                   v_at.moved(peak.T_to_from, 0.0, {0.0, shift}),
                                   v_at.moved(peak.T_to_from, 0.0, {0.0, -shift})};
    bool moved = false;
    for (const GridTransform& step : steps) {
      const double v = v_at.at(step);
      if (v > peak.v) {
        peak = {step, v, true};
        moved = true;
      }
    }
    if (!moved) {
      turn *= 0.5;
      shift *= 0.5;
    }
  }
  return peak;
}

/// The grid's points around T_to_from (the transform itself left out), best V first.
std::vector<Peak> gridPoints(VAtTransforms& v_at, const GridTransform& T_to_from,
                             const NeighbourBasinSettings& settings) {
  std::vector<Peak> points;
  for (int k = -settings.turn_steps; k <= settings.turn_steps; ++k) {
    for (int i = -settings.shift_steps; i <= settings.shift_steps; ++i) {
      for (int j = -settings.shift_steps; j <= settings.shift_steps; ++j) {
        if (k == 0 && i == 0 && j == 0) {
          continue;
        }
        const GridTransform T =
            v_at.moved(T_to_from, k * settings.turn_step_deg * kDegToRad,
                       {i * settings.shift_step_cells, j * settings.shift_step_cells});
        points.push_back({T, v_at.at(T)});
      }
    }
  }
  std::stable_sort(points.begin(), points.end(),
                   [](const Peak& a, const Peak& b) { return a.v > b.v; });
  return points;
}

}  // namespace

NeighbourBasins neighbourBasins(const std::vector<CellSample>& known_from, const CodeImage& to,
                                const ComparisonTables& tables, const GridTransform& T_to_from,
                                const NeighbourBasinSettings& settings) {
  const std::vector<CellSample> samples = everyNth(known_from, settings.sampled_cells);
  VAtTransforms v_at(samples, to, tables, T_to_from, settings.min_overlap_share);
  const Peak own = climb(v_at, T_to_from, v_at.at(T_to_from), settings);
  Peak other{own.T_to_from, -1.0};
  const std::vector<Peak> points = gridPoints(v_at, T_to_from, settings);
  const auto climbs = static_cast<std::size_t>(std::max(0, settings.climbs));
  for (std::size_t i = 0; i < std::min(climbs, points.size()) && points[i].v >= 0.0; ++i) {
    const Peak peak = climb(v_at, points[i].T_to_from, points[i].v, settings);
    if (v_at.apart(peak.T_to_from, own.T_to_from) > settings.distinct_cells && peak.v > other.v) {
      other = peak;
    }
  }
  NeighbourBasins basins;
  basins.comparisons = v_at.comparisons();
  const auto full = [&](const GridTransform& T) {
    ++basins.comparisons;
    return compareAt(known_from, to, T, tables, false);
  };
  // The accepted transform itself where the sample's peak is lower over all known cells.
  const Agreement at_accepted = full(T_to_from);
  const Agreement at_own = own.climbed ? full(own.T_to_from) : at_accepted;
  const bool own_higher = verificationIndex(at_own) > verificationIndex(at_accepted);
  basins.own = own_higher ? own.T_to_from : T_to_from;
  basins.own_v = verificationIndex(own_higher ? at_own : at_accepted);
  basins.other = other.T_to_from;
  if (other.v < 0.0) {
    return basins;
  }
  const Agreement at_other = full(other.T_to_from);
  if (static_cast<double>(at_other.overlap()) <
      settings.min_overlap_share * static_cast<double>(at_accepted.overlap())) {
    return basins;
  }
  basins.other_v = verificationIndex(at_other);
  basins.other_cells = v_at.apart(other.T_to_from, basins.own);
  basins.other_deg =
      std::abs(std::remainder(other.T_to_from.theta_rad - basins.own.theta_rad, 2.0 * M_PI)) /
      kDegToRad;
  return basins;
}

NeighbourBasins neighbourBasins(const GridMap& from, const GridMap& to,
                                const SimilaritySettings& classes, const GridTransform& T_to_from,
                                const NeighbourBasinSettings& settings) {
  const ComparisonTables tables(classes);
  return neighbourBasins(knownCells(from, tables), codeImage(to, 1, tables), tables, T_to_from,
                         settings);
}

}  // namespace mrslam::fusion
