// The 3DM-GX1 driver: start-up, polled and continuous reading, loss and reconnection.

#include "mrslam/drivers/gx1_driver.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <thread>

#include "mrslam/drivers/device_host_clock.hpp"

namespace mrslam::drivers {

namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

constexpr milliseconds kWriteTimeout{100};

Gx1Settings checked(Gx1Settings settings) {
  if (const std::string problem = settings.check(); !problem.empty()) {
    throw std::invalid_argument("3DM-GX1 settings: " + problem);
  }
  return settings;
}

TickClock::Settings clockSettings(const Gx1Settings& settings) {
  return {settings.tick_period_s, settings.clock_drift_allowance, settings.max_clock_error_s};
}

std::string hex(std::uint8_t byte) {
  char text[8];
  std::snprintf(text, sizeof(text), "0x%02X", byte);
  return text;
}

milliseconds until(Clock::time_point when) {
  const auto left = std::chrono::ceil<milliseconds>(when - Clock::now());
  return std::max(left, milliseconds(0));
}

std::vector<std::uint8_t> allHeaders() {
  return {gx1::kEulerCommand, gx1::kEulerVectorsCommand, gx1::kQuaternionVectorsCommand,
          gx1::kEepromReadCommand, gx1::kContinuousCommand};
}

}  // namespace

Gx1Driver::Gx1Driver(Gx1Settings settings)
    : settings_(checked(std::move(settings))),
      problems_("3DM-GX1 " + settings_.device),
      backoff_(settings_.reconnect_initial, settings_.reconnect_max),
      clock_(clockSettings(settings_)) {}

Gx1Driver::~Gx1Driver() {
  close();
}

void Gx1Driver::close() {
  if (health_.state == Gx1State::kRunning && settings_.mode == Gx1Mode::kContinuous) {
    const auto stop = gx1::continuousRequest(0);
    port_.writeAll(stop.data(), stop.size(), kWriteTimeout);
  }
  port_.close();
  health_.state = Gx1State::kClosed;
}

Gx1Health Gx1Driver::health() const {
  Gx1Health health = health_;
  health.parser = parser_.counters();
  health.clock_resyncs = clock_.resyncs();
  return health;
}

std::optional<ImuSample> Gx1Driver::poll(milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while (health_.state != Gx1State::kClosed) {
    if (health_.state == Gx1State::kDisconnected && !connectWhenDue(deadline)) {
      return std::nullopt;
    }
    if (std::optional<ImuSample> sample = readSample(deadline)) {
      return sample;
    }
    if (Clock::now() >= deadline) {
      break;
    }
  }
  return std::nullopt;
}

bool Gx1Driver::connectWhenDue(Clock::time_point deadline) {
  if (Clock::now() < next_attempt_) {
    std::this_thread::sleep_until(std::min(next_attempt_, deadline));
    if (Clock::now() < next_attempt_) {
      return false;
    }
  }
  const bool opened = port_.open(settings_.device, settings_.baud);
  if (!opened || !startUp()) {
    if (!opened) {
      health_.last_error = port_.error();
    }
    ++health_.failed_startups;
    spdlog::warn("3DM-GX1 {}: start-up failed: {}", settings_.device, health_.last_error);
    port_.close();
    next_attempt_ = Clock::now() + backoff_.next();
    return false;
  }
  backoff_.reset();
  clock_.reset();
  ++health_.startups;
  health_.state = Gx1State::kRunning;
  parser_.accept({settings_.command});
  request_pending_ = false;
  silent_timeouts_ = 0;
  received_in_window_ = 0;
  reply_due_ = Clock::now() + settings_.read_timeout;
  spdlog::info("3DM-GX1 {}: started ({} mode, command {}, gains gyro {} accel {} mag {})",
               settings_.device, settings_.mode == Gx1Mode::kPolled ? "polled" : "continuous",
               hex(settings_.command), gains_.gyro, gains_.accel, gains_.mag);
  return true;
}

bool Gx1Driver::startUp() {
  parser_.clear();
  std::vector<std::uint8_t> headers = allHeaders();
  if (!settings_.expect_continuous_confirmation) {
    headers.pop_back();  // 0x10: its layout is unsure, so it is not looked for
  }
  parser_.accept(headers);
  const auto quiet = gx1::continuousRequest(0);  // in case the device still streams
  if (!send(quiet.data(), quiet.size())) {
    return false;
  }
  const auto gyro = readGain(gx1::kGyroGainAddress, "gyro");
  const auto accel = gyro ? readGain(gx1::kAccelGainAddress, "accel") : std::nullopt;
  const auto mag = accel ? readGain(gx1::kMagGainAddress, "mag") : std::nullopt;
  if (!mag) {
    return false;
  }
  gains_ = {static_cast<double>(*gyro), static_cast<double>(*accel), static_cast<double>(*mag)};
  return settings_.mode == Gx1Mode::kPolled || startContinuous();
}

