// Step 8 of seed_merger.hpp: a coarse-to-fine global search for when no segment pair leads to an
// accepted merge.
//
// 1. Rotation candidates: the strongest peaks of the Radon profile correlation (block 7), each
//    with its other half turn.
// 2. For each rotation, the coarse score of every translation at once, on grids coarsened by
//    `kCoarse`: `from`'s occupied cells, rotated, mark their coarse cells; `to`'s coarse cells
//    weigh +1 where they hold an occupied cell and -kFreeWeight where they are known free only.
//    The cross correlation of the two grids (by DFT) is the coarse score as a function of the
//    translation; its strongest peaks are the candidates.
// 3. Each candidate is scored at full resolution ±kCoarse cells around (CoarseScorer), and the
//    best go through the same translation search and verification as the segment hypotheses.

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "mrslam/fusion/merge/padded_spectrum.hpp"
#include "seed_stages.hpp"

namespace mrslam::fusion::seed {

namespace {

constexpr int kCoarse = 4;           // cells per coarse cell
constexpr double kFreeWeight = 0.5;  // a known free coarse cell under a wall costs this much
constexpr int kPeakSeparation = 3;   // coarse cells between two peaks

// `to` on the coarse grid: +1 where a coarse cell holds an occupied cell, -kFreeWeight where it
// holds known free cells only, 0 where it is unknown.
cv::Mat coarseTarget(const PreparedMap& to, const GridMap& to_map, int free_threshold) {
  const int cols = (to.occupied.cols + kCoarse - 1) / kCoarse;
  const int rows = (to.occupied.rows + kCoarse - 1) / kCoarse;
  cv::Mat target(rows, cols, CV_32F, cv::Scalar(0.0f));
  for (int y = 0; y < to.occupied.rows; ++y) {
    for (int x = 0; x < to.occupied.cols; ++x) {
      float& cell = target.at<float>(y / kCoarse, x / kCoarse);
      const std::int8_t value = to_map.at(x, y);
      if (to.occupied.at<std::uint8_t>(y, x) != 0) {
        cell = 1.0f;
      } else if (value >= 0 && value <= free_threshold && cell == 0.0f) {
        cell = -static_cast<float>(kFreeWeight);
      }
    }
  }
  return target;
}

// `from`'s occupied cells turned by theta on the coarse grid; `corner` is the turned cells'
// lowest corner (cells), the coarse grid's origin.
cv::Mat coarseSource(const std::vector<cv::Point>& occupied, double theta,
                     Eigen::Vector2d& corner) {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  std::vector<Eigen::Vector2d> turned;
  corner = Eigen::Vector2d::Constant(1e18);
  Eigen::Vector2d high = Eigen::Vector2d::Constant(-1e18);
  for (const cv::Point& p : occupied) {
    turned.emplace_back(c * p.x - s * p.y, s * p.x + c * p.y);
    corner = corner.cwiseMin(turned.back());
    high = high.cwiseMax(turned.back());
  }
  const Eigen::Vector2d extent = (high - corner) / kCoarse;
  cv::Mat source(static_cast<int>(extent.y()) + 1, static_cast<int>(extent.x()) + 1, CV_32F,
                 cv::Scalar(0.0f));
  for (const Eigen::Vector2d& q : turned) {
    const Eigen::Vector2d u = (q - corner) / kCoarse;
    source.at<float>(static_cast<int>(u.y()), static_cast<int>(u.x())) = 1.0f;
  }
  return source;
}

// Circular cross correlations c[k] = Σ_u target(u + k) source(u) by DFT, for one target and many
// sources; the target's spectrum is kept for each padded size it was taken at.
class TargetCorrelator {
 public:
  explicit TargetCorrelator(const cv::Mat& target) : target_(target) {}

  cv::Mat correlate(const cv::Mat& source) {
    const cv::Size size(cv::getOptimalDFTSize(target_.cols + source.cols),
                        cv::getOptimalDFTSize(target_.rows + source.rows));
    cv::Mat product;
    cv::mulSpectrums(spectrumOfTarget(size), paddedSpectrum(source, size), product, 0, true);
    cv::Mat correlation;
    cv::idft(product, correlation, cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
    return correlation;
  }

 private:
  const cv::Mat& spectrumOfTarget(const cv::Size& size) {
    for (const auto& [at, kept] : target_spectra_) {
      if (at == size) {
        return kept;
      }
    }
    target_spectra_.emplace_back(size, paddedSpectrum(target_, size));
    return target_spectra_.back().second;
  }

  const cv::Mat& target_;
  std::vector<std::pair<cv::Size, cv::Mat>> target_spectra_;
};

// The strongest peaks of a correlation as coarse shifts (negative shifts wrap around).
std::vector<cv::Point> strongestShifts(cv::Mat correlation, int count) {
  std::vector<cv::Point> shifts;
  for (int i = 0; i < count; ++i) {
    double best = 0.0;
    cv::Point peak;
    cv::minMaxLoc(correlation, nullptr, &best, nullptr, &peak);
    if (best <= 0.0) {
      break;
    }
    shifts.emplace_back(peak.x > correlation.cols / 2 ? peak.x - correlation.cols : peak.x,
                        peak.y > correlation.rows / 2 ? peak.y - correlation.rows : peak.y);
    const int reach = kPeakSeparation;
    for (int dy = -reach; dy <= reach; ++dy) {  // suppress the peak's neighbourhood (wrapping)
      for (int dx = -reach; dx <= reach; ++dx) {
        const int x = (peak.x + dx + correlation.cols) % correlation.cols;
        const int y = (peak.y + dy + correlation.rows) % correlation.rows;
        correlation.at<float>(y, x) = 0.0f;
      }
    }
  }
  return shifts;
}

}  // namespace

std::vector<Hypothesis> fallbackHypotheses(const PreparedMap& from, const PreparedMap& to,
                                           const GridMap& to_map,
                                           const std::vector<double>& radon_correlation,
                                           const CoarseScorer& scorer,
                                           const SeedMergerSettings& settings) {
  std::vector<Hypothesis> hypotheses;
  const std::vector<cv::Point> occupied = nonZeroCells(from.occupied);
  if (occupied.empty()) {
    return hypotheses;
  }
  const cv::Mat target = coarseTarget(to, to_map, settings.similarity.free_threshold);
  TargetCorrelator correlator(target);
  for (const double half_turn :
       rotationCandidates(radon_correlation, settings.fallback_rotations)) {
    for (const double theta : {half_turn, half_turn + M_PI}) {
      Eigen::Vector2d corner;
      const cv::Mat source = coarseSource(occupied, theta, corner);
      for (const cv::Point& shift :
           strongestShifts(correlator.correlate(source), settings.fallback_translations)) {
        GridTransform coarse;
        coarse.theta_rad = std::remainder(theta, 2.0 * M_PI);
        coarse.t_cells = kCoarse * Eigen::Vector2d(shift.x, shift.y) - corner;
        hypotheses.push_back(bestShift(coarse, kCoarse, 2, scorer, Stage::kRadonFallback));
      }
    }
  }
  return hypotheses;
}

}  // namespace mrslam::fusion::seed
