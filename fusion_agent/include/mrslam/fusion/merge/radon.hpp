#pragma once
// Block 7 of the seed merge: rotation tuning with Radon images.
//
// 1. The Radon image of a map's edge cells R(φ, ρ), φ over [0°, 180°) in `angle_step` steps and
//    ρ in bins of one cell about the image centre: every cell adds 1 to the line
//    x cos φ + y sin φ = ρ through it (in the nearest ρ bin).
// 2. A translation shifts each column of R along ρ but keeps its energy, so the angular profile
//    S(φ) = Σ_ρ R(φ, ρ)² depends on the rotation only: rotating a map by θ shifts S by θ
//    (modulo 180°). Clutter and the map's outline add a smooth background to S that blurs the
//    correlation below, so S minus its moving average over ±`profile_highpass` is kept (the
//    sharp peaks of straight walls), normalised to zero mean and unit variance.
// 3. The circular cross correlation C(θ) = mean_φ S_from(φ) S_to(φ + θ) peaks at the rotation
//    between the maps. The tuned rotation is the peak of C within ±`rotation_window` of the
//    approximate angle (modulo 180°), refined between steps by a parabola through the peak and
//    its neighbours; it keeps the approximate angle's half turn. No peak inside the window (the
//    maximum on its border) means the approximate angle was wrong.
// 4. For the fallback (seed_merger.hpp), rotationCandidates() lists the strongest peaks of C
//    over the whole half turn.

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace mrslam::fusion {

/// Settings of block 7.
struct RadonSettings {
  double angle_step_rad = 1.0 * M_PI / 180.0;        ///< angular step of the Radon images
  double rotation_window_rad = 5.0 * M_PI / 180.0;   ///< the peak is sought this far around
  double profile_highpass_rad = 5.0 * M_PI / 180.0;  ///< half width of the background removed
};

/// A peak of a Radon image.
struct RadonPeak {
  double angle_rad = 0.0;  ///< φ of the line's normal, in [0, π)
  double rho = 0.0;        ///< signed distance (cells) of the line from the image centre
  double value = 0.0;      ///< cells on the line
};

/// Block 7.1: the Radon image (CV_32F, rows = angles j · π / rows, cols = ρ bins) of cells of
/// an image of `size`; the step is π / round(π / angle_step_rad).
cv::Mat radonTransform(const std::vector<cv::Point>& cells, cv::Size size, double angle_step_rad);

/// The strongest line of a Radon image.
RadonPeak radonPeak(const cv::Mat& radon);

/// Block 7.2: the high-passed, normalised angular energy profile S(φ) of a Radon image.
std::vector<double> radonSpectrum(const cv::Mat& radon, double highpass_rad);

/// The same profile of `cells` without the Radon image: each angle's counts are made in one row
/// and its energy Σ_ρ R(φ, ρ)² taken at once; equal to
/// radonSpectrum(radonTransform(cells, size, angle_step_rad), highpass_rad).
std::vector<double> radonSpectrumOfCells(const std::vector<cv::Point>& cells, cv::Size size,
                                         double angle_step_rad, double highpass_rad);

/// Block 7.3: C(θ_j) for θ_j = j · π / size, j = 0 … size-1 (profiles of equal size).
std::vector<double> spectrumCorrelation(const std::vector<double>& spectrum_from,
                                        const std::vector<double>& spectrum_to);

/// Block 7.3: the rotation tuned near `approximate_theta_rad`, or nothing without a peak there.
std::optional<double> tuneRotation(const std::vector<double>& correlation,
                                   double approximate_theta_rad, double window_rad);

/// Block 7.4: the `count` strongest local maxima of C in [0, π), strongest first.
std::vector<double> rotationCandidates(const std::vector<double>& correlation, int count);

}  // namespace mrslam::fusion