std::optional<std::uint16_t> Gx1Driver::readGain(std::uint16_t address, const char* name) {
  const auto request = gx1::eepromReadRequest(address);
  if (!send(request.data(), request.size())) {
    return std::nullopt;
  }
  const std::string what = std::string("the EEPROM read of the ") + name + " gain (address " +
                           std::to_string(address) + ")";
  const auto frame =
      awaitFrame([](const gx1::Frame& f) { return f.header == gx1::kEepromReadCommand; }, what);
  if (!frame) {
    return std::nullopt;
  }
  const std::uint16_t value = gx1::decodeEepromValue(*frame).value_or(0);
  if (value == 0) {
    health_.last_error = "implausible gain 0 in reply to " + what;
    return std::nullopt;
  }
  return value;
}

bool Gx1Driver::startContinuous() {
  const auto request = gx1::continuousRequest(settings_.command);
  if (!send(request.data(), request.size())) {
    return false;
  }
  if (!settings_.expect_continuous_confirmation) {
    return true;  // silence will show if streaming did not start
  }
  const std::uint8_t command = settings_.command;
  const auto confirmed = [command](const gx1::Frame& f) {
    return f.header == command || gx1::decodeContinuousConfirmation(f) == command;
  };
  return awaitFrame(confirmed, "the start of continuous mode (0x10 0x00 " + hex(command) + ")")
      .has_value();
}

template <class Wanted>
std::optional<gx1::Frame> Gx1Driver::awaitFrame(Wanted wanted, const std::string& what) {
  const auto deadline = Clock::now() + settings_.read_timeout;
  const gx1::ParserCounters before = parser_.counters();
  std::size_t received = 0;
  for (;;) {
    while (std::optional<gx1::Frame> frame = parser_.next()) {
      if (wanted(*frame)) {
        return frame;
      }
    }
    if (Clock::now() >= deadline) {
      break;
    }
    std::uint8_t buffer[256];
    const auto result = port_.read(buffer, sizeof(buffer), until(deadline));
    if (result.status == SerialPort::Status::kOk) {
      last_read_host_ = device_clock::hostNow();
      parser_.push(buffer, result.bytes);
      received += result.bytes;
    } else if (result.status != SerialPort::Status::kTimeout) {
      health_.last_error = "device gone waiting for " + what + ": " + port_.error();
      return std::nullopt;
    }
  }
  const gx1::ParserCounters& after = parser_.counters();
  health_.last_error =
      received == 0
          ? "no answer to " + what + " within " + std::to_string(settings_.read_timeout.count()) +
                " ms"
          : "garbage in reply to " + what + ": " + std::to_string(received) + " bytes, " +
                std::to_string(after.bad_checksums - before.bad_checksums) + " bad checksums, " +
                std::to_string(after.garbage_bytes - before.garbage_bytes) + " stray bytes";
  return std::nullopt;
}

std::optional<ImuSample> Gx1Driver::readSample(Clock::time_point deadline) {
  for (;;) {
    if (std::optional<ImuSample> sample = takeSample()) {
      return sample;
    }
    if (settings_.mode == Gx1Mode::kPolled && !request_pending_) {
      if (!send(&settings_.command, 1)) {
        lose(health_.last_error);
        return std::nullopt;
      }
      request_pending_ = true;
      reply_due_ = Clock::now() + settings_.read_timeout;
    }
    const auto now = Clock::now();
    if (now >= reply_due_) {
      // The caller may not have polled for a while: bytes waiting in the port are no time-out.
      if (!readBytes(milliseconds(0))) {
        return std::nullopt;
      }
      if (std::optional<ImuSample> sample = takeSample()) {
        return sample;
      }
      onSilence();
      if (health_.state != Gx1State::kRunning) {
        return std::nullopt;
      }
      continue;
    }
    if (now >= deadline || !readBytes(until(std::min(deadline, reply_due_)))) {
      return std::nullopt;
    }
  }
}

