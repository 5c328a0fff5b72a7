#include "mrslam/drivers/scip_responder.hpp"

#include <algorithm>
#include <cstdio>

#include "mrslam/drivers/scip_codec.hpp"

namespace mrslam::drivers {
namespace {

using scip::keyValueLine;
using scip::ScanRequest;

constexpr std::size_t kScanLineChars = 12;    // GD/GS: command, start, end, cluster
constexpr std::size_t kStreamLineChars = 15;  // MD/MS: … interval, count

std::optional<int> digits(std::string_view text) {
  int value = 0;
  for (const char c : text) {
    if (c < '0' || c > '9') {
      return std::nullopt;
    }
    value = value * 10 + (c - '0');
  }
  return value;
}

/// Parses a GD/GS/MD/MS line into `request`; returns the SCIP status ("00" when valid).
std::string parseScanLine(std::string_view line, const scip::ScanGeometry& geometry,
                          ScanRequest& request) {
  request.command = std::string(line.substr(0, 2));
  if (line.size() != (request.continuous() ? kStreamLineChars : kScanLineChars)) {
    return line.size() < kScanLineChars ? "0C" : "0F";
  }
  const auto start = digits(line.substr(2, 4));
  const auto end = digits(line.substr(6, 4));
  const auto cluster = digits(line.substr(10, 2));
  const auto interval = request.continuous() ? digits(line.substr(12, 1)) : 0;
  const auto count = request.continuous() ? digits(line.substr(13, 2)) : 0;
  const std::pair<bool, const char*> checks[] = {
      {start.has_value(), "01"},
      {end.has_value(), "02"},
      {cluster.has_value(), "03"},
      {end && *end <= geometry.amax && start && *start >= geometry.amin, "04"},
      {end && start && *end >= *start, "05"},
      {interval.has_value(), "06"},
      {count.has_value(), "07"},
  };
  for (const auto& [passed, status] : checks) {
    if (!passed) {
      return status;
    }
  }
  request.start_step = *start;
  request.end_step = *end;
  request.cluster = std::max(1, *cluster);
  request.interval = *interval;
  request.count = *count;
  return "00";
}

std::string hex24(std::uint32_t value) {
  char text[8];
  std::snprintf(text, sizeof(text), "%06X", value & 0xFFFFFFu);
  return text;
}

}  // namespace

HokuyoModel HokuyoModel::urg04lx() {
  HokuyoModel model;
  model.product = "SOKUIKI Sensor URG-04LX";
  model.firmware = "3.3.00";
  model.model_name = "URG-04LX(Hokuyo Automatic Co.,Ltd.)";
  model.geometry = {20, 5600, 1024, 44, 725, 384, 600};
  return model;
}

HokuyoModel HokuyoModel::ubg05ln() {
  HokuyoModel model;
  model.product = "SOKUIKI Sensor UBG-05LN";
  model.firmware = "1.0.0";
  model.model_name = "UBG-05LN(Hokuyo Automatic Co.,Ltd.)";
  model.geometry = {20, 4500, 1000, 244, 756, 500, 600};
  return model;
}

std::vector<std::uint32_t> modelRanges(const RangeSource& source, std::uint64_t scan_index,
                                       const HokuyoModel& model) {
  std::vector<std::uint32_t> ranges = source ? source(scan_index) : std::vector<std::uint32_t>{};
  ranges.resize(static_cast<std::size_t>(model.geometry.measuredSteps()), 0);
  return ranges;
}

std::vector<std::uint32_t> requestedValues(const std::vector<std::uint32_t>& model_ranges,
                                           const HokuyoModel& model, const ScanRequest& request) {
  const std::uint32_t largest = (1u << (6 * request.valueChars())) - 1;
  std::vector<std::uint32_t> values;
  values.reserve(request.valueCount());
  for (int step = request.start_step; step <= request.end_step; step += request.cluster) {
    const int last = std::min(request.end_step, step + request.cluster - 1);
    std::uint32_t value = largest;
    for (int s = step; s <= last; ++s) {
      value = std::min(value, model_ranges[static_cast<std::size_t>(s - model.geometry.amin)]);
    }
    values.push_back(value);
  }
  return values;
}

ScipResponder::ScipResponder(HokuyoModel model, RangeSource ranges, Options options)
    : model_(std::move(model)), ranges_(std::move(ranges)), options_(options) {
  powerOn();
}

void ScipResponder::powerOn() {
  scip2_ = !options_.start_in_scip11;
  laser_on_ = false;
  time_sync_mode_ = false;
  stream_.reset();
}

std::string ScipResponder::respond(std::string_view line, std::uint32_t now_ms) {
  if (line.empty()) {
    return {};
  }
  if (!scip2_) {
    return respondScip11(line);
  }
  const std::string echo(line);
  const std::string_view command = line.substr(0, std::min<std::size_t>(2, line.size()));
  const std::string_view request = line.substr(0, line.find(';'));  // drop the ";string"
  if (command == "QT" || command == "RS") {
    stream_.reset();
    laser_on_ = false;
    time_sync_mode_ = time_sync_mode_ && command == "QT";
    return scip::formatReply(echo, "00", {});
  }
  if (command == "BM") {
    return respondBeamOn(echo);
  }
  if (command == "VV") {
    return scip::formatReply(echo, "00", versionLines());
  }
  if (command == "PP") {
    return scip::formatReply(echo, "00", parameterLines());
  }
  if (command == "II") {
    return scip::formatReply(echo, "00", stateLines(now_ms));
  }
  if (command == "TM" && options_.support_time_sync) {
    return respondTimeSync(echo, request, now_ms);
  }
  if (command == "GD" || command == "GS" || command == "MD" || command == "MS") {
    return respondScan(echo, request, now_ms);
  }
  return scip::formatReply(echo, "0E", {});
}

std::string ScipResponder::respondScip11(std::string_view line) {
  // SCIP 1.1 replies: echo, a one-char status ("0" OK, otherwise an error), empty line.
  if (line == "SCIP2.0") {
    scip2_ = true;
    return std::string(line) + "\n0\n\n";
  }
  return std::string(line) + "\nE\n\n";
}

std::string ScipResponder::respondBeamOn(std::string_view echo) {
  if (options_.laser_malfunction) {
    return scip::formatReply(echo, "01", {});
  }
  const bool was_on = laser_on_;
  laser_on_ = true;
  return scip::formatReply(echo, was_on ? "02" : "00", {});
}

std::string ScipResponder::respondTimeSync(std::string_view echo, std::string_view command,
                                           std::uint32_t now_ms) {
  if (command == "TM0" || command == "TM2") {
    time_sync_mode_ = command == "TM0";
    return scip::formatReply(echo, "00", {});
  }
  if (command == "TM1" && time_sync_mode_) {
    return scip::formatReply(echo, "00", {scip::withChecksum(scip::encode(now_ms & 0xFFFFFFu, 4))});
  }
  return scip::formatReply(echo, command == "TM1" ? "01" : "0C", {});
}

std::string ScipResponder::respondScan(std::string_view echo, std::string_view line,
                                       std::uint32_t now_ms) {
  ScanRequest request;
  const std::string status = parseScanLine(line, model_.geometry, request);
  if (status != "00") {
    return scip::formatReply(echo, status, {});
  }
  if (request.continuous()) {
    laser_on_ = true;
    stream_ = request;
    stream_turn_ = 0;
    stream_left_ = request.count == 0 ? -1 : request.count;
    return scip::formatReply(echo, "00", {});
  }
  if (!laser_on_) {
    return scip::formatReply(echo, "10", {});
  }
  return scanReply(std::string(echo), "00", request, now_ms);
}

std::optional<std::string> ScipResponder::streamTurn(std::uint32_t stamp_ms) {
  if (!stream_) {
    return std::nullopt;
  }
  if (stream_turn_++ % (stream_->interval + 1) != 0) {
    return std::nullopt;
  }
  if (stream_left_ > 0) {
    --stream_left_;
  }
  char count[16];
  std::snprintf(count, sizeof(count), "%02d", std::clamp(stream_left_, 0, 99));
  const std::string echo = stream_->echoPrefix() + count;
  std::string reply = scanReply(echo, "99", *stream_, stamp_ms);
  if (stream_left_ == 0) {
    stream_.reset();
  }
  return reply;
}

std::string ScipResponder::scanReply(const std::string& echo, std::string_view status,
                                     const ScanRequest& request, std::uint32_t stamp_ms) {
  const auto ranges = modelRanges(ranges_, scans_taken_++, model_);
  const auto values = requestedValues(ranges, model_, request);
  return scip::formatReply(echo, status,
                           scip::scanDataLines(stamp_ms & 0xFFFFFFu, values, request.valueChars()));
}

std::vector<std::string> ScipResponder::versionLines() const {
  return {keyValueLine("VEND", model_.vendor), keyValueLine("PROD", model_.product),
          keyValueLine("FIRM", model_.firmware), keyValueLine("PROT", model_.protocol),
          keyValueLine("SERI", model_.serial)};
}

std::vector<std::string> ScipResponder::parameterLines() const {
  const scip::ScanGeometry& g = model_.geometry;
  return {keyValueLine("MODL", model_.model_name),
          keyValueLine("DMIN", std::to_string(g.dmin_mm)),
          keyValueLine("DMAX", std::to_string(g.dmax_mm)),
          keyValueLine("ARES", std::to_string(g.ares)),
          keyValueLine("AMIN", std::to_string(g.amin)),
          keyValueLine("AMAX", std::to_string(g.amax)),
          keyValueLine("AFRT", std::to_string(g.afrt)),
          keyValueLine("SCAN", std::to_string(g.scan_rpm))};
}

std::vector<std::string> ScipResponder::stateLines(std::uint32_t now_ms) const {
  return {keyValueLine("MODL", model_.model_name),
          keyValueLine("LASR", laser_on_ ? "ON" : "OFF"),
          keyValueLine("SCSP", "Initial(" + std::to_string(model_.geometry.scan_rpm) + "[rpm])"),
          keyValueLine("MESM", stream_ ? "Measuring by MD" : "Idle"),
          keyValueLine("SBPS", "USB only"),
          keyValueLine("TIME", hex24(now_ms)),
          keyValueLine("STAT", "Sensor works well.")};
}

}  // namespace mrslam::drivers
