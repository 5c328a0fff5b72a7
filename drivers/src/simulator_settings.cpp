// Loading and checking SimulatorSettings: one table of keys and ranges serves both.

#include <sstream>
#include <stdexcept>
#include <string>

#include "mrslam/drivers/simulator.hpp"

namespace mrslam::drivers {
namespace {

struct DoubleField {
  const char* key;
  double SimulatorSettings::*field;
  Range range;
};

const DoubleField kDoubleFields[] = {
    {"duration_s", &SimulatorSettings::duration_s, {1e-3, 1e6}},
    {"start_time_s", &SimulatorSettings::start_time_s, {0.0, 4e9}},
    {"max_speed_m_s", &SimulatorSettings::max_speed_m_s, {0.01, 2.0}},
    {"max_turn_rate_rad_s", &SimulatorSettings::max_turn_rate_rad_s, {0.05, 6.0}},
    {"max_acceleration_m_s2", &SimulatorSettings::max_acceleration_m_s2, {0.05, 10.0}},
    {"max_angular_acceleration_rad_s2",
     &SimulatorSettings::max_angular_acceleration_rad_s2,
     {0.1, 50.0}},
    {"laser_rate_hz", &SimulatorSettings::laser_rate_hz, {0.1, 100.0}},
    {"laser_range_sigma_m", &SimulatorSettings::laser_range_sigma_m, {0.0, 0.5}},
    {"encoder_rate_hz", &SimulatorSettings::encoder_rate_hz, {1.0, 1000.0}},
    {"encoder_scale_sigma", &SimulatorSettings::encoder_scale_sigma, {0.0, 0.1}},
    {"encoder_slip_sigma", &SimulatorSettings::encoder_slip_sigma, {0.0, 1.0}},
    {"imu_rate_hz", &SimulatorSettings::imu_rate_hz, {1.0, 1000.0}},
    {"imu_yaw_sigma_rad", &SimulatorSettings::imu_yaw_sigma_rad, {0.0, 1.0}},
    {"imu_rate_sigma_rad_s", &SimulatorSettings::imu_rate_sigma_rad_s, {0.0, 1.0}},
    {"imu_rate_bias_rad_s", &SimulatorSettings::imu_rate_bias_rad_s, {-1.0, 1.0}},
    {"imu_tilt_sigma_rad", &SimulatorSettings::imu_tilt_sigma_rad, {0.0, 0.5}},
    {"imu_acceleration_sigma_g", &SimulatorSettings::imu_acceleration_sigma_g, {0.0, 1.0}},
};

const Range kRobotIndexRange{0.0, kBuiltInRouteCount - 1.0};
const Range kSeedRange{0.0, 9007199254740992.0};  // 2^53: every integer up to it is exact

bool inRange(double value, Range range) {
  return value >= range.min && value <= range.max;
}

[[noreturn]] void failRange(const std::string& key, double value, Range range) {
  std::ostringstream text;
  text << "simulator setting " << key << " = " << value << " must be in [" << range.min << ", "
       << range.max << "]";
  throw std::invalid_argument(text.str());
}

}  // namespace

SimulatorSettings loadSimulatorSettings(const Config& section) {
  SimulatorSettings settings;
  settings.robot_index =
      static_cast<int>(section.getInt("robot_index", settings.robot_index, kRobotIndexRange));
  settings.seed = static_cast<std::uint64_t>(
      section.getInt("seed", static_cast<long long>(settings.seed), kSeedRange));
  settings.noise_enabled = section.getBool("noise_enabled", settings.noise_enabled);
  for (const DoubleField& field : kDoubleFields) {
    settings.*field.field = section.getDouble(field.key, settings.*field.field, field.range);
  }
  return settings;
}

void checkSimulatorSettings(const SimulatorSettings& settings) {
  if (!inRange(settings.robot_index, kRobotIndexRange)) {
    failRange("robot_index", settings.robot_index, kRobotIndexRange);
  }
  for (const DoubleField& field : kDoubleFields) {
    if (!inRange(settings.*field.field, field.range)) {  // also catches NaN
      failRange(field.key, settings.*field.field, field.range);
    }
  }
}

}  // namespace mrslam::drivers
