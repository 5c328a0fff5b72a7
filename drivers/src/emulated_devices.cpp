// The conversions an emulated robot makes from samples to what its devices send, and the feed
// file of the emulated Phidget board.

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "mrslam/drivers/emulated_robot.hpp"

namespace mrslam::drivers {

namespace {

constexpr std::uint32_t kErrorCode = 1;  // below DMIN: the driver reads it as invalid
constexpr int kSmallestDmin = 20;        // raw values below it are error codes

bool geometryMatches(const LaserScan& scan, const HokuyoModel& model) {
  const scip::ScanGeometry& g = model.geometry;
  const double increment = 2.0 * M_PI / g.ares;
  return static_cast<int>(scan.ranges_m.size()) == g.measuredSteps() &&
         std::abs(scan.angle_increment_rad - increment) < 1e-9 &&
         std::abs(scan.angle_min_rad - g.stepAngleRad(g.amin)) < 1e-6;
}

}  // namespace

Result<HokuyoModel> hokuyoModelFor(const LaserScan& scan, double scan_rate_hz) {
  if (scan.ranges_m.empty() || !(scan.angle_increment_rad > 0.0) || !(scan_rate_hz > 0.0)) {
    return Result<HokuyoModel>::failure("the first scan has no beams or no angle increment");
  }
  const int rpm = static_cast<int>(std::lround(60.0 * scan_rate_hz));
  for (HokuyoModel model : {HokuyoModel::urg04lx(), HokuyoModel::ubg05ln()}) {
    if (geometryMatches(scan, model)) {
      model.geometry.scan_rpm = rpm;
      return Result<HokuyoModel>::success(model);
    }
  }
  HokuyoModel model = HokuyoModel::urg04lx();
  model.product = "SOKUIKI Sensor (emulated)";
  model.model_name = "emulated from a log's scans";
  const double turn_steps = 2.0 * M_PI / scan.angle_increment_rad;
  const double front_steps = -scan.angle_min_rad / scan.angle_increment_rad;
  if (std::abs(turn_steps - std::round(turn_steps)) > 1e-3 * turn_steps ||
      std::abs(front_steps - std::round(front_steps)) > 1e-3 || front_steps < 0.0) {
    return Result<HokuyoModel>::failure("no Hokuyo step geometry fits the scans (" +
                                        std::to_string(scan.ranges_m.size()) + " beams from " +
                                        std::to_string(scan.angle_min_rad) + " rad by " +
                                        std::to_string(scan.angle_increment_rad) + " rad)");
  }
  scip::ScanGeometry& g = model.geometry;
  g.ares = static_cast<int>(std::lround(turn_steps));
  g.amin = 0;
  g.amax = static_cast<int>(scan.ranges_m.size()) - 1;
  g.afrt = static_cast<int>(std::lround(front_steps));
  g.dmin_mm = std::max(kSmallestDmin, static_cast<int>(std::lround(scan.range_min_m * 1000.0)));
  g.dmax_mm = std::max(g.dmin_mm + 1, static_cast<int>(std::lround(scan.range_max_m * 1000.0)));
  g.scan_rpm = rpm;
  return Result<HokuyoModel>::success(model);
}

std::vector<std::uint32_t> rawRangesOf(const LaserScan& scan, const HokuyoModel& model) {
  const scip::ScanGeometry& g = model.geometry;
  std::vector<std::uint32_t> raw(static_cast<std::size_t>(g.measuredSteps()), kErrorCode);
  const std::size_t beams = std::min(raw.size(), scan.ranges_m.size());
  for (std::size_t i = 0; i < beams; ++i) {
    const float range = scan.ranges_m[i];
    if (std::isnan(range)) {
      continue;  // the error code
    }
    const long long mm = std::isinf(range) ? g.dmax_mm + 1LL : std::llround(range * 1000.0);
    if (mm < g.dmin_mm) {
      continue;  // closer than the device measures: an error code as on the device
    }
    raw[i] = static_cast<std::uint32_t>(std::min<long long>(mm, g.dmax_mm + 1LL));
  }
  return raw;
}

gx1::DeviceState gx1StateOf(const ImuSample& sample, bool z_down) {
  // The inverse of Gx1Driver::toSample: z down is a turn by π about x (self-inverse).
  const double flip = z_down ? -1.0 : 1.0;
  const Eigen::Vector3d axes(1.0, flip, flip);
  gx1::DeviceState state;
  state.roll_rad = sample.roll_rad;
  state.pitch_rad = flip * sample.pitch_rad;
  state.yaw_rad = flip * sample.yaw_rad;
  const auto known = [](const Eigen::Vector3d& v) -> Eigen::Vector3d {
    return v.allFinite() ? v : Eigen::Vector3d::Zero().eval();
  };
  state.acceleration_g = known(sample.acceleration_g).cwiseProduct(axes);
  state.angular_rate_rad_s = known(sample.angular_rate_rad_s).cwiseProduct(axes);
  state.magnetic_gauss = Eigen::Vector3d(0.2, 0.0, 0.4);  // a plausible field; unused
  return state;
}

PhidgetFeedWriter::PhidgetFeedWriter(std::string path) : path_(std::move(path)) {}

PhidgetFeedWriter::~PhidgetFeedWriter() {
  std::remove(path_.c_str());
}

void PhidgetFeedWriter::write(const std::vector<std::int64_t>& counts) {
  const std::string temporary = path_ + ".tmp";
  {
    std::ofstream file(temporary, std::ios::trunc);
    file << "mrslam-phidget-feed 1\n";
    for (std::size_t i = 0; i < counts.size(); ++i) {
      file << (i == 0 ? "" : " ") << counts[i];
    }
    file << '\n';
    if (!file) {
      throw std::runtime_error("cannot write the encoder feed " + temporary);
    }
  }
  if (std::rename(temporary.c_str(), path_.c_str()) != 0) {
    throw std::runtime_error("cannot replace the encoder feed " + path_ + ": " +
                             std::strerror(errno));
  }
}

}  // namespace mrslam::drivers
