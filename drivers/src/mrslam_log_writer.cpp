#include <zlib.h>

#include <charconv>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "mrslam/drivers/mrslam_log.hpp"

namespace mrslam::drivers {

namespace {

// Shortest text that reads back to the same bits (std::to_chars round-trip guarantee);
// "inf", "-inf" and "nan" for the special values.
template <class Float>
void appendNumber(std::string& line, Float value) {
  static_assert(std::is_floating_point_v<Float>);
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  line.push_back(' ');
  line.append(buffer, result.ptr);
}

void appendInteger(std::string& line, std::int64_t value) {
  line.push_back(' ');
  line += std::to_string(value);
}

std::string laserLine(const LaserScan& scan) {
  std::string line = "LASER";
  appendInteger(line, scan.stamp.ns);
  appendNumber(line, scan.angle_min_rad);
  appendNumber(line, scan.angle_increment_rad);
  appendNumber(line, scan.range_min_m);
  appendNumber(line, scan.range_max_m);
  appendInteger(line, static_cast<std::int64_t>(scan.ranges_m.size()));
  for (const float range : scan.ranges_m) {
    appendNumber(line, range);
  }
  if (scan.logged_pose) {
    line += " POSE";
    appendNumber(line, scan.logged_pose->x());
    appendNumber(line, scan.logged_pose->y());
    appendNumber(line, scan.logged_pose->theta());
  }
  return line;
}

std::string imuLine(const ImuSample& imu) {
  std::string line = "IMU";
  appendInteger(line, imu.stamp.ns);
  appendNumber(line, imu.roll_rad);
  appendNumber(line, imu.pitch_rad);
  appendNumber(line, imu.yaw_rad);
  appendInteger(line, imu.has_orientation ? 1 : 0);
  for (int axis = 0; axis < 3; ++axis) {
    appendNumber(line, imu.angular_rate_rad_s[axis]);
  }
  for (int axis = 0; axis < 3; ++axis) {
    appendNumber(line, imu.acceleration_g[axis]);
  }
  return line;
}

}  // namespace

std::string formatSampleLine(const Sample& sample) {
  if (const auto* scan = std::get_if<LaserScan>(&sample)) {
    return laserLine(*scan);
  }
  if (const auto* imu = std::get_if<ImuSample>(&sample)) {
    return imuLine(*imu);
  }
  std::string line;
  if (const auto* ticks = std::get_if<WheelTicks>(&sample)) {
    line = "TICKS";
    appendInteger(line, ticks->stamp.ns);
    appendInteger(line, ticks->left);
    appendInteger(line, ticks->right);
  } else if (const auto* odometry = std::get_if<OdometryPose>(&sample)) {
    line = "ODOM";
    appendInteger(line, odometry->stamp.ns);
    appendNumber(line, odometry->T_odom_robot.x());
    appendNumber(line, odometry->T_odom_robot.y());
    appendNumber(line, odometry->T_odom_robot.theta());
  }
  return line;
}

struct MrslamLogWriter::File {
  gzFile handle = nullptr;
};

MrslamLogWriter::MrslamLogWriter(const std::string& path, const std::string& robot_id)
    : path_(path), file_(std::make_unique<File>()) {
  const bool compress = path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0;
  file_->handle = gzopen(path.c_str(), compress ? "wb6" : "wbT");
  if (file_->handle == nullptr) {
    throw std::runtime_error(path + ": cannot create the log: " + std::strerror(errno));
  }
  writeLine(kMrslamLogMagic);
  writeLine("# robot " + robot_id);
}

MrslamLogWriter::~MrslamLogWriter() {
  if (file_->handle != nullptr) {
    gzclose(file_->handle);
  }
}

void MrslamLogWriter::writeLine(const std::string& line) {
  if (file_->handle == nullptr) {
    throw std::runtime_error(path_ + ": the log is closed");
  }
  const auto size = static_cast<int>(line.size());
  if (gzwrite(file_->handle, line.data(), static_cast<unsigned>(size)) != size ||
      gzputc(file_->handle, '\n') != '\n') {
    throw std::runtime_error(path_ + ": cannot write the log");
  }
}

void MrslamLogWriter::write(const Sample& sample) {
  writeLine(formatSampleLine(sample));
}

void MrslamLogWriter::close() {
  if (file_->handle == nullptr) {
    return;
  }
  const int result = gzclose(file_->handle);
  file_->handle = nullptr;
  if (result != Z_OK) {
    throw std::runtime_error(path_ + ": cannot finish the log");
  }
}

}  // namespace mrslam::drivers
