#include "mrslam/drivers/breezyslam_reader.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace mrslam::drivers {
namespace {

constexpr std::size_t kStampField = 1;  // 1-based field numbers
constexpr std::size_t kLeftField = 3;
constexpr std::size_t kRightField = 4;

const BreezySlamSettings& checked(const BreezySlamSettings& s) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("BreezySlamSettings: " + what);
  };
  if (s.beam_count < 2) {
    fail("beam_count must be at least 2, got " + std::to_string(s.beam_count));
  }
  if (s.header_field_count < kRightField) {
    fail("header_field_count must be at least 4 (time stamp and encoders), got " +
         std::to_string(s.header_field_count));
  }
  if (!(s.field_of_view_deg > 0.0 && s.field_of_view_deg <= 360.0)) {
    fail("field_of_view_deg must be in (0, 360], got " + std::to_string(s.field_of_view_deg));
  }
  if (!(s.range_min_m >= 0.0 && s.range_max_m > s.range_min_m && std::isfinite(s.range_max_m))) {
    fail("need 0 <= range_min_m < range_max_m, got " + std::to_string(s.range_min_m) + " and " +
         std::to_string(s.range_max_m));
  }
  return s;
}

std::string quoted(std::string_view text) {
  return "'" + std::string(text) + "'";
}

}  // namespace

BreezySlamReader::BreezySlamReader(BreezySlamSettings settings)
    : settings_(checked(settings)),
      lines_(settings_.path),
      malformed_("breezyslam log", settings_.malformed_policy) {}

std::string BreezySlamReader::describe() const {
  return "breezyslam log " + settings_.path;
}

SourceCounters BreezySlamReader::counters() const {
  SourceCounters counters = counters_;
  counters.malformed_records = malformed_.count();
  return counters;
}

std::optional<Sample> BreezySlamReader::next() {
  while (pending_.empty()) {
    if (!lines_.next(line_)) {
      return std::nullopt;
    }
    splitFields(line_, fields_);
    if (fields_.empty()) {
      continue;
    }
    if (const std::optional<LineProblem> problem = parseLine()) {
      pending_.clear();
      malformed_.handle(settings_.path, lines_.lineNumber(), *problem);
    }
  }
  Sample sample = std::move(pending_.front());
  pending_.pop_front();
  const Stamp stamp = stampOf(sample);
  if (last_stamp_ && stamp < *last_stamp_) {
    ++counters_.out_of_order_stamps;
  }
  last_stamp_ = stamp;
  ++counters_.samples;
  return sample;
}

std::optional<LineProblem> BreezySlamReader::parseLine() {
  const std::size_t expected = settings_.header_field_count + settings_.beam_count;
  if (fields_.size() != expected) {
    return LineProblem{"field count", "expected " + std::to_string(expected) + " fields, found " +
                                          std::to_string(fields_.size())};
  }
  // Every header field must be a finite number; the time stamp and the counts integers.
  for (std::size_t i = 0; i < settings_.header_field_count; ++i) {
    const std::string field = "field " + std::to_string(i + 1) + ": " + quoted(fields_[i]);
    const std::size_t number = i + 1;
    if (number == kStampField || number == kLeftField || number == kRightField) {
      if (!parseInteger(fields_[i])) {
        return LineProblem{"not a number", field + " is not an integer"};
      }
      continue;
    }
    const std::optional<double> value = parseNumber(fields_[i]);
    if (!value) {
      return LineProblem{"not a number", field + " is not a number"};
    }
    if (!std::isfinite(*value)) {
      return LineProblem{"not finite", field + " is not finite"};
    }
  }
  const std::int64_t stamp_us = *parseInteger(fields_[kStampField - 1]);
  if (stamp_us < 0) {
    return LineProblem{"negative",
                       "field 1: time stamp " + std::to_string(stamp_us) + " us is negative"};
  }
  WheelTicks ticks;
  ticks.stamp = Stamp::fromMicroseconds(stamp_us);
  ticks.left = *parseInteger(fields_[kLeftField - 1]);
  ticks.right = *parseInteger(fields_[kRightField - 1]);

  LaserScan scan;
  scan.stamp = ticks.stamp;
  const double fov_rad = settings_.field_of_view_deg * M_PI / 180.0;
  scan.angle_min_rad = -0.5 * fov_rad;
  scan.angle_increment_rad = fov_rad / static_cast<double>(settings_.beam_count - 1);
  scan.range_min_m = settings_.range_min_m;
  scan.range_max_m = settings_.range_max_m;
  scan.ranges_m.reserve(settings_.beam_count);
  for (std::size_t beam = 0; beam < settings_.beam_count; ++beam) {
    const std::size_t i = settings_.header_field_count + beam;
    const std::optional<std::int64_t> mm = parseInteger(fields_[i]);
    if (!mm) {
      return LineProblem{"not a number", "field " + std::to_string(i + 1) + ": " +
                                             quoted(fields_[i]) + " is not an integer"};
    }
    if (*mm < 0) {
      return LineProblem{"negative", "field " + std::to_string(i + 1) + ": range " +
                                         std::to_string(*mm) + " mm is negative"};
    }
    const double metres = static_cast<double>(*mm) / 1000.0;
    if (*mm == 0 || metres > settings_.range_max_m) {
      scan.ranges_m.push_back(LaserScan::kNoReturn);
    } else if (metres < settings_.range_min_m) {
      scan.ranges_m.push_back(LaserScan::kInvalid);
    } else {
      scan.ranges_m.push_back(static_cast<float>(metres));
    }
  }
  if (settings_.beam_order == BeamOrder::kLastIsMostClockwise) {
    std::reverse(scan.ranges_m.begin(), scan.ranges_m.end());
  }
  pending_.emplace_back(ticks);
  pending_.emplace_back(std::move(scan));
  return std::nullopt;
}

}  // namespace mrslam::drivers
