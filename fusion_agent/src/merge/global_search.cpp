#include "mrslam/fusion/merge/global_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "mrslam/fusion/merge/padded_spectrum.hpp"
#include "mrslam/fusion/merge/quarter_turns.hpp"
#include "mrslam/fusion/merge/torus_peaks.hpp"

namespace mrslam::fusion {

namespace {

// A map on the coarse grid: occupied and known-free-only coarse cells as 0/1 images.
struct CoarseMap {
  cv::Mat occupied;  // CV_32F
  cv::Mat free;      // CV_32F
};

CoarseMap coarsen(const GridMap& map, int coarse, const SimilaritySettings& classes) {
  const int cols = (map.geometry.width + coarse - 1) / coarse;
  const int rows = (map.geometry.height + coarse - 1) / coarse;
  CoarseMap result{cv::Mat(rows, cols, CV_32F, cv::Scalar(0.0f)),
                   cv::Mat(rows, cols, CV_32F, cv::Scalar(0.0f))};
  for (int y = 0; y < map.geometry.height; ++y) {
    for (int x = 0; x < map.geometry.width; ++x) {
      const int value = map.at(x, y);
      if (classes.isOccupied(value)) {
        result.occupied.at<float>(y / coarse, x / coarse) += 1.0f;
      } else if (classes.isFree(value)) {
        result.free.at<float>(y / coarse, x / coarse) += 1.0f;
      }
    }
  }
  result.free.setTo(0.0f, result.occupied > 0.5f);  // free only where no wall is
  cv::threshold(result.occupied, result.occupied, 0.5, 1.0, cv::THRESH_BINARY);
  cv::threshold(result.free, result.free, 0.5, 1.0, cv::THRESH_BINARY);
  return result;
}

// The turning of `from`'s coarse images onto a square canvas about their centres.
struct Turn {
  int canvas = 0;                                         // canvas side, coarse cells
  Eigen::Vector2d centre_from = Eigen::Vector2d::Zero();  // coarse image centre
  Eigen::Vector2d centre_canvas = Eigen::Vector2d::Zero();
  cv::Mat matrix(double theta) const {
    const double c = std::cos(theta);
    const double s = std::sin(theta);
    const Eigen::Vector2d shift =
        centre_canvas - Eigen::Vector2d(c * centre_from.x() - s * centre_from.y(),
                                        s * centre_from.x() + c * centre_from.y());
    return (cv::Mat_<double>(2, 3) << c, -s, shift.x(), s, c, shift.y());
  }
};

// The fine-cell transform of a coarse shift k at rotation theta: a coarse cell p_c of `from`
// lands on R (p_c - c_from) + c_canvas + k of `to`; fine cell p = coarse · p_c + h, h = the
// offset of a coarse cell's centre.
GridTransform fineTransform(const Turn& turn, double theta, const Eigen::Vector2d& shift,
                            int coarse) {
  const double h = 0.5 * (coarse - 1);
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  const Eigen::Vector2d anchor = Eigen::Vector2d::Constant(h) + coarse * turn.centre_from;
  GridTransform T_to_from;
  T_to_from.theta_rad = std::remainder(theta, 2.0 * M_PI);
  T_to_from.t_cells =
      -Eigen::Vector2d(c * anchor.x() - s * anchor.y(), s * anchor.x() + c * anchor.y()) +
      coarse * (turn.centre_canvas + shift) + Eigen::Vector2d::Constant(h);
  return T_to_from;
}

struct Peak {
  Eigen::Vector2d shift;  // coarse cells, wrapped to negative where past half the DFT size
  double score;
};

// The strongest peaks of a rotation's scores (spent: see strongestTorusPeaks), their shifts
// wrapped to negative past half the DFT size.
std::vector<Peak> strongestPeaks(cv::Mat& scores, int count, int separation) {
  std::vector<Peak> peaks;
  for (const TorusPeak& peak : strongestTorusPeaks(scores, count, separation)) {
    const int x = peak.cell.x;
    const int y = peak.cell.y;
    peaks.push_back({Eigen::Vector2d(x > scores.cols / 2 ? x - scores.cols : x,
                                     y > scores.rows / 2 ? y - scores.rows : y),
                     peak.score});
  }
  return peaks;
}

// The best hypotheses, no two placing `from`'s centre within `cells` at a rotation within
// `angle` of each other.
std::vector<GlobalHypothesis> bestDistinct(std::vector<GlobalHypothesis> all, int count,
                                           const Eigen::Vector2d& centre_from, double cells,
                                           double angle) {
  std::sort(all.begin(), all.end(),
            [](const GlobalHypothesis& a, const GlobalHypothesis& b) { return a.score > b.score; });
  std::vector<GlobalHypothesis> kept;
  for (const GlobalHypothesis& candidate : all) {
    if (static_cast<int>(kept.size()) >= count) {
      break;
    }
    const Eigen::Vector2d placed = candidate.T_to_from.apply(centre_from);
    const bool alike = std::any_of(kept.begin(), kept.end(), [&](const GlobalHypothesis& other) {
      return std::abs(std::remainder(candidate.T_to_from.theta_rad - other.T_to_from.theta_rad,
                                     2.0 * M_PI)) < angle &&
             (other.T_to_from.apply(centre_from) - placed).norm() < cells;
    });
    if (!alike) {
      kept.push_back(candidate);
    }
  }
  return kept;
}

// Whether the sweep turns `from` by theta: every rotation, or those within one step (and a
// rounding margin) of a wanted one.
bool sweeps(double theta, const GlobalSearchSettings& settings) {
  return settings.only_rotations_rad.empty() ||
         std::any_of(settings.only_rotations_rad.begin(), settings.only_rotations_rad.end(),
                     [&](double wanted) {
                       return std::abs(std::remainder(theta - wanted, 2.0 * M_PI)) <=
                              1.01 * settings.rotation_step_rad;
                     });
}

// `to`'s images as the correlations take them: the spectra of W_to, O_to and (step 5) F_to.
struct TargetSpectra {
  cv::Mat weights;
  cv::Mat walls;
  cv::Mat free;  // empty without step 5
};

TargetSpectra targetSpectra(const cv::Mat& weights, const cv::Mat& walls, const cv::Mat& free,
                            cv::Size size) {
  return {paddedSpectrum(weights, size), paddedSpectrum(walls, size),
          free.empty() ? cv::Mat() : paddedSpectrum(free, size)};
}

// s and (step 5, when `target.free` is given) s_f of one rotation from the spectra of its turned
// images.
struct RotationScores {
  cv::Mat scores;
  cv::Mat free_scores;
};

RotationScores rotationScores(const TargetSpectra& target, const cv::Mat& walls_spectrum,
                              const cv::Mat& free_spectrum, const GlobalSearchSettings& settings) {
  const float w = static_cast<float>(settings.free_weight);
  RotationScores result;
  cv::Mat on_walls;
  cv::Mat on_free;
  cv::mulSpectrums(target.weights, walls_spectrum, on_walls, 0, true);
  cv::mulSpectrums(target.walls, free_spectrum, on_free, 0, true);
  cv::idft(on_walls - w * on_free, result.scores, cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
  if (!target.free.empty()) {
    // The same score plus the free cells that meet free cells, weighted.
    cv::Mat free_on_free;
    cv::mulSpectrums(target.free, free_spectrum, free_on_free, 0, true);
    cv::idft(free_on_free, result.free_scores, cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
    result.free_scores =
        result.scores + static_cast<float>(settings.free_agreement_weight) * result.free_scores;
  }
  return result;
}

// The coarse maps, the turning of `from` and the spectra of `to`, as every rotation shares them.
struct Sweep {
  CoarseMap from;
  CoarseMap to;
  Turn turn;
  cv::Size size;  // of the DFTs
  bool by_free = false;
  bool quarter_turns = false;
  std::vector<TargetSpectra> targets;  // `to` turned back by 0 (and with quarter_turns 1-3) turns
};

// Peaks of one rotation: those of s, then (step 5) those of s_f.
struct RotationPeaks {
  std::vector<GlobalHypothesis> by_walls;
  std::vector<GlobalHypothesis> by_free;
};

RotationPeaks peaksOf(const Sweep& sweep, double theta, int coarse, RotationScores scores,
                      const GlobalSearchSettings& settings) {
  RotationPeaks peaks;
  if (sweep.by_free) {
    for (const Peak& peak : strongestPeaks(scores.free_scores, settings.peaks_per_rotation,
                                           settings.peak_separation)) {
      peaks.by_free.push_back(
          {fineTransform(sweep.turn, theta, peak.shift, coarse), peak.score, true});
    }
  }
  for (const Peak& peak :
       strongestPeaks(scores.scores, settings.peaks_per_rotation, settings.peak_separation)) {
    peaks.by_walls.push_back({fineTransform(sweep.turn, theta, peak.shift, coarse), peak.score});
  }
  return peaks;
}

// The spectra of `from`'s images turned by theta onto the canvas: walls, free.
std::pair<cv::Mat, cv::Mat> turnedSpectra(const Sweep& sweep, double theta) {
  const cv::Mat matrix = sweep.turn.matrix(theta);
  const cv::Size canvas(sweep.turn.canvas, sweep.turn.canvas);
  cv::Mat turned_walls;
  cv::Mat turned_free;
  cv::warpAffine(sweep.from.occupied, turned_walls, matrix, canvas, cv::INTER_LINEAR);
  cv::warpAffine(sweep.from.free, turned_free, matrix, canvas, cv::INTER_LINEAR);
  return {paddedSpectrum(turned_walls, sweep.size), paddedSpectrum(turned_free, sweep.size)};
}

// W_to = O_to - w F_to, the target of the walls of `from`.
cv::Mat wallTarget(const Sweep& sweep, const GlobalSearchSettings& settings) {
  return sweep.to.occupied - static_cast<float>(settings.free_weight) * sweep.to.free;
}

// Every swept rotation's peaks, by rotation index of `rotations` over the full turn (empty where
// not swept), each rotation's images of `from` turned and transformed.
std::vector<RotationPeaks> sweepEachRotation(const Sweep& sweep, int rotations,
                                             const GlobalSearchSettings& settings) {
  const int coarse = std::max(1, settings.coarse_cells);
  const TargetSpectra& target = sweep.targets.front();
  if (settings.exact_rotations) {
    std::vector<RotationPeaks> peaks;
    for (const double theta : settings.only_rotations_rad) {
      const auto [walls, free] = turnedSpectra(sweep, theta);
      peaks.push_back(
          peaksOf(sweep, theta, coarse, rotationScores(target, walls, free, settings), settings));
    }
    return peaks;
  }
  std::vector<RotationPeaks> peaks(static_cast<std::size_t>(rotations));
  for (int k = 0; k < rotations; ++k) {
    const double theta = 2.0 * M_PI * k / rotations;
    if (!sweeps(theta, settings)) {
      continue;
    }
    const auto [walls, free] = turnedSpectra(sweep, theta);
    peaks[static_cast<std::size_t>(k)] =
        peaksOf(sweep, theta, coarse, rotationScores(target, walls, free, settings), settings);
  }
  return peaks;
}

// The same for every rotation of the full turn, their count a multiple of 4, on a square DFT:
// the images of `from` are turned and transformed for the first quarter turn only, each of them
// correlated with `to` turned back by 0-3 quarter turns (quarter_turns.hpp).
std::vector<RotationPeaks> sweepByQuarterTurns(const Sweep& sweep, int rotations,
                                               const GlobalSearchSettings& settings) {
  const int coarse = std::max(1, settings.coarse_cells);
  std::vector<RotationPeaks> peaks(static_cast<std::size_t>(rotations));
  const int quarter = rotations / 4;
  for (int k = 0; k < quarter; ++k) {
    const auto [walls_spectrum, free_spectrum] = turnedSpectra(sweep, 2.0 * M_PI * k / rotations);
    for (int quarters = 0; quarters < 4; ++quarters) {
      const int index = k + quarters * quarter;
      RotationScores scores = rotationScores(sweep.targets[static_cast<std::size_t>(quarters)],
                                             walls_spectrum, free_spectrum, settings);
      if (quarters > 0) {
        scores.scores = quarterTurnScores(scores.scores, sweep.turn.canvas, quarters);
        if (sweep.by_free) {
          scores.free_scores = quarterTurnScores(scores.free_scores, sweep.turn.canvas, quarters);
        }
      }
      peaks[static_cast<std::size_t>(index)] =
          peaksOf(sweep, 2.0 * M_PI * index / rotations, coarse, std::move(scores), settings);
    }
  }
  return peaks;
}

// The spectra of `to`'s images as the correlations take them, turned back by 0 quarter turns,
// and with quarter_turns by 1-3 as well (quarter_turns.hpp).
std::vector<TargetSpectra> targetsOf(const Sweep& sweep, const GlobalSearchSettings& settings) {
  const cv::Mat weights = wallTarget(sweep, settings);
  const cv::Mat free = sweep.by_free ? sweep.to.free : cv::Mat();
  std::vector<TargetSpectra> targets;
  for (int quarters = 0; quarters < (sweep.quarter_turns ? 4 : 1); ++quarters) {
    const auto turned = [&](const cv::Mat& image) {
      return quarters == 0 || image.empty() ? image
                                            : turnedOnTorus(image, sweep.size.width, quarters);
    };
    targets.push_back(
        targetSpectra(turned(weights), turned(sweep.to.occupied), turned(free), sweep.size));
  }
  return targets;
}

// The rotations of the sweep's full turn.
int rotationCount(const GlobalSearchSettings& settings) {
  return std::max(1, static_cast<int>(std::lround(2.0 * M_PI / settings.rotation_step_rad)));
}

// Whether the sweep turns `from` for the first quarter turn only (GlobalSearchSettings).
bool byQuarterTurns(const GlobalSearchSettings& settings) {
  return settings.quarter_turns && settings.only_rotations_rad.empty() &&
         rotationCount(settings) % 4 == 0;
}

}  // namespace

struct GlobalSweep::Prepared {
  Sweep sweep;
  Eigen::Vector2d centre_from = Eigen::Vector2d::Zero();  // of `from`, fine cells
};

GlobalSweep::PreparedFor GlobalSweep::preparedFor(const GlobalSearchSettings& settings) {
  return {std::max(1, settings.coarse_cells), settings.free_weight,
          settings.free_agreement_hypotheses > 0, byQuarterTurns(settings)};
}

GlobalSweep::GlobalSweep(const GridMap& from, const GridMap& to,
                         const GlobalSearchSettings& settings, const SimilaritySettings& classes)
    : prepared_for_(preparedFor(settings)) {
  if (!from.isValid() || !to.isValid() || from.cells.empty() || to.cells.empty()) {
    return;  // nothing to coarsen
  }
  auto prepared = std::make_unique<Prepared>();
  Sweep& sweep = prepared->sweep;
  sweep.from = coarsen(from, prepared_for_.coarse_cells, classes);
  sweep.to = coarsen(to, prepared_for_.coarse_cells, classes);
  if (cv::countNonZero(sweep.from.occupied) == 0 || cv::countNonZero(sweep.to.occupied) == 0) {
    return;
  }
  Turn& turn = sweep.turn;
  turn.canvas =
      static_cast<int>(std::ceil(std::hypot(sweep.from.occupied.cols, sweep.from.occupied.rows))) +
      2;
  turn.centre_from =
      0.5 * Eigen::Vector2d(sweep.from.occupied.cols - 1, sweep.from.occupied.rows - 1);
  turn.centre_canvas = Eigen::Vector2d::Constant(0.5 * (turn.canvas - 1));
  sweep.by_free = prepared_for_.free_agreement;
  sweep.quarter_turns = prepared_for_.quarter_turns;
  const int width = cv::getOptimalDFTSize(sweep.to.occupied.cols + turn.canvas);
  const int height = cv::getOptimalDFTSize(sweep.to.occupied.rows + turn.canvas);
  sweep.size = sweep.quarter_turns ? cv::Size(std::max(width, height), std::max(width, height))
                                   : cv::Size(width, height);
  sweep.targets = targetsOf(sweep, settings);
  prepared->centre_from = 0.5 * Eigen::Vector2d(from.geometry.width - 1, from.geometry.height - 1);
  prepared_ = std::move(prepared);
}

GlobalSweep::~GlobalSweep() = default;
GlobalSweep::GlobalSweep(GlobalSweep&&) noexcept = default;
GlobalSweep& GlobalSweep::operator=(GlobalSweep&&) noexcept = default;

std::vector<GlobalHypothesis> GlobalSweep::search(const GlobalSearchSettings& settings) const {
  const PreparedFor wanted = preparedFor(settings);
  if (wanted.coarse_cells != prepared_for_.coarse_cells ||
      wanted.free_weight != prepared_for_.free_weight ||
      wanted.free_agreement != prepared_for_.free_agreement ||
      wanted.quarter_turns != prepared_for_.quarter_turns) {
    throw std::invalid_argument(
        "a prepared global sweep is searched with other coarse cells, free weight, free "
        "agreement or quarter turns than it was prepared for");
  }
  if (!prepared_) {
    return {};
  }
  const Sweep& sweep = prepared_->sweep;
  const int rotations = rotationCount(settings);
  std::vector<GlobalHypothesis> all;
  std::vector<GlobalHypothesis> all_by_free;
  for (const RotationPeaks& peaks : sweep.quarter_turns
                                        ? sweepByQuarterTurns(sweep, rotations, settings)
                                        : sweepEachRotation(sweep, rotations, settings)) {
    all.insert(all.end(), peaks.by_walls.begin(), peaks.by_walls.end());
    all_by_free.insert(all_by_free.end(), peaks.by_free.begin(), peaks.by_free.end());
  }
  const double distinct_rad = 1.5 * settings.rotation_step_rad;
  std::vector<GlobalHypothesis> kept =
      bestDistinct(std::move(all), settings.kept_hypotheses, prepared_->centre_from,
                   prepared_for_.coarse_cells, distinct_rad);
  const std::vector<GlobalHypothesis> kept_by_free =
      bestDistinct(std::move(all_by_free), settings.free_agreement_hypotheses,
                   prepared_->centre_from, prepared_for_.coarse_cells, distinct_rad);
  kept.insert(kept.end(), kept_by_free.begin(), kept_by_free.end());
  return kept;
}

std::vector<GlobalHypothesis> globalSearch(const GridMap& from, const GridMap& to,
                                           const GlobalSearchSettings& settings,
                                           const SimilaritySettings& classes) {
  return GlobalSweep(from, to, settings, classes).search(settings);
}

}  // namespace mrslam::fusion
