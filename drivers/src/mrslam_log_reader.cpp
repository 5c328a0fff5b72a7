#include <charconv>
#include <cmath>

#include "mrslam/drivers/mrslam_log.hpp"

namespace mrslam::drivers {

namespace {

// Reads fields one after the other; the first failure is kept as the line's problem.
class FieldCursor {
 public:
  FieldCursor(const std::vector<std::string_view>& fields, LineProblem& problem)
      : fields_(fields), problem_(problem) {}

  bool failed() const { return failed_; }
  std::size_t left() const { return fields_.size() - next_; }
  std::string_view peek() const { return next_ < fields_.size() ? fields_[next_] : ""; }
  void skip() { ++next_; }

  std::int64_t integer(const char* what) {
    const std::string_view field = take(what);
    std::int64_t value = 0;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (!failed_ && (error != std::errc() || end != field.data() + field.size())) {
      fail("not a number", std::string(what) + " is not an integer: '" + std::string(field) + "'");
    }
    return value;
  }

  template <class Float>
  Float number(const char* what, bool must_be_finite) {
    const std::string_view field = take(what);
    Float value = 0;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (failed_) {
      return value;
    }
    if (error != std::errc() || end != field.data() + field.size()) {
      fail("not a number", std::string(what) + " is not a number: '" + std::string(field) + "'");
    } else if (must_be_finite && !std::isfinite(value)) {
      fail("not finite", std::string(what) + " is not finite");
    }
    return value;
  }

  void fail(const char* kind, const std::string& what) {
    if (!failed_) {
      failed_ = true;
      problem_ = {kind, what};
    }
  }

 private:
  std::string_view take(const char* what) {
    if (next_ >= fields_.size()) {
      fail("field count", std::string("the line ends before ") + what);
      return "0";
    }
    return fields_[next_++];
  }

  const std::vector<std::string_view>& fields_;
  LineProblem& problem_;
  std::size_t next_ = 1;  // field 0 is the record type
  bool failed_ = false;
};

constexpr std::int64_t kMaxBeams = 1 << 20;

LaserScan parseLaser(FieldCursor& fields) {
  LaserScan scan;
  scan.stamp = Stamp{fields.integer("the time stamp")};
  scan.angle_min_rad = fields.number<double>("angle_min", true);
  scan.angle_increment_rad = fields.number<double>("angle_increment", true);
  scan.range_min_m = fields.number<double>("range_min", true);
  scan.range_max_m = fields.number<double>("range_max", true);
  const std::int64_t count = fields.integer("the beam count");
  if (fields.failed()) {
    return scan;
  }
  if (count < 0 || count > kMaxBeams || static_cast<std::size_t>(count) > fields.left()) {
    fields.fail("field count", "the beam count " + std::to_string(count) +
                                   " disagrees with the fields on the line");
    return scan;
  }
  scan.ranges_m.reserve(static_cast<std::size_t>(count));
  for (std::int64_t i = 0; i < count && !fields.failed(); ++i) {
    scan.ranges_m.push_back(fields.number<float>("a range", false));
  }
  if (!fields.failed() && fields.left() == 4 && fields.peek() == "POSE") {
    fields.skip();
    const double x = fields.number<double>("the pose x", true);
    const double y = fields.number<double>("the pose y", true);
    const double theta = fields.number<double>("the pose theta", true);
    scan.logged_pose = SE2(x, y, theta);
  }
  return scan;
}

}  // namespace

MrslamLogReader::MrslamLogReader(MrslamLogSettings settings)
    : settings_(std::move(settings)),
      lines_(settings_.path),
      malformed_("mrslam log " + settings_.path, settings_.malformed_policy) {
  std::string line;
  if (!lines_.next(line) || line != kMrslamLogMagic) {
    throw std::runtime_error(settings_.path + ": not an mrslam log (the first line must be '" +
                             std::string(kMrslamLogMagic) + "')");
  }
}

std::string MrslamLogReader::describe() const {
  return "mrslam log " + settings_.path;
}

std::optional<Sample> MrslamLogReader::next() {
  std::string line;
  while (lines_.next(line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) {
      continue;  // a blank line
    }
    if (line[0] == '#') {
      if (line.rfind("# robot ", 0) == 0) {
        robot_id_ = line.substr(8);
      }
      continue;
    }
    LineProblem problem;
    std::optional<Sample> sample = parseLine(line, problem);
    if (!sample) {
      ++counters_.malformed_records;
      malformed_.handle(settings_.path, lines_.lineNumber(), problem);
      continue;
    }
    const Stamp stamp = stampOf(*sample);
    if (last_stamp_ && stamp < *last_stamp_) {
      ++counters_.out_of_order_stamps;
    }
    last_stamp_ = stamp;
    ++counters_.samples;
    return sample;
  }
  return std::nullopt;
}

std::optional<Sample> MrslamLogReader::parseLine(const std::string& line,
                                                 LineProblem& problem) const {
  std::vector<std::string_view> fields;
  splitFields(line, fields);
  if (fields.empty()) {
    problem = {"blank", "the line holds only white space"};
    return std::nullopt;
  }
  FieldCursor cursor(fields, problem);
  const std::string_view type = fields.front();
  Sample sample;
  if (type == "TICKS") {
    WheelTicks ticks;
    ticks.stamp = Stamp{cursor.integer("the time stamp")};
    ticks.left = cursor.integer("the left count");
    ticks.right = cursor.integer("the right count");
    sample = ticks;
  } else if (type == "ODOM") {
    OdometryPose odometry;
    odometry.stamp = Stamp{cursor.integer("the time stamp")};
    const double x = cursor.number<double>("x", true);
    const double y = cursor.number<double>("y", true);
    const double theta = cursor.number<double>("theta", true);
    odometry.T_odom_robot = SE2(x, y, theta);
    sample = odometry;
  } else if (type == "IMU") {
    ImuSample imu;
    imu.stamp = Stamp{cursor.integer("the time stamp")};
    imu.roll_rad = cursor.number<double>("roll", true);
    imu.pitch_rad = cursor.number<double>("pitch", true);
    imu.yaw_rad = cursor.number<double>("yaw", true);
    imu.has_orientation = cursor.integer("has_orientation") != 0;
    for (int axis = 0; axis < 3; ++axis) {
      imu.angular_rate_rad_s[axis] = cursor.number<double>("a rate", true);
    }
    for (int axis = 0; axis < 3; ++axis) {
      imu.acceleration_g[axis] = cursor.number<double>("an acceleration", true);
    }
    sample = imu;
  } else if (type == "LASER") {
    sample = parseLaser(cursor);
  } else {
    problem = {"unknown record", "unknown record type '" + std::string(type) + "'"};
    return std::nullopt;
  }
  if (!cursor.failed() && cursor.left() != 0) {
    cursor.fail("field count", "unexpected fields at the end of the line");
  }
  return cursor.failed() ? std::nullopt : std::optional<Sample>(std::move(sample));
}

}  // namespace mrslam::drivers
