#include "mrslam/drivers/hokuyo_driver.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>
#include <thread>

#include "hokuyo_handshake.hpp"
#include "hokuyo_link.hpp"
#include "mrslam/drivers/scip_codec.hpp"

namespace mrslam::drivers {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

/// A device answering only with bad replies for this many stall limits is reopened too.
constexpr int kBadRepliesOnlyFactor = 10;

void require(bool condition, const std::string& what) {
  if (!condition) {
    throw std::invalid_argument("HokuyoSettings: " + what);
  }
}

const HokuyoSettings& checked(const HokuyoSettings& s) {
  require(!s.device.empty(), "device is empty");
  require(s.cluster >= 1 && s.cluster <= 99, "cluster must be in 1…99");
  require(s.skip_scans >= 0 && s.skip_scans <= 9, "skip_scans must be in 0…9");
  require(s.start_step >= -1 && s.end_step >= -1 && s.start_step <= 9999 && s.end_step <= 9999,
          "start_step and end_step must be -1 (from PP) or 0…9999");
  require(s.start_step < 0 || s.end_step < 0 || s.start_step <= s.end_step,
          "start_step must not exceed end_step");
  require(s.read_timeout.count() > 0, "read_timeout must be positive");
  require(s.stall_scan_periods >= 1, "stall_scan_periods must be at least 1");
  require(s.reconnect_backoff_min.count() > 0 && s.reconnect_backoff_max >= s.reconnect_backoff_min,
          "need 0 < reconnect_backoff_min <= reconnect_backoff_max");
  require(s.time_sync_round_trips >= 0 && s.time_sync_round_trips <= 100,
          "time_sync_round_trips must be in 0…100");
  return s;
}

/// The MD request of the settings on this device; nothing when the steps do not fit it.
Result<scip::ScanRequest> scanRequestFor(const HokuyoSettings& settings,
                                         const scip::ScanGeometry& geometry) {
  scip::ScanRequest request;
  request.start_step = settings.start_step >= 0 ? settings.start_step : geometry.amin;
  request.end_step = settings.end_step >= 0 ? settings.end_step : geometry.amax;
  request.cluster = settings.cluster;
  request.interval = settings.skip_scans;
  if (request.start_step < geometry.amin || request.end_step > geometry.amax ||
      request.start_step > request.end_step) {
    return Result<scip::ScanRequest>::failure(
        "steps " + std::to_string(request.start_step) + "…" + std::to_string(request.end_step) +
        " are outside AMIN…AMAX (" + std::to_string(geometry.amin) + "…" +
        std::to_string(geometry.amax) + ") of this device");
  }
  return Result<scip::ScanRequest>::success(request);
}

std::int64_t stepsToNs(double steps, const scip::ScanGeometry& geometry) {
  return static_cast<std::int64_t>(steps * geometry.stepDurationS() * 1e9);
}

}  // namespace

HokuyoDriver::HokuyoDriver(HokuyoSettings settings)
    : settings_(checked(settings)),
      link_(std::make_unique<HokuyoLink>()),
      backoff_(settings_.reconnect_backoff_min, settings_.reconnect_backoff_max),
      errors_("hokuyo " + settings_.device) {}

HokuyoDriver::~HokuyoDriver() {
  stop();
}

void HokuyoDriver::report(const std::string& kind, const std::string& reason) {
  errors_.report(kind, reason);
  last_error_ = reason;
}

Result<HokuyoIdentity> HokuyoDriver::connect() {
  if (attemptConnect()) {
    return Result<HokuyoIdentity>::success(*identity_);
  }
  return Result<HokuyoIdentity>::failure(last_error_);
}

