#pragma once
// Shared by the 3DM-GX1 driver tests: a fixed device state, the samples it must give in robot
// axes, driver settings for ptys, and bounded loops (no test asserts a duration).

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include "mrslam/drivers/gx1_codec.hpp"
#include "mrslam/drivers/gx1_driver.hpp"
#include "mrslam/drivers/gx1_emulator.hpp"

namespace mrslam::drivers::gx1_test {

using namespace std::chrono_literals;

/// Gains other than the defaults, so that reading them from EEPROM matters.
constexpr std::uint16_t kGyroGain = 12000;
constexpr std::uint16_t kAccelGain = 7000;
constexpr std::uint16_t kMagGain = 3000;

/// Every value is an exact multiple of its scale, so polled and decoded values match exactly.
inline gx1::DeviceState fixedState() {
  gx1::DeviceState state;
  state.roll_rad = gx1::angleFromWord(1820);
  state.pitch_rad = gx1::angleFromWord(-1000);
  state.yaw_rad = gx1::angleFromWord(8192);  // 45° clockwise
  state.acceleration_g = {gx1::vectorFromWord(100, kAccelGain),
                          gx1::vectorFromWord(-200, kAccelGain),
                          gx1::vectorFromWord(-4681, kAccelGain)};  // about -1 g: level
  state.angular_rate_rad_s = {gx1::vectorFromWord(1000, kGyroGain),
                              gx1::vectorFromWord(-500, kGyroGain),
                              gx1::vectorFromWord(2000, kGyroGain)};
  state.magnetic_gauss = {gx1::vectorFromWord(3000, kMagGain), 0.0,
                          gx1::vectorFromWord(6000, kMagGain)};
  return state;
}

/// The sample a device in `state` must give for `command`, in robot axes (z up).
inline ImuSample expectedSample(const gx1::DeviceState& state, std::uint8_t command) {
  ImuSample sample;
  sample.roll_rad = state.roll_rad;
  sample.pitch_rad = -state.pitch_rad;
  sample.yaw_rad = -state.yaw_rad;
  const Eigen::Vector3d flip(1.0, -1.0, -1.0);
  if (command == gx1::kEulerCommand) {
    sample.acceleration_g.setConstant(std::nan(""));
    sample.angular_rate_rad_s.setConstant(std::nan(""));
  } else {
    sample.acceleration_g = state.acceleration_g.cwiseProduct(flip);
    sample.angular_rate_rad_s = state.angular_rate_rad_s.cwiseProduct(flip);
  }
  return sample;
}

/// Angles to `angle_tolerance` (0x0C angles come from a quantised quaternion), vectors exactly.
inline void expectSample(const ImuSample& actual, const ImuSample& expected,
                         double angle_tolerance = 1e-12) {
  EXPECT_NEAR(actual.roll_rad, expected.roll_rad, angle_tolerance);
  EXPECT_NEAR(actual.pitch_rad, expected.pitch_rad, angle_tolerance);
  EXPECT_NEAR(actual.yaw_rad, expected.yaw_rad, angle_tolerance);
  for (int i = 0; i < 3; ++i) {
    for (const auto& [got, want] :
         {std::pair{actual.acceleration_g[i], expected.acceleration_g[i]},
          std::pair{actual.angular_rate_rad_s[i], expected.angular_rate_rad_s[i]}}) {
      if (std::isnan(want)) {
        EXPECT_TRUE(std::isnan(got)) << "axis " << i;
      } else {
        EXPECT_NEAR(got, want, 1e-12) << "axis " << i;
      }
    }
  }
}

inline Gx1EmulatorSettings emulatorSettings(const std::string& link_path = "") {
  Gx1EmulatorSettings settings;
  settings.link_path = link_path;
  settings.gyro_gain = kGyroGain;
  settings.accel_gain = kAccelGain;
  settings.mag_gain = kMagGain;
  settings.ticks_per_frame = 3;
  settings.continuous_interval = std::chrono::microseconds(5000);
  return settings;
}

inline Gx1Settings driverSettings(const std::string& device, Gx1Mode mode, std::uint8_t command) {
  Gx1Settings settings;
  settings.device = device;
  settings.mode = mode;
  settings.command = command;
  settings.read_timeout = 250ms;  // generous: other processes may load the machine
  settings.reconnect_initial = 20ms;
  settings.reconnect_max = 100ms;
  return settings;
}

/// Up to `count` samples, polling at most `max_polls` times.
inline std::vector<ImuSample> collect(Gx1Driver& driver, std::size_t count, int max_polls = 100) {
  std::vector<ImuSample> samples;
  for (int poll = 0; poll < max_polls && samples.size() < count; ++poll) {
    if (std::optional<ImuSample> sample = driver.poll(50ms)) {
      samples.push_back(*sample);
    }
  }
  return samples;
}

/// Polls the driver until `done` holds (at most `max_polls` polls).
template <class Done>
bool pollUntil(Gx1Driver& driver, Done done, int max_polls = 200) {
  for (int poll = 0; poll < max_polls; ++poll) {
    if (done()) {
      return true;
    }
    driver.poll(20ms);
  }
  return done();
}

/// Waits (10 ms steps, at most `attempts`) until `done` holds.
template <class Done>
bool waitUntil(Done done, int attempts = 200) {
  for (int attempt = 0; attempt < attempts; ++attempt) {
    if (done()) {
      return true;
    }
    std::this_thread::sleep_for(10ms);
  }
  return done();
}

}  // namespace mrslam::drivers::gx1_test
