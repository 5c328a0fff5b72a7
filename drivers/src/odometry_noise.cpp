#include "mrslam/drivers/odometry_noise.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mrslam::drivers {

namespace {

double parseNonNegative(const std::string& text, const std::string& what) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value) || value < 0.0) {
    throw std::invalid_argument("odometry noise: " + what + " '" + text + "' is not a number >= 0");
  }
  return value;
}

}  // namespace

OdometryNoiseSettings parseOdometryNoise(const std::string& text) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) {
    throw std::invalid_argument("odometry noise: '" + text +
                                "' is not DIST_FRACTION,DEG_PER_M (e.g. 0.1,2)");
  }
  OdometryNoiseSettings settings;
  settings.distance_fraction = parseNonNegative(text.substr(0, comma), "DIST_FRACTION");
  settings.deg_per_m = parseNonNegative(text.substr(comma + 1), "DEG_PER_M");
  return settings;
}

OdometryNoiseSource::OdometryNoiseSource(std::unique_ptr<SampleSource> source,
                                         const OdometryNoiseSettings& settings)
    : source_(std::move(source)), settings_(settings), rng_(settings.seed) {
  if (!source_) {
    throw std::invalid_argument("OdometryNoiseSource: no source");
  }
  if (!(settings.distance_fraction >= 0.0) || !(settings.deg_per_m >= 0.0)) {
    throw std::invalid_argument("OdometryNoiseSource: noise must be >= 0");
  }
}

std::optional<Sample> OdometryNoiseSource::next() {
  std::optional<Sample> sample = source_->next();
  if (sample) {
    if (const auto* odometry = std::get_if<OdometryPose>(&*sample)) {
      return Sample{addNoise(*odometry)};
    }
  }
  return sample;
}

OdometryPose OdometryNoiseSource::addNoise(const OdometryPose& odometry) {
  if (!last_true_) {
    last_true_ = odometry.T_odom_robot;
    noisy_ = odometry.T_odom_robot;
    return odometry;
  }
  const SE2 increment = last_true_->inverse() * odometry.T_odom_robot;
  last_true_ = odometry.T_odom_robot;
  const double distance = increment.translation().norm();
  const double sigma_xy = settings_.distance_fraction * distance;
  const double sigma_theta = settings_.distance_fraction * std::abs(increment.theta()) +
                             settings_.deg_per_m * M_PI / 180.0 * distance;
  std::normal_distribution<double> unit(0.0, 1.0);
  const double nx = sigma_xy * unit(rng_);
  const double ny = sigma_xy * unit(rng_);
  const double ntheta = sigma_theta * unit(rng_);
  noisy_ = noisy_ * SE2(increment.x() + nx, increment.y() + ny, increment.theta() + ntheta);
  return OdometryPose{odometry.stamp, noisy_};
}

std::string OdometryNoiseSource::describe() const {
  std::ostringstream text;
  text << source_->describe() << " + odometry noise " << settings_.distance_fraction << ','
       << settings_.deg_per_m << " (seed " << settings_.seed << ')';
  return text.str();
}

}  // namespace mrslam::drivers
