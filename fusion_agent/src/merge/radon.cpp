#include "mrslam/fusion/merge/radon.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace mrslam::fusion {

namespace {

int angleCount(double angle_step_rad) {
  return std::max(1, static_cast<int>(std::lround(M_PI / angle_step_rad)));
}

double at(const std::vector<double>& values, int index) {
  const int size = static_cast<int>(values.size());
  return values[static_cast<std::size_t>(((index % size) + size) % size)];
}

// Sub-step offset in (-0.5, 0.5) of the vertex of the parabola through three samples.
double parabolicOffset(double before, double peak, double after) {
  const double curvature = before - 2.0 * peak + after;
  return curvature < 0.0 ? std::clamp(0.5 * (before - after) / curvature, -0.5, 0.5) : 0.0;
}

// The `count` strongest local maxima of circular `values`, at least `separation` apart, with
// sub-sample positions from a parabola; strongest first.
std::vector<double> strongestPeaks(const std::vector<double>& values, int count, int separation) {
  std::vector<int> peaks;
  const int size = static_cast<int>(values.size());
  for (int j = 0; j < size; ++j) {
    if (at(values, j) > at(values, j - 1) && at(values, j) >= at(values, j + 1)) {
      peaks.push_back(j);
    }
  }
  std::sort(peaks.begin(), peaks.end(),
            [&](int a, int b) { return at(values, a) > at(values, b); });
  std::vector<int> kept;
  for (const int j : peaks) {
    if (static_cast<int>(kept.size()) >= count) {
      break;
    }
    const bool close = std::any_of(kept.begin(), kept.end(), [&](int other) {
      const int gap = std::abs(j - other);
      return std::min(gap, size - gap) < separation;
    });
    if (!close) {
      kept.push_back(j);
    }
  }
  std::vector<double> positions;
  for (const int j : kept) {
    positions.push_back(j + parabolicOffset(at(values, j - 1), at(values, j), at(values, j + 1)));
  }
  return positions;
}

}  // namespace

namespace {

/// The cells about the centre of an image of `size`, and the ρ bins' offset `half`.
struct CentredCells {
  std::vector<float> xs;
  std::vector<float> ys;
  int half = 0;
  CentredCells(const std::vector<cv::Point>& cells, cv::Size size) {
    const double centre_x = 0.5 * (size.width - 1);
    const double centre_y = 0.5 * (size.height - 1);
    half = static_cast<int>(std::ceil(std::hypot(centre_x, centre_y))) + 1;
    for (const cv::Point& cell : cells) {
      xs.push_back(static_cast<float>(cell.x - centre_x));
      ys.push_back(static_cast<float>(cell.y - centre_y));
    }
  }
  int binCount() const { return 2 * half + 2; }
  /// Each cell's ρ bin at angle j of `angles`.
  void binsAt(int j, int angles, std::vector<int>& bins) const {
    const auto c = static_cast<float>(std::cos(j * M_PI / angles));
    const auto s = static_cast<float>(std::sin(j * M_PI / angles));
    // ρ + half + ½ ≥ 0 by the choice of `half`: truncation rounds to the nearest bin. A loop
    // the compiler vectorises.
    bins.resize(xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i) {
      bins[i] = static_cast<int>(xs[i] * c + ys[i] * s + static_cast<float>(half) + 0.5f);
    }
  }
};

}  // namespace

cv::Mat radonTransform(const std::vector<cv::Point>& cells, cv::Size size, double angle_step_rad) {
  const int angles = angleCount(angle_step_rad);
  const CentredCells centred(cells, size);
  cv::Mat radon(angles, centred.binCount(), CV_32F, cv::Scalar(0.0f));
  std::vector<int> bins;
  for (int j = 0; j < angles; ++j) {
    centred.binsAt(j, angles, bins);
    auto* row = radon.ptr<float>(j);
    for (const int bin : bins) {
      row[bin] += 1.0f;
    }
  }
  return radon;
}

RadonPeak radonPeak(const cv::Mat& radon) {
  double value = 0.0;
  cv::Point location;
  cv::minMaxLoc(radon, nullptr, &value, nullptr, &location);
  return {location.y * M_PI / radon.rows, location.x - 0.5 * (radon.cols - 1), value};
}

