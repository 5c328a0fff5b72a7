// mrslam_imu: checks a MicroStrain 3DM-GX1 on a serial port: reads its gains and prints samples.
//   mrslam_imu DEVICE [--count N] [--json] [--mode polled|continuous] [--command 0x31]
// --json prints one object per line: first {"gains": {...}}, then per sample
//   {"ticks": n, "roll": r, "pitch": p, "yaw": y, "accel": [ax, ay, az], "rate": [wx, wy, wz]}
// in rad, m/s² and rad/s, robot axes (z up, counter-clockwise); ticks are the device timer,
// unwrapped. A value the command does not carry (0x0E: accel, rate) is null.
// Exit 0 after N samples; 2 with a one-line reason when the device does not answer, answers
// garbage or vanishes (CLI11's own codes for bad arguments).

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "mrslam/common/version.hpp"
#include "mrslam/drivers/gx1_driver.hpp"

namespace {

using mrslam::ImuSample;
using mrslam::drivers::Gx1Driver;
using mrslam::drivers::Gx1Mode;
using mrslam::drivers::Gx1Settings;

constexpr double kStandardGravity = 9.80665;  // m/s² per g
constexpr double kDegreesPerRadian = 180.0 / M_PI;

struct Options {
  std::string device;
  int count = 5;
  bool json = false;
  std::string mode = "polled";
  std::string command = "0x31";
  double timeout_s = 2.0;
  double tick_period_ms = 6.5536;
  int baud = 38400;
  bool raw_axes = false;
  bool verbose = false;
};

Gx1Settings settingsFrom(const Options& options) {
  Gx1Settings settings;
  settings.device = options.device;
  settings.baud = options.baud;
  settings.mode = options.mode == "continuous" ? Gx1Mode::kContinuous : Gx1Mode::kPolled;
  settings.command = static_cast<std::uint8_t>(std::stoul(options.command, nullptr, 16));
  settings.tick_period_s = options.tick_period_ms / 1000.0;
  settings.device_z_down = !options.raw_axes;
  return settings;
}

nlohmann::ordered_json vectorJson(const Eigen::Vector3d& v, double scale) {
  nlohmann::ordered_json values = nlohmann::ordered_json::array();
  for (int i = 0; i < 3; ++i) {
    values.push_back(std::isfinite(v[i]) ? nlohmann::ordered_json(v[i] * scale) : nullptr);
  }
  return values;
}

void printGains(const mrslam::drivers::gx1::Gains& gains, bool json) {
  if (json) {
    nlohmann::ordered_json line;
    // Raw EEPROM values: integers.
    line["gains"] = {{"gyro", std::lround(gains.gyro)},
                     {"accel", std::lround(gains.accel)},
                     {"mag", std::lround(gains.mag)}};
    std::cout << line.dump() << std::endl;
    return;
  }
  std::printf("gains: gyro %.0f, accel %.0f, mag %.0f (EEPROM 130, 230, 232)\n", gains.gyro,
              gains.accel, gains.mag);
}

void printSample(const ImuSample& s, std::uint64_t ticks, bool json) {
  const Eigen::Vector3d accel = s.acceleration_g * kStandardGravity;
  const Eigen::Vector3d& rate = s.angular_rate_rad_s;
  if (json) {
    nlohmann::ordered_json line;
    line["ticks"] = ticks;
    line["roll"] = s.roll_rad;
    line["pitch"] = s.pitch_rad;
    line["yaw"] = s.yaw_rad;
    line["accel"] = vectorJson(s.acceleration_g, kStandardGravity);
    line["rate"] = vectorJson(s.angular_rate_rad_s, 1.0);
    std::cout << line.dump() << std::endl;
    return;
  }
  std::printf(
      "ticks %8llu  roll %7.2f°  pitch %7.2f°  yaw %7.2f°  accel [%6.2f %6.2f %6.2f] m/s²  "
      "rate [%7.3f %7.3f %7.3f] rad/s\n",
      static_cast<unsigned long long>(ticks), s.roll_rad * kDegreesPerRadian,
      s.pitch_rad * kDegreesPerRadian, s.yaw_rad * kDegreesPerRadian, accel.x(), accel.y(),
      accel.z(), rate.x(), rate.y(), rate.z());
}

// The tick period as the host sees it (receipt times, not the stamps, which follow the setting),
// to check the tick_period setting (*unsure*). More samples give a better estimate.
void printSummary(const Gx1Driver& driver, std::chrono::steady_clock::duration elapsed,
                  std::uint64_t ticks) {
  const auto health = driver.health();
  std::printf("%llu samples, %llu time-outs, %llu bad checksums, %llu stray bytes\n",
              static_cast<unsigned long long>(health.samples),
              static_cast<unsigned long long>(health.timeouts),
              static_cast<unsigned long long>(health.parser.bad_checksums),
              static_cast<unsigned long long>(health.parser.garbage_bytes));
  if (ticks > 0) {
    const double period_ms =
        std::chrono::duration<double, std::milli>(elapsed).count() / static_cast<double>(ticks);
    std::printf("tick period: about %.3f ms seen by the host, %.4f ms set\n", period_ms,
                driver.settings().tick_period_s * 1000.0);
  }
}

int fail(const std::string& device, const std::string& reason) {
  // Port errors name the device already.
  const bool named = reason.rfind(device + ": ", 0) == 0;
  std::fprintf(stderr, "mrslam_imu: %s\n", (named ? reason : device + ": " + reason).c_str());
  return 2;
}

int run(const Options& options) {
  Gx1Driver driver(settingsFrom(options));
  const auto timeout = std::chrono::milliseconds(std::llround(options.timeout_s * 1000.0));
  std::chrono::steady_clock::time_point first_receipt;
  std::uint64_t first_ticks = 0;
  for (int printed = 0; printed < options.count; ++printed) {
    const std::optional<ImuSample> sample = driver.poll(timeout);
    const auto receipt = std::chrono::steady_clock::now();
    const auto health = driver.health();
    if (health.disconnects > 0) {
      return fail(options.device, health.last_loss);
    }
    if (health.failed_startups > 0) {
      return fail(options.device, health.last_error);
    }
    if (!sample) {
      return fail(options.device, "no sample within " + std::to_string(options.timeout_s) + " s");
    }
    if (printed == 0) {
      printGains(driver.gains(), options.json);
      first_receipt = receipt;
      first_ticks = driver.lastUnwrappedTicks();
    }
    printSample(*sample, driver.lastUnwrappedTicks(), options.json);
    if (!options.json && printed + 1 == options.count) {
      printSummary(driver, receipt - first_receipt, driver.lastUnwrappedTicks() - first_ticks);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{"Checks a MicroStrain 3DM-GX1: prints its gains and a few samples."};
  app.add_option("device", options.device, "serial device, e.g. /dev/ttyUSB0")->required();
  app.add_option("--count", options.count, "samples to print")->check(CLI::Range(1, 1000000));
  app.add_flag("--json", options.json, "one JSON object per line (rad, m/s², rad/s)");
  app.add_option("--mode", options.mode, "polled or continuous")
      ->check(CLI::IsMember({"polled", "continuous"}));
  app.add_option("--command", options.command, "0x0E (Euler), 0x31 (Euler + vectors), 0x0C")
      ->check(CLI::IsMember({"0x0E", "0x0e", "0x31", "0x0C", "0x0c"}));
  app.add_option("--timeout", options.timeout_s, "seconds to wait for each sample")
      ->check(CLI::Range(0.01, 600.0));
  app.add_option("--tick-period-ms", options.tick_period_ms, "device timer period (unsure)")
      ->check(CLI::Range(0.1, 100.0));
  app.add_option("--baud", options.baud, "baud rate");
  app.add_flag("--raw-axes", options.raw_axes, "device axes as sent (no z-down to z-up turn)");
  app.add_flag("--verbose", options.verbose, "log the driver's warnings on stderr");
  app.set_version_flag("--version", mrslam::versionLine("imu"));
  CLI11_PARSE(app, argc, argv);
  // Logs go to stderr so that stdout stays clean JSON.
  spdlog::set_default_logger(spdlog::stderr_color_mt("mrslam_imu"));
  spdlog::set_level(options.verbose ? spdlog::level::info : spdlog::level::off);
  try {
    return run(options);
  } catch (const std::exception& error) {
    return fail(options.device, error.what());
  }
}