bool HokuyoDriver::attemptConnect() {
  const bool recovering = state_ == HokuyoState::kReconnecting;
  ++connect_attempts_;
  mode_ = Mode::kClosed;
  link_->close();
  const auto fail = [this](const std::string& reason) {
    link_->close();
    last_error_ = reason;
    state_ = HokuyoState::kReconnecting;
    next_attempt_ = Clock::now() + backoff_.next();
    return false;
  };
  HokuyoSettings attempt = settings_;
  if (identity_) {
    attempt.baud = identity_->baud;  // probe the rate that worked last time first
  }
  if (!link_->open(attempt.device, attempt.baud)) {
    report("disconnect", link_->error());
    return fail(link_->error());
  }
  const auto reporter = [this](const std::string& kind, const std::string& reason) {
    report(kind, reason);
  };
  auto identity = runHandshake(*link_, attempt, clock_, reporter);
  if (!identity) {
    return fail(identity.reason());
  }
  auto request = scanRequestFor(settings_, identity.value().geometry);
  if (!request) {
    return fail(request.reason());
  }
  request_ = request.value();
  identity_ = std::move(identity.value());
  mode_ = Mode::kIdle;
  state_ = HokuyoState::kConnected;
  backoff_.reset();
  reconnects_ += recovering ? 1 : 0;
  spdlog::info("hokuyo {}: {} at {} baud, steps {}…{}", settings_.device,
               identity_->parameters.count("MODL") ? identity_->parameters.at("MODL") : "?",
               identity_->baud, request_.start_step, request_.end_step);
  return true;
}

bool HokuyoDriver::startStreaming() {
  request_.command = "MD";
  request_.count = 0;
  const CommandResult ack =
      link_->command(request_.text(), scip::LineCheck::kData, settings_.read_timeout);
  if (!ack.parsed()) {
    loseDevice(ack.link == SerialPort::Status::kTimeout ? "timeout" : "disconnect",
               "no valid reply to " + request_.text());
    return false;
  }
  const std::string& status = ack.reply->value().status;
  if (!scip::isSuccessStatus("MD", status)) {
    loseDevice("status",
               request_.text() + " status " + status + ": " + scip::statusText("MD", status));
    return false;
  }
  mode_ = Mode::kStreaming;
  last_valid_scan_ = last_reply_ = Clock::now();
  return true;
}

bool HokuyoDriver::stopStreaming() {
  const CommandResult quit = link_->command("QT", scip::LineCheck::kData, settings_.read_timeout);
  mode_ = Mode::kIdle;
  return quit.parsed();
}

bool HokuyoDriver::ensureStreaming(Clock::time_point deadline) {
  if (mode_ == Mode::kClosed) {
    const auto now = Clock::now();
    if (now < next_attempt_) {
      std::this_thread::sleep_for(std::min(next_attempt_, deadline) - now);
      if (Clock::now() < next_attempt_) {
        return false;
      }
    }
    if (!attemptConnect()) {
      return false;
    }
  }
  return mode_ == Mode::kStreaming || startStreaming();
}

std::optional<LaserScan> HokuyoDriver::poll(milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while (true) {
    if (mode_ != Mode::kStreaming) {
      if (!ensureStreaming(deadline) && Clock::now() >= deadline) {
        return std::nullopt;
      }
      continue;
    }
    if (auto block = link_->framer().next()) {
      last_reply_ = Clock::now();
      if (auto scan = handleStreamBlock(*block)) {
        return scan;
      }
      continue;
    }
    if (const std::string stall = stallReason(); !stall.empty()) {
      loseDevice("timeout", stall);
      continue;
    }
    const auto now = Clock::now();
    if (now >= deadline) {
      return std::nullopt;
    }
    const auto wait = std::min(deadline, last_reply_ + stallLimit()) - now;
    const auto dropped_before = link_->framer().droppedBytes();
    const auto status =
        link_->readSome(std::chrono::duration_cast<milliseconds>(wait) + milliseconds(1));
    if (link_->framer().droppedBytes() != dropped_before) {
      report("garbage", "a long run of bytes without a reply end");
    }
    if (status == SerialPort::Status::kDisconnected || status == SerialPort::Status::kError) {
      loseDevice("disconnect", link_->error());
    }
  }
}

std::optional<LaserScan> HokuyoDriver::handleStreamBlock(std::string_view block) {
  const std::size_t at = scip::findEcho(block, request_.echoPrefix());
  if (at == std::string_view::npos) {
    if (block.substr(0, 3) != "QT\n") {  // a late QT reply is no noise
      report("garbage", std::to_string(block.size()) + " bytes that are no scan reply");
    }
    return std::nullopt;
  }
  if (at > 0) {
    report("garbage", std::to_string(at) + " bytes of noise before a scan");
  }
  const auto reply = scip::parseReply(block.substr(at), scip::LineCheck::kData);
  if (!reply) {
    report(scip::errorKindName(reply.error()), reply.reason());
    return std::nullopt;
  }
  if (reply.value().status == "00" && reply.value().data.empty()) {
    return std::nullopt;  // the MD acknowledgement
  }
  const auto data = scip::decodeScanReply(reply.value(), request_);
  if (!data) {
    report(scip::errorKindName(data.error()), data.reason());
    return std::nullopt;
  }
  return toStampedScan(data.value());
}