namespace {

std::vector<double> rowEnergies(const cv::Mat& radon) {
  std::vector<double> energy(static_cast<std::size_t>(radon.rows), 0.0);
  for (int j = 0; j < radon.rows; ++j) {
    const auto* row = radon.ptr<float>(j);
    for (int i = 0; i < radon.cols; ++i) {
      energy[static_cast<std::size_t>(j)] += static_cast<double>(row[i]) * row[i];
    }
  }
  return energy;
}

// The high-passed, normalised profile of the angles' energies.
std::vector<double> spectrumOfEnergies(const std::vector<double>& energy, double highpass_rad) {
  const int angles = static_cast<int>(energy.size());
  const int reach = static_cast<int>(std::lround(highpass_rad / (M_PI / angles)));
  std::vector<double> spectrum(energy.size(), 0.0);
  for (int j = 0; j < angles; ++j) {
    double background = 0.0;
    for (int i = j - reach; i <= j + reach; ++i) {
      background += at(energy, i);
    }
    spectrum[static_cast<std::size_t>(j)] = at(energy, j) - background / (2 * reach + 1);
  }
  const double mean =
      std::accumulate(spectrum.begin(), spectrum.end(), 0.0) / static_cast<double>(angles);
  double variance = 0.0;
  for (double& value : spectrum) {
    value -= mean;
    variance += value * value;
  }
  const double deviation = std::sqrt(variance / static_cast<double>(angles));
  if (deviation > 0.0) {
    for (double& value : spectrum) {
      value /= deviation;
    }
  }
  return spectrum;
}

}  // namespace

std::vector<double> radonSpectrum(const cv::Mat& radon, double highpass_rad) {
  return spectrumOfEnergies(rowEnergies(radon), highpass_rad);
}

std::vector<double> radonSpectrumOfCells(const std::vector<cv::Point>& cells, cv::Size size,
                                         double angle_step_rad, double highpass_rad) {
  const int angles = angleCount(angle_step_rad);
  const CentredCells centred(cells, size);
  std::vector<double> energy(static_cast<std::size_t>(angles), 0.0);
  std::vector<int> bins;
  std::vector<float> counts(static_cast<std::size_t>(centred.binCount()));
  for (int j = 0; j < angles; ++j) {
    centred.binsAt(j, angles, bins);
    std::fill(counts.begin(), counts.end(), 0.0f);
    for (const int bin : bins) {
      counts[static_cast<std::size_t>(bin)] += 1.0f;
    }
    // As rowEnergies() sums a row of the image: the same values in the same order.
    double sum = 0.0;
    for (const float count : counts) {
      sum += static_cast<double>(count) * count;
    }
    energy[static_cast<std::size_t>(j)] = sum;
  }
  return spectrumOfEnergies(energy, highpass_rad);
}

std::vector<double> spectrumCorrelation(const std::vector<double>& spectrum_from,
                                        const std::vector<double>& spectrum_to) {
  const int size = static_cast<int>(spectrum_from.size());
  std::vector<double> correlation(spectrum_from.size(), 0.0);
  for (int j = 0; j < size; ++j) {
    double sum = 0.0;
    for (int i = 0; i < size; ++i) {
      sum += spectrum_from[static_cast<std::size_t>(i)] * at(spectrum_to, i + j);
    }
    correlation[static_cast<std::size_t>(j)] = sum / size;
  }
  return correlation;
}

std::optional<double> tuneRotation(const std::vector<double>& correlation,
                                   double approximate_theta_rad, double window_rad) {
  const double angle_step_rad = M_PI / static_cast<double>(correlation.size());
  const double half_turn = std::fmod(std::fmod(approximate_theta_rad, M_PI) + M_PI, M_PI);
  const int centre = static_cast<int>(std::lround(half_turn / angle_step_rad));
  const int reach = std::max(1, static_cast<int>(std::lround(window_rad / angle_step_rad)));
  int best = centre - reach;
  for (int j = centre - reach; j <= centre + reach; ++j) {
    if (at(correlation, j) > at(correlation, best)) {
      best = j;
    }
  }
  if (best == centre - reach || best == centre + reach) {
    return std::nullopt;
  }
  const double peak = (best + parabolicOffset(at(correlation, best - 1), at(correlation, best),
                                              at(correlation, best + 1))) *
                      angle_step_rad;
  return approximate_theta_rad + (peak - half_turn);
}

std::vector<double> rotationCandidates(const std::vector<double>& correlation, int count) {
  std::vector<double> angles = strongestPeaks(correlation, count, 1);
  for (double& angle : angles) {
    angle *= M_PI / static_cast<double>(correlation.size());
  }
  return angles;
}

}  // namespace mrslam::fusion
