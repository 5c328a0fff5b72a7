#include "mrslam/fusion/merge/global_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "mrslam/fusion/merge/padded_spectrum.hpp"

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
      if (value >= classes.occupied_threshold) {
        result.occupied.at<float>(y / coarse, x / coarse) += 1.0f;
      } else if (value >= 0 && value <= classes.free_threshold) {
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

std::vector<Peak> strongestPeaks(cv::Mat scores, int count, int separation) {
  std::vector<Peak> peaks;
  for (int i = 0; i < count; ++i) {
    double best = 0.0;
    cv::Point at;
    cv::minMaxLoc(scores, nullptr, &best, nullptr, &at);
    if (best <= 0.0) {
      break;
    }
    peaks.push_back({Eigen::Vector2d(at.x > scores.cols / 2 ? at.x - scores.cols : at.x,
                                     at.y > scores.rows / 2 ? at.y - scores.rows : at.y),
                     best});
    for (int dy = -separation; dy <= separation; ++dy) {  // wrapping, like the correlation
      for (int dx = -separation; dx <= separation; ++dx) {
        scores.at<float>((at.y + dy + scores.rows) % scores.rows,
                         (at.x + dx + scores.cols) % scores.cols) = 0.0f;
      }
    }
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

}  // namespace

std::vector<GlobalHypothesis> globalSearch(const GridMap& from, const GridMap& to,
                                           const GlobalSearchSettings& settings,
                                           const SimilaritySettings& classes) {
  if (!from.isValid() || !to.isValid() || from.cells.empty() || to.cells.empty()) {
    return {};  // nothing to coarsen
  }
  const int coarse = std::max(1, settings.coarse_cells);
  const CoarseMap coarse_from = coarsen(from, coarse, classes);
  const CoarseMap coarse_to = coarsen(to, coarse, classes);
  if (cv::countNonZero(coarse_from.occupied) == 0 || cv::countNonZero(coarse_to.occupied) == 0) {
    return {};
  }
  Turn turn;
  turn.canvas = static_cast<int>(
                    std::ceil(std::hypot(coarse_from.occupied.cols, coarse_from.occupied.rows))) +
                2;
  turn.centre_from =
      0.5 * Eigen::Vector2d(coarse_from.occupied.cols - 1, coarse_from.occupied.rows - 1);
  turn.centre_canvas = Eigen::Vector2d::Constant(0.5 * (turn.canvas - 1));
  const cv::Size size(cv::getOptimalDFTSize(coarse_to.occupied.cols + turn.canvas),
                      cv::getOptimalDFTSize(coarse_to.occupied.rows + turn.canvas));
  const float w = static_cast<float>(settings.free_weight);
  const cv::Mat target_weights = paddedSpectrum(coarse_to.occupied - w * coarse_to.free, size);
  const cv::Mat target_walls = paddedSpectrum(coarse_to.occupied, size);
  const bool by_free = settings.free_agreement_hypotheses > 0;
  const cv::Mat target_free = by_free ? paddedSpectrum(coarse_to.free, size) : cv::Mat();

  const int rotations =
      std::max(1, static_cast<int>(std::lround(2.0 * M_PI / settings.rotation_step_rad)));
  const cv::Size canvas(turn.canvas, turn.canvas);
  std::vector<GlobalHypothesis> all;
  std::vector<GlobalHypothesis> all_by_free;
  cv::Mat turned_walls;
  cv::Mat turned_free;
  cv::Mat free_spectrum;
  cv::Mat on_walls;
  cv::Mat on_free;
  cv::Mat free_on_free;
  cv::Mat scores;
  cv::Mat free_scores;
  for (int k = 0; k < rotations; ++k) {
    const double theta = 2.0 * M_PI * k / rotations;
    if (!sweeps(theta, settings)) {
      continue;
    }
    const cv::Mat matrix = turn.matrix(theta);
    cv::warpAffine(coarse_from.occupied, turned_walls, matrix, canvas, cv::INTER_LINEAR);
    cv::warpAffine(coarse_from.free, turned_free, matrix, canvas, cv::INTER_LINEAR);
    free_spectrum = paddedSpectrum(turned_free, size);
    cv::mulSpectrums(target_weights, paddedSpectrum(turned_walls, size), on_walls, 0, true);
    cv::mulSpectrums(target_walls, free_spectrum, on_free, 0, true);
    cv::idft(on_walls - w * on_free, scores, cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
    if (by_free) {
      // The same score plus the free cells that meet free cells, weighted (before the peak
      // search below clears the neighbourhoods of its peaks in `scores`).
      cv::mulSpectrums(target_free, free_spectrum, free_on_free, 0, true);
      cv::idft(free_on_free, free_scores, cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
      free_scores = scores + static_cast<float>(settings.free_agreement_weight) * free_scores;
      for (const Peak& peak :
           strongestPeaks(free_scores, settings.peaks_per_rotation, settings.peak_separation)) {
        all_by_free.push_back({fineTransform(turn, theta, peak.shift, coarse), peak.score, true});
      }
    }
    for (const Peak& peak :
         strongestPeaks(scores, settings.peaks_per_rotation, settings.peak_separation)) {
      all.push_back({fineTransform(turn, theta, peak.shift, coarse), peak.score});
    }
  }
  const Eigen::Vector2d centre_from =
      0.5 * Eigen::Vector2d(from.geometry.width - 1, from.geometry.height - 1);
  std::vector<GlobalHypothesis> kept =
      bestDistinct(std::move(all), settings.kept_hypotheses, centre_from, coarse,
                   1.5 * settings.rotation_step_rad);
  const std::vector<GlobalHypothesis> kept_by_free =
      bestDistinct(std::move(all_by_free), settings.free_agreement_hypotheses, centre_from, coarse,
                   1.5 * settings.rotation_step_rad);
  kept.insert(kept.end(), kept_by_free.begin(), kept_by_free.end());
  return kept;
}

}  // namespace mrslam::fusion
