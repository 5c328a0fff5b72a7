// Gx1Settings: checking, and reading from a config section.

#include <cmath>

#include "mrslam/common/config.hpp"
#include "mrslam/drivers/gx1_driver.hpp"

namespace mrslam::drivers {

namespace {

std::chrono::milliseconds secondsToMs(double seconds) {
  return std::chrono::milliseconds(std::llround(seconds * 1000.0));
}

double msToSeconds(std::chrono::milliseconds ms) {
  return static_cast<double>(ms.count()) / 1000.0;
}

std::uint8_t commandFromText(const std::string& text) {
  return static_cast<std::uint8_t>(std::stoul(text, nullptr, 16));
}

}  // namespace

std::string Gx1Settings::check() const {
  if (device.empty()) {
    return "device: must name the serial device";
  }
  if (baud <= 0) {
    return "baud: must be positive";
  }
  if (!gx1::isOrientationCommand(command)) {
    return "command: must be 0x0E, 0x31 or 0x0C";
  }
  if (!(tick_period_s > 0.0 && tick_period_s < 1.0)) {
    return "tick_period_s: must be in (0, 1) s";
  }
  if (read_timeout.count() <= 0 || max_silent_timeouts < 1) {
    return "read_timeout and max_silent_timeouts: must be positive";
  }
  if (reconnect_initial.count() <= 0 || reconnect_max < reconnect_initial) {
    return "reconnect delays: need 0 < initial <= max";
  }
  if (!(clock_drift_allowance >= 0.0 && clock_drift_allowance < 0.1) ||
      !(max_clock_error_s > 0.0)) {
    return "clock_drift_allowance in [0, 0.1) and max_clock_error_s > 0 required";
  }
  return "";
}

Gx1Settings Gx1Settings::fromConfig(const Config& section) {
  Gx1Settings s;
  s.device = section.requirePath("device");
  s.baud = static_cast<int>(section.getInt("baud", s.baud, {1200, 921600}));
  s.mode = section.getChoice("mode", "polled", {"polled", "continuous"}) == "continuous"
               ? Gx1Mode::kContinuous
               : Gx1Mode::kPolled;
  s.command = commandFromText(
      section.getChoice("command", "0x31", {"0x0E", "0x0e", "0x31", "0x0C", "0x0c"}));
  s.tick_period_s = section.getDouble("tick_period_s", s.tick_period_s, {1e-4, 0.1});
  s.read_timeout =
      secondsToMs(section.getDouble("read_timeout_s", msToSeconds(s.read_timeout), {0.005, 10.0}));
  s.max_silent_timeouts =
      static_cast<int>(section.getInt("max_silent_timeouts", s.max_silent_timeouts, {1, 1000}));
  s.reconnect_initial = secondsToMs(
      section.getDouble("reconnect_initial_s", msToSeconds(s.reconnect_initial), {0.001, 60.0}));
  s.reconnect_max = secondsToMs(
      section.getDouble("reconnect_max_s", msToSeconds(s.reconnect_max), {0.001, 600.0}));
  s.device_z_down = section.getBool("device_z_down", s.device_z_down);
  s.quaternion = section.getChoice("quaternion", "sensor_to_earth",
                                   {"sensor_to_earth", "earth_to_sensor"}) == "earth_to_sensor"
                     ? gx1::QuaternionConvention::kEarthToSensor
                     : gx1::QuaternionConvention::kSensorToEarth;
  s.expect_continuous_confirmation =
      section.getBool("expect_continuous_confirmation", s.expect_continuous_confirmation);
  s.clock_drift_allowance =
      section.getDouble("clock_drift_allowance", s.clock_drift_allowance, {0.0, 0.05});
  s.max_clock_error_s = section.getDouble("max_clock_error_s", s.max_clock_error_s, {1e-4, 10.0});
  if (const std::string problem = s.check(); !problem.empty()) {
    section.fail("reconnect_max_s", problem);
  }
  return s;
}

}  // namespace mrslam::drivers