std::optional<LaserScan> HokuyoDriver::toStampedScan(const scip::ScanData& data) {
  const scip::ScanGeometry& geometry = identity_->geometry;
  LaserScan scan = scip::toLaserScan(data.ranges_mm, geometry, request_, settings_.zero_range);
  const double first_beam_step = request_.start_step + 0.5 * (request_.cluster - 1);
  scan.stamp = clock_.stampScan(data.timestamp_ms, link_->lastReceive(),
                                stepsToNs(first_beam_step, geometry),
                                stepsToNs(request_.end_step, geometry));
  last_valid_scan_ = Clock::now();
  ++scans_;
  return scan;
}

Result<LaserScan> HokuyoDriver::singleScan() {
  if (mode_ == Mode::kClosed && !attemptConnect()) {
    return Result<LaserScan>::failure(last_error_);
  }
  if (mode_ == Mode::kStreaming) {
    stopStreaming();  // QT turns the laser off: on again
    link_->command("BM", scip::LineCheck::kData, settings_.read_timeout);
  }
  scip::ScanRequest single = request_;
  single.command = "GD";
  const CommandResult result =
      link_->command(single.text(), scip::LineCheck::kData, settings_.read_timeout);
  if (result.link != SerialPort::Status::kOk) {
    const bool timeout = result.link == SerialPort::Status::kTimeout;
    loseDevice(timeout ? "timeout" : "disconnect",
               timeout ? "no reply to " + single.text() : link_->error());
    return Result<LaserScan>::failure(last_error_);
  }
  if (!result.reply->ok()) {
    report(scip::errorKindName(result.reply->error()), result.reply->reason());
    return Result<LaserScan>::failure(last_error_);
  }
  const auto data = scip::decodeScanReply(result.reply->value(), single);
  if (!data) {
    report(scip::errorKindName(data.error()), data.reason());
    return Result<LaserScan>::failure(last_error_);
  }
  return Result<LaserScan>::success(*toStampedScan(data.value()));
}

void HokuyoDriver::stop() {
  if (link_->isOpen()) {
    if (mode_ != Mode::kClosed) {
      stopStreaming();
      if (settings_.reset_on_stop) {
        link_->command("RS", scip::LineCheck::kData, settings_.read_timeout);
      }
    }
    link_->close();
  }
  mode_ = Mode::kClosed;
  state_ = HokuyoState::kDisconnected;
  next_attempt_ = {};
}

void HokuyoDriver::loseDevice(const std::string& kind, const std::string& reason) {
  report(kind, reason);
  link_->close();
  mode_ = Mode::kClosed;
  state_ = HokuyoState::kReconnecting;
  next_attempt_ = Clock::now() + backoff_.next();
}

Clock::duration HokuyoDriver::stallLimit() const {
  const double period_s = identity_ ? identity_->geometry.scanPeriodS() : 0.1;
  const auto stall = std::chrono::duration<double>(period_s * (settings_.skip_scans + 1) *
                                                   settings_.stall_scan_periods);
  return std::chrono::duration_cast<Clock::duration>(stall);
}

std::string HokuyoDriver::stallReason() const {
  const auto now = Clock::now();
  const std::string periods = std::to_string(settings_.stall_scan_periods);
  if (now - last_reply_ > stallLimit()) {
    return "no reply for " + periods + " scan periods";
  }
  if (now - last_valid_scan_ > kBadRepliesOnlyFactor * stallLimit()) {
    return "only bad replies for " + std::to_string(kBadRepliesOnlyFactor) + " × " + periods +
           " scan periods";
  }
  return {};
}

HokuyoHealth HokuyoDriver::health() const {
  HokuyoHealth health;
  health.state = state_;
  health.last_error = last_error_;
  HokuyoCounters& c = health.counters;
  c.scans = scans_;
  c.checksum = errors_.count("checksum");
  c.truncated = errors_.count("truncated");
  c.status = errors_.count("status");
  c.garbage = errors_.count("garbage");
  c.timeout = errors_.count("timeout");
  c.disconnect = errors_.count("disconnect");
  c.reconnects = reconnects_;
  c.connect_attempts = connect_attempts_;
  return health;
}

}  // namespace mrslam::drivers
