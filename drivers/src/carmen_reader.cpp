#include "mrslam/drivers/carmen_reader.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <stdexcept>
#include <utility>

#include "mrslam/common/se2.hpp"

namespace mrslam::drivers {
namespace {

constexpr std::size_t kFlaserExtraFields = 11;  // name, n, 6 pose values, 3 time stamp fields
constexpr std::size_t kOdomFields = 10;

const CarmenSettings& checked(const CarmenSettings& s) {
  if (!(s.range_min_m >= 0.0 && s.max_range_m > s.range_min_m && std::isfinite(s.max_range_m))) {
    throw std::invalid_argument("CarmenSettings: need 0 <= range_min_m < max_range_m, got " +
                                std::to_string(s.range_min_m) + " and " +
                                std::to_string(s.max_range_m));
  }
  return s;
}

std::string fieldText(std::size_t index, std::string_view text) {
  return "field " + std::to_string(index + 1) + ": '" + std::string(text) + "'";
}

/// A CARMEN message name: an upper-case letter, then upper-case letters, digits or '_'.
bool isMessageName(std::string_view text) {
  if (text.empty() || text[0] < 'A' || text[0] > 'Z') {
    return false;
  }
  for (const char c : text) {
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) {
      return false;
    }
  }
  return true;
}

bool includesOdomLines(CarmenOdometry odometry) {
  return odometry != CarmenOdometry::kFlaserOdom;
}
bool includesFlaserOdom(CarmenOdometry odometry) {
  return odometry != CarmenOdometry::kOdomLines;
}

}  // namespace

CarmenReader::CarmenReader(CarmenSettings settings)
    : settings_(checked(settings)),
      lines_(settings_.path),
      malformed_("carmen log", settings_.malformed_policy) {
  while (!flaser_seen_ && readLine()) {
  }
}

std::string CarmenReader::describe() const {
  return "carmen log " + settings_.path;
}

SourceCounters CarmenReader::counters() const {
  SourceCounters counters = counters_;
  counters.malformed_records = malformed_.count();
  return counters;
}

double CarmenReader::beamIncrementRad(std::size_t beam_count) {
  if (beam_count < 2) {
    return 0.0;
  }
  const std::size_t intervals = beam_count % 2 == 1 ? beam_count - 1 : beam_count;
  return M_PI / static_cast<double>(intervals);
}

std::optional<SE2> CarmenReader::laserMounting() const {
  if (flaser_mounting_) {
    return flaser_mounting_;
  }
  if (param_laser_offset_m_) {
    return SE2(*param_laser_offset_m_, 0.0, 0.0);
  }
  return std::nullopt;
}

bool CarmenReader::readLine() {
  if (!lines_.next(line_)) {
    return false;
  }
  splitFields(line_, fields_);
  if (const std::optional<LineProblem> problem = parseLine()) {
    pending_.clear();
    flaser_pose_.reset();
    malformed_.handle(settings_.path, lines_.lineNumber(), *problem);
  }
  return true;
}