std::optional<ImuSample> Gx1Driver::takeSample() {
  while (std::optional<gx1::Frame> frame = parser_.next()) {
    const auto reading = gx1::decodeReading(*frame, gains_, settings_.quaternion);
    if (!reading) {
      ++health_.implausible_frames;
      continue;
    }
    request_pending_ = false;
    silent_timeouts_ = 0;
    received_in_window_ = 0;
    reply_due_ = Clock::now() + settings_.read_timeout;
    last_raw_ticks_ = reading->ticks;
    const Stamp stamp = clock_.stamp(reading->ticks, last_read_host_);
    ++health_.samples;
    return toSample(*reading, stamp);
  }
  reportProblems();
  return std::nullopt;
}

void Gx1Driver::reportProblems() {
  // Logged with a rate limit per kind; health() has the exact counts.
  const gx1::ParserCounters& counters = parser_.counters();
  const auto report = [this](const char* kind, std::uint64_t count, std::uint64_t& reported) {
    if (count > reported) {
      problems_.report(kind, std::to_string(count - reported) + " " + kind + " dropped (" +
                                 std::to_string(count) + " in all)");
      reported = count;
    }
  };
  report("bad checksums", counters.bad_checksums, reported_.bad_checksums);
  report("stray bytes", counters.garbage_bytes, reported_.garbage_bytes);
  report("truncated frames", counters.truncated_frames, reported_.truncated_frames);
}

bool Gx1Driver::readBytes(milliseconds wait) {
  std::uint8_t buffer[512];
  const auto result = port_.read(buffer, sizeof(buffer), wait);
  if (result.status == SerialPort::Status::kOk) {
    last_read_host_ = device_clock::hostNow();
    received_in_window_ += result.bytes;
    parser_.push(buffer, result.bytes);
    return true;
  }
  if (result.status == SerialPort::Status::kTimeout) {
    return true;
  }
  lose("device lost: " + port_.error());
  return false;
}

bool Gx1Driver::send(const std::uint8_t* bytes, std::size_t size) {
  const SerialPort::Status status = port_.writeAll(bytes, size, kWriteTimeout);
  if (status == SerialPort::Status::kOk) {
    return true;
  }
  health_.last_error = status == SerialPort::Status::kTimeout
                           ? settings_.device + ": write timed out"
                           : "device lost: " + port_.error();
  return false;
}

void Gx1Driver::onSilence() {
  // Only a window without a single byte counts towards losing the device: one that answers
  // corrupt frames is still there (and reconnecting would not cure it).
  ++health_.timeouts;
  silent_timeouts_ = received_in_window_ == 0 ? silent_timeouts_ + 1 : 0;
  received_in_window_ = 0;
  parser_.discardPartial();
  problems_.report("time-outs",
                   "no frame within " + std::to_string(settings_.read_timeout.count()) + " ms");
  if (silent_timeouts_ >= settings_.max_silent_timeouts) {
    lose("device silent: " + std::to_string(silent_timeouts_) + " time-outs of " +
         std::to_string(settings_.read_timeout.count()) + " ms in a row");
    return;
  }
  request_pending_ = false;  // polled: ask again
  reply_due_ = Clock::now() + settings_.read_timeout;
}

void Gx1Driver::lose(const std::string& reason) {
  ++health_.disconnects;
  health_.last_error = reason;
  health_.last_loss = reason;
  health_.state = Gx1State::kDisconnected;
  spdlog::warn("3DM-GX1 {}: {}; reconnecting", settings_.device, reason);
  port_.close();
  parser_.clear();
  request_pending_ = false;
  next_attempt_ = Clock::now() + backoff_.next();
}

ImuSample Gx1Driver::toSample(const gx1::Reading& reading, Stamp stamp) const {
  // z down → z up: a turn by π about x (see the header).
  const double flip = settings_.device_z_down ? -1.0 : 1.0;
  const Eigen::Vector3d axes(1.0, flip, flip);
  ImuSample sample;
  sample.stamp = stamp;
  sample.roll_rad = reading.roll_rad;
  sample.pitch_rad = flip * reading.pitch_rad;
  sample.yaw_rad = flip * reading.yaw_rad;
  if (reading.has_vectors) {
    sample.acceleration_g = reading.acceleration_g.cwiseProduct(axes);
    sample.angular_rate_rad_s = reading.angular_rate_rad_s.cwiseProduct(axes);
  } else {
    // 0x0E has no vectors: unknown, not zero (a zero yaw rate would be a false measurement).
    const double unknown = std::numeric_limits<double>::quiet_NaN();
    sample.acceleration_g.setConstant(unknown);
    sample.angular_rate_rad_s.setConstant(unknown);
  }
  return sample;
}

}  // namespace mrslam::drivers
