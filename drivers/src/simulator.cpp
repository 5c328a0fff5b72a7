#include "mrslam/drivers/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "route_follower.hpp"

namespace mrslam::drivers {
namespace {

constexpr std::int64_t kCommandPeriodNs = 10'000'000;  // the follower commands at 100 Hz
constexpr double kCommandPeriodS = 1e-9 * kCommandPeriodNs;
constexpr double kGravityM_S2 = 9.80665;

// A standard normal draw by Box–Muller from 53-bit uniforms: the same numbers with every
// standard library (std::normal_distribution's algorithm is left to the implementation).
double standardNormal(std::mt19937_64& rng) {
  constexpr double kTwoToMinus53 = 1.0 / 9007199254740992.0;
  const double u1 = (static_cast<double>(rng() >> 11) + 1.0) * kTwoToMinus53;  // (0, 1]
  const double u2 = static_cast<double>(rng() >> 11) * kTwoToMinus53;          // [0, 1)
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

void checkDrive(const DiffDriveParams& drive) {
  if (!(drive.wheel_radius_m > 0.0) || !(drive.track_width_m > 0.0) ||
      !(drive.ticks_per_revolution > 0.0)) {
    throw std::invalid_argument(
        "simulator: wheel radius, track width and ticks per revolution must be positive");
  }
}

}  // namespace

Simulator::Simulator(const SimulatorSettings& settings, const DiffDriveParams& drive,
                     const SensorMounting& mounting)
    : settings_(settings), drive_(drive), mounting_(mounting), plan_(builtInFloorPlan()) {
  checkSimulatorSettings(settings_);
  checkDrive(drive_);
  const MotionLimits limits{settings_.max_speed_m_s, settings_.max_turn_rate_rad_s,
                            settings_.max_acceleration_m_s2,
                            settings_.max_angular_acceleration_rad_s2};
  follower_ = std::make_unique<RouteFollower>(builtInRoute(settings_.robot_index), limits);
  truth_.pose = builtInStartPose(settings_.robot_index);

  start_ns_ = Stamp::fromSeconds(settings_.start_time_s).ns;
  end_ns_ = start_ns_ + Stamp::fromSeconds(settings_.duration_s).ns;
  now_ns_ = start_ns_;
  next_command_ns_ = start_ns_;
  ticks_stream_.rate_hz = settings_.encoder_rate_hz;
  imu_stream_.rate_hz = settings_.imu_rate_hz;
  laser_stream_.rate_hz = settings_.laser_rate_hz;
  for (Stream* stream : {&ticks_stream_, &imu_stream_, &laser_stream_}) {
    schedule(*stream);
  }

  // One seeded engine; each sensor draws from its own stream seeded by it, so that changing one
  // sensor's rate leaves the others' noise as it was.
  std::mt19937_64 master(settings_.seed);
  laser_rng_.seed(master());
  encoder_rng_.seed(master());
  imu_rng_.seed(master());
  encoders_.left_scale = 1.0 + noise(encoder_rng_, settings_.encoder_scale_sigma);
  encoders_.right_scale = 1.0 + noise(encoder_rng_, settings_.encoder_scale_sigma);
}

Simulator::~Simulator() = default;

std::optional<Sample> Simulator::next() {
  // Earliest stream first; at equal stamps the order below (ticks, IMU, laser) decides.
  Stream* earliest = &ticks_stream_;
  for (Stream* stream : {&imu_stream_, &laser_stream_}) {
    if (stream->next_ns < earliest->next_ns) {
      earliest = stream;
    }
  }
  if (earliest->next_ns >= end_ns_) {
    return std::nullopt;
  }
  advanceTo(earliest->next_ns);
  const Stamp stamp = Stamp::fromNanoseconds(earliest->next_ns);
  std::optional<Sample> sample;
  if (earliest == &ticks_stream_) {
    sample = makeTicks(stamp);
  } else if (earliest == &imu_stream_) {
    sample = makeImu(stamp);
  } else {
    sample = makeScan(stamp);
  }
  ++earliest->count;
  schedule(*earliest);
  ++counters_.samples;
  return sample;
}

std::string Simulator::describe() const {
  std::ostringstream text;
  text << "simulator robot " << settings_.robot_index << " (seed " << settings_.seed << ", "
       << settings_.duration_s << " s)";
  return text.str();
}

void Simulator::schedule(Stream& stream) const {
  stream.next_ns =
      start_ns_ + std::llround(static_cast<double>(stream.count) * 1e9 / stream.rate_hz);
}

void Simulator::advanceTo(std::int64_t t_ns) {
  while (now_ns_ < t_ns) {
    if (now_ns_ >= next_command_ns_) {
      const VelocityCommand now{truth_.v_m_s, truth_.omega_rad_s};
      const VelocityCommand command = follower_->update(truth_.pose, now, kCommandPeriodS);
      truth_.acceleration_m_s2 = (command.v_m_s - truth_.v_m_s) / kCommandPeriodS;
      truth_.v_m_s = command.v_m_s;
      truth_.omega_rad_s = command.omega_rad_s;
      next_command_ns_ += kCommandPeriodNs;
    }
    const std::int64_t step_end = std::min(t_ns, next_command_ns_);
    integrate(1e-9 * static_cast<double>(step_end - now_ns_));
    now_ns_ = step_end;
  }
}

void Simulator::integrate(double dt) {
  // Constant (v, ω) over dt: the robot moves along an exact circular arc (a line when ω = 0).
  const double v = truth_.v_m_s;
  const double omega = truth_.omega_rad_s;
  const double theta = truth_.pose.theta();
  double dx = 0.0;
  double dy = 0.0;
  if (std::abs(omega) < 1e-9) {
    dx = v * dt * std::cos(theta);
    dy = v * dt * std::sin(theta);
  } else {
    dx = v / omega * (std::sin(theta + omega * dt) - std::sin(theta));
    dy = v / omega * (std::cos(theta) - std::cos(theta + omega * dt));
  }
  truth_.pose = SE2(truth_.pose.x() + dx, truth_.pose.y() + dy, theta + omega * dt);
  const double half_track = 0.5 * drive_.track_width_m;
  truth_.left_wheel_rad += (v - omega * half_track) * dt / drive_.wheel_radius_m;
  truth_.right_wheel_rad += (v + omega * half_track) * dt / drive_.wheel_radius_m;
}

double Simulator::noise(std::mt19937_64& rng, double sigma) const {
  return settings_.noise_enabled ? sigma * standardNormal(rng) : 0.0;
}

LaserScan Simulator::makeScan(Stamp stamp) {
  LaserScan scan;
  scan.stamp = stamp;
  scan.angle_min_rad = kLaserAngleMinRad;
  scan.angle_increment_rad = kLaserAngleIncrementRad;
  scan.range_min_m = kLaserRangeMinM;
  scan.range_max_m = kLaserRangeMaxM;
  scan.logged_pose = truth_.pose;

  const SE2 T_world_laser = truth_.pose * mounting_.T_robot_laser;
  const Eigen::Vector2d origin = T_world_laser.translation();
  // Only walls within range can be hit (the margin covers the end-point tolerance of a hit).
  const FloorPlan near = plan_.wallsNear(origin, kLaserRangeMaxM + 1e-6);
  scan.ranges_m.resize(kLaserBeamCount);
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const std::optional<double> hit =
        near.castRay(origin, T_world_laser.theta() + scan.beamAngle(i), kLaserRangeMaxM);
    if (!hit) {
      scan.ranges_m[i] = LaserScan::kNoReturn;
      continue;
    }
    const double range = *hit + noise(laser_rng_, settings_.laser_range_sigma_m);
    if (range > kLaserRangeMaxM) {
      scan.ranges_m[i] = LaserScan::kNoReturn;
    } else if (range < kLaserRangeMinM) {
      scan.ranges_m[i] = LaserScan::kInvalid;  // too close: the device reports an error
    } else {
      scan.ranges_m[i] = static_cast<float>(range);
    }
  }
  return scan;
}

WheelTicks Simulator::makeTicks(Stamp stamp) {
  const double counts_per_rad = drive_.ticks_per_revolution / (2.0 * M_PI);
  const double sigma = settings_.encoder_slip_sigma;
  // Left first, then right: the draws happen in a fixed order.
  const double left = (truth_.left_wheel_rad - encoders_.left_wheel_rad) * counts_per_rad;
  encoders_.left_counts +=
      left * encoders_.left_scale + noise(encoder_rng_, sigma * std::abs(left));
  const double right = (truth_.right_wheel_rad - encoders_.right_wheel_rad) * counts_per_rad;
  encoders_.right_counts +=
      right * encoders_.right_scale + noise(encoder_rng_, sigma * std::abs(right));
  encoders_.left_wheel_rad = truth_.left_wheel_rad;
  encoders_.right_wheel_rad = truth_.right_wheel_rad;

  WheelTicks ticks;
  ticks.stamp = stamp;
  // Whole counts seen so far; the fraction stays in the cumulative count for the next reading.
  ticks.left = static_cast<std::int64_t>(std::floor(encoders_.left_counts));
  ticks.right = static_cast<std::int64_t>(std::floor(encoders_.right_counts));
  return ticks;
}

ImuSample Simulator::makeImu(Stamp stamp) {
  ImuSample imu;
  imu.stamp = stamp;
  imu.has_orientation = true;
  imu.roll_rad = noise(imu_rng_, settings_.imu_tilt_sigma_rad);
  imu.pitch_rad = noise(imu_rng_, settings_.imu_tilt_sigma_rad);
  imu.yaw_rad = wrapAngle(truth_.pose.theta() + mounting_.imu_yaw_offset_rad +
                          noise(imu_rng_, settings_.imu_yaw_sigma_rad));

  const double bias = settings_.noise_enabled ? settings_.imu_rate_bias_rad_s : 0.0;
  imu.angular_rate_rad_s.x() = noise(imu_rng_, settings_.imu_rate_sigma_rad_s);
  imu.angular_rate_rad_s.y() = noise(imu_rng_, settings_.imu_rate_sigma_rad_s);
  imu.angular_rate_rad_s.z() =
      truth_.omega_rad_s + bias + noise(imu_rng_, settings_.imu_rate_sigma_rad_s);

  // Forward and centripetal acceleration in the robot frame, turned into the IMU's frame.
  const Eigen::Vector2d robot_g(truth_.acceleration_m_s2 / kGravityM_S2,
                                truth_.v_m_s * truth_.omega_rad_s / kGravityM_S2);
  const Eigen::Vector2d imu_g = SE2(0.0, 0.0, -mounting_.imu_yaw_offset_rad) * robot_g;
  imu.acceleration_g.x() = imu_g.x() + noise(imu_rng_, settings_.imu_acceleration_sigma_g);
  imu.acceleration_g.y() = imu_g.y() + noise(imu_rng_, settings_.imu_acceleration_sigma_g);
  imu.acceleration_g.z() = 1.0 + noise(imu_rng_, settings_.imu_acceleration_sigma_g);
  return imu;
}

std::optional<double> Simulator::progress() const {
  const double span = static_cast<double>(end_ns_ - start_ns_);
  return span > 0.0 ? std::clamp(static_cast<double>(now_ns_ - start_ns_) / span, 0.0, 1.0) : 1.0;
}

}  // namespace mrslam::drivers