std::optional<Sample> CarmenReader::next() {
  while (pending_.empty()) {
    if (!readLine()) {
      return std::nullopt;
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

std::optional<LineProblem> CarmenReader::parseLine() {
  if (fields_.empty() || fields_[0].front() == '#') {
    return std::nullopt;
  }
  const std::string_view name = fields_[0];
  if (name == "FLASER") {
    return parseFlaser();
  }
  if (name == "ODOM") {
    return parseOdom();
  }
  if (name == "PARAM") {
    return parseParam();
  }
  if (name == "NEFF") {
    return std::nullopt;
  }
  if (isMessageName(name)) {
    ++skipped_records_;
    return std::nullopt;
  }
  return LineProblem{"not a message", fieldText(0, name) + " is not a message name"};
}

std::optional<LineProblem> CarmenReader::numbers(std::size_t first, std::size_t count,
                                                 double* out) const {
  for (std::size_t i = first; i < first + count; ++i) {
    const std::optional<double> value = parseNumber(fields_[i]);
    if (!value) {
      return LineProblem{"not a number", fieldText(i, fields_[i]) + " is not a number"};
    }
    if (!std::isfinite(*value)) {
      return LineProblem{"not finite", fieldText(i, fields_[i]) + " is not finite"};
    }
    out[i - first] = *value;
  }
  return std::nullopt;
}

std::optional<LineProblem> CarmenReader::parseFlaser() {
  flaser_pose_.reset();
  if (fields_.size() < 2) {
    return LineProblem{"field count", "FLASER needs at least 2 fields, found 1"};
  }
  const std::optional<std::int64_t> n = parseInteger(fields_[1]);
  if (!n || *n <= 0) {
    return LineProblem{"beam count",
                       fieldText(1, fields_[1]) + " is not a beam count (a positive integer)"};
  }
  const auto beams = static_cast<std::uint64_t>(*n);
  if (beams + kFlaserExtraFields != fields_.size()) {
    return LineProblem{"field count", "FLASER with " + std::to_string(beams) + " beams needs " +
                                          std::to_string(beams + kFlaserExtraFields) +
                                          " fields, found " + std::to_string(fields_.size())};
  }
  const std::size_t count = static_cast<std::size_t>(beams);
  values_.resize(count + 6);
  if (auto problem = numbers(2, count + 6, values_.data())) {
    return problem;
  }
  const std::size_t stamp_index = 2 + count + 6;
  const std::optional<Stamp> stamp = parseStampSeconds(fields_[stamp_index]);
  if (!stamp) {
    return LineProblem{"bad stamp",
                       fieldText(stamp_index, fields_[stamp_index]) + " is not a time stamp"};
  }
  double logger_stamp = 0.0;
  if (auto problem = numbers(stamp_index + 2, 1, &logger_stamp)) {
    return problem;
  }

  LaserScan scan;
  scan.stamp = *stamp;
  scan.angle_min_rad = -0.5 * M_PI;
  scan.angle_increment_rad = beamIncrementRad(count);
  scan.range_min_m = settings_.range_min_m;
  scan.range_max_m = settings_.max_range_m;
  scan.ranges_m.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double range = values_[i];
    if (range < 0.0) {
      return LineProblem{"negative", fieldText(2 + i, fields_[2 + i]) + " is a negative range"};
    }
    if (range >= settings_.max_range_m) {
      scan.ranges_m.push_back(LaserScan::kNoReturn);
    } else if (range < settings_.range_min_m) {
      scan.ranges_m.push_back(LaserScan::kInvalid);
    } else {
      scan.ranges_m.push_back(static_cast<float>(range));
    }
  }
  const double* pose = values_.data() + count;
  const SE2 T_world_laser(pose[0], pose[1], pose[2]);
  const SE2 T_world_robot(pose[3], pose[4], pose[5]);
  scan.logged_pose = T_corrected_raw_ * T_world_laser;
  if (includesFlaserOdom(settings_.odometry)) {
    pending_.emplace_back(OdometryPose{*stamp, T_corrected_raw_ * T_world_robot});
  }
  pending_.emplace_back(std::move(scan));
  flaser_pose_ = std::array<double, 3>{pose[0], pose[1], pose[2]};
  flaser_stamp_ = *stamp;
  noteMounting(T_world_laser, T_world_robot);
  return std::nullopt;
}

void CarmenReader::noteMounting(const SE2& T_world_laser, const SE2& T_world_robot) {
  const SE2 T_robot_laser = T_world_robot.inverse() * T_world_laser;
  flaser_seen_ = true;
  if (!flaser_mounting_) {
    flaser_mounting_ = T_robot_laser;
    return;
  }
  const SE2 difference = flaser_mounting_->inverse() * T_robot_laser;
  if (difference.translation().norm() > kMountingToleranceM ||
      std::abs(difference.theta()) > kMountingToleranceRad) {
    ++mounting_mismatches_;
  }
}

std::optional<LineProblem> CarmenReader::parseParam() {
  if (fields_.size() < 3 || fields_[1] != "robot_frontlaser_offset") {
    return std::nullopt;
  }
  double offset_m = 0.0;
  if (auto problem = numbers(2, 1, &offset_m)) {
    return problem;
  }
  param_laser_offset_m_ = offset_m;
  return std::nullopt;
}

std::optional<LineProblem> CarmenReader::parseOdom() {
  const std::optional<std::array<double, 3>> flaser_pose = flaser_pose_;
  flaser_pose_.reset();
  if (fields_.size() != kOdomFields) {
    return LineProblem{"field count", "ODOM needs " + std::to_string(kOdomFields) +
                                          " fields, found " + std::to_string(fields_.size())};
  }
  double values[6];
  if (auto problem = numbers(1, 6, values)) {
    return problem;
  }
  const std::optional<Stamp> stamp = parseStampSeconds(fields_[7]);
  if (!stamp) {
    return LineProblem{"bad stamp", fieldText(7, fields_[7]) + " is not a time stamp"};
  }
  double logger_stamp = 0.0;
  if (auto problem = numbers(9, 1, &logger_stamp)) {
    return problem;
  }
  const bool reanchor = flaser_pose && (*flaser_pose)[0] == values[0] &&
                        (*flaser_pose)[1] == values[1] && (*flaser_pose)[2] == values[2] &&
                        secondsBetween(*stamp, flaser_stamp_) > kReanchorLagS;
  if (reanchor) {
    ++reanchor_odom_records_;
  }
  const SE2 T_world_robot = reanchor
                                ? T_corrected_raw_ * SE2(values[0], values[1], values[2])
                                : correctReversing(SE2(values[0], values[1], values[2]), values[3]);
  if (includesOdomLines(settings_.odometry) && (!reanchor || settings_.emit_reanchor_odom)) {
    pending_.emplace_back(OdometryPose{*stamp, T_world_robot});
  }
  return std::nullopt;
}

SE2 CarmenReader::correctReversing(const SE2& T_world_robot_raw, double tv_mps) {
  if (last_raw_odom_) {
    const SE2 step = last_raw_odom_->inverse() * T_world_robot_raw;
    if (tv_mps < -kReversingSpeedMps && step.x() > kReversingStepM) {
      const SE2 mirrored(-step.x(), -step.y(), step.theta());
      const SE2 T_world_corrected = T_corrected_raw_ * *last_raw_odom_ * mirrored;
      T_corrected_raw_ = T_world_corrected * T_world_robot_raw.inverse();
      if (++reversed_odometry_steps_ == 1) {
        spdlog::warn(
            "carmen: {}: an ODOM step runs {:.3f} m ahead while reversing at {:.2f} m/s: "
            "mirrored, as every such step will be (counted)",
            settings_.path, step.x(), tv_mps);
      }
    }
  }
  last_raw_odom_ = T_world_robot_raw;
  return T_corrected_raw_ * T_world_robot_raw;
}

}  // namespace mrslam::drivers
