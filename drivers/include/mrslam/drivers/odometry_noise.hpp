#pragma once
// Realistic odometry for logs whose odometry is perfect (the corrected CARMEN logs re-anchor it to
// the SLAM poses): a SampleSource wrapper that adds seeded noise to every OdometryPose increment
// and integrates the noisy increments, as a drifting odometry would. Per increment u = (x, y, θ)
// of length d = |(x, y)|:
//   x' = x + n_x,  y' = y + n_y,      n_x, n_y ~ N(0, (f d)²)
//   θ' = θ + n_θ,                     n_θ ~ N(0, (f |θ| + a d)²)
// with f = distance_fraction and a = deg_per_m in radians per metre. The first pose is kept;
// every other sample (scans with their true logged poses, ticks, IMU) passes unchanged.

#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>

#include "mrslam/drivers/sample_source.hpp"

namespace mrslam::drivers {

struct OdometryNoiseSettings {
  double distance_fraction = 0.0;  ///< f: σ of x, y per metre of the increment (and of θ per rad)
  double deg_per_m = 0.0;          ///< a: σ of the turn in degrees per metre of the increment
  std::uint64_t seed = 1;          ///< seed of the noise
  bool enabled() const { return distance_fraction > 0.0 || deg_per_m > 0.0; }
};

/// Parses "DIST_FRACTION,DEG_PER_M" (e.g. "0.1,2"); throws std::invalid_argument naming the
/// problem for anything else (negative, not a number, not two values).
OdometryNoiseSettings parseOdometryNoise(const std::string& text);

class OdometryNoiseSource final : public SampleSource {
 public:
  /// Throws std::invalid_argument for a null source or negative settings.
  OdometryNoiseSource(std::unique_ptr<SampleSource> source, const OdometryNoiseSettings& settings);

  std::optional<Sample> next() override;
  /// The wrapped source's description plus the noise, e.g. "... + odometry noise 0.1,2 (seed 7)".
  std::string describe() const override;
  SourceCounters counters() const override { return source_->counters(); }
  std::vector<SensorStatus> sensors() const override { return source_->sensors(); }
  std::optional<double> progress() const override { return source_->progress(); }

 private:
  OdometryPose addNoise(const OdometryPose& odometry);

  std::unique_ptr<SampleSource> source_;
  const OdometryNoiseSettings settings_;
  std::mt19937_64 rng_;
  std::optional<SE2> last_true_;  ///< T_odom_robot of the previous pose, as logged
  SE2 noisy_;                     ///< the integrated noisy pose
};

}  // namespace mrslam::drivers
