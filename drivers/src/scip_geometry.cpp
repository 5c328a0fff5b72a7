#include "mrslam/drivers/scip_geometry.hpp"

#include <charconv>
#include <cmath>
#include <string>

namespace mrslam::drivers::scip {
namespace {

constexpr int kMaxStep = 9999;  // steps travel as 4 decimal digits

Parsed<int> integerParameter(const KeyValues& parameters, const std::string& key) {
  const auto found = parameters.find(key);
  if (found == parameters.end()) {
    return Parsed<int>::failure(ErrorKind::kGarbage, "PP reply has no " + key);
  }
  const std::string& text = found->second;
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) {
    return Parsed<int>::failure(ErrorKind::kGarbage,
                                "PP " + key + " '" + text + "' is not an integer");
  }
  return Parsed<int>::success(value);
}

std::string checkGeometry(const ScanGeometry& g) {
  if (g.dmin_mm < 0 || g.dmax_mm <= g.dmin_mm) {
    return "need 0 <= DMIN < DMAX";
  }
  if (g.ares <= 0 || g.ares > kMaxStep + 1) {
    return "need 0 < ARES <= 10000";
  }
  if (g.amin < 0 || g.amax < g.amin || g.amax > kMaxStep) {
    return "need 0 <= AMIN <= AMAX <= 9999";
  }
  if (g.afrt < 0 || g.afrt > kMaxStep) {
    return "need 0 <= AFRT <= 9999";
  }
  if (g.scan_rpm <= 0) {
    return "need SCAN > 0";
  }
  return {};
}

}  // namespace

Parsed<ScanGeometry> ScanGeometry::fromParameters(const KeyValues& parameters) {
  ScanGeometry geometry;
  const std::pair<const char*, int ScanGeometry::*> kFields[] = {
      {"DMIN", &ScanGeometry::dmin_mm},  {"DMAX", &ScanGeometry::dmax_mm},
      {"ARES", &ScanGeometry::ares},     {"AMIN", &ScanGeometry::amin},
      {"AMAX", &ScanGeometry::amax},     {"AFRT", &ScanGeometry::afrt},
      {"SCAN", &ScanGeometry::scan_rpm},
  };
  for (const auto& [key, field] : kFields) {
    const auto value = integerParameter(parameters, key);
    if (!value) {
      return Parsed<ScanGeometry>::failure(value.error(), value.reason());
    }
    geometry.*field = value.value();
  }
  const std::string problem = checkGeometry(geometry);
  if (!problem.empty()) {
    return Parsed<ScanGeometry>::failure(ErrorKind::kGarbage, "PP geometry: " + problem);
  }
  return Parsed<ScanGeometry>::success(geometry);
}

double ScanGeometry::stepAngleRad(double step) const {
  return (step - afrt) * 2.0 * M_PI / ares;
}

float rangeToMetres(std::uint32_t value_mm, const ScanGeometry& geometry, ZeroRange zero) {
  if (value_mm == 0) {
    return zero == ZeroRange::kNoReturn ? LaserScan::kNoReturn : LaserScan::kInvalid;
  }
  if (value_mm < static_cast<std::uint32_t>(geometry.dmin_mm)) {
    return LaserScan::kInvalid;
  }
  if (value_mm > static_cast<std::uint32_t>(geometry.dmax_mm)) {
    return LaserScan::kNoReturn;
  }
  return static_cast<float>(value_mm) / 1000.0f;  // exact mm, correctly rounded metres
}

LaserScan toLaserScan(const std::vector<std::uint32_t>& ranges_mm, const ScanGeometry& geometry,
                      const ScanRequest& request, ZeroRange zero) {
  LaserScan scan;
  const double first_beam_step = request.start_step + 0.5 * (request.cluster - 1);
  scan.angle_min_rad = geometry.stepAngleRad(first_beam_step);
  scan.angle_increment_rad = request.cluster * 2.0 * M_PI / geometry.ares;
  scan.range_min_m = geometry.dmin_mm / 1000.0;
  scan.range_max_m = geometry.dmax_mm / 1000.0;
  scan.ranges_m.resize(ranges_mm.size());
  for (std::size_t i = 0; i < ranges_mm.size(); ++i) {
    scan.ranges_m[i] = rangeToMetres(ranges_mm[i], geometry, zero);
  }
  return scan;
}

}  // namespace mrslam::drivers::scip
