#include "mrslam/drivers/scip_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mrslam::drivers::scip {
namespace {

KeyValues urg04lxParameters() {
  return {{"MODL", "URG-04LX(Hokuyo Automatic Co.,Ltd.)"},
          {"DMIN", "20"},
          {"DMAX", "5600"},
          {"ARES", "1024"},
          {"AMIN", "44"},
          {"AMAX", "725"},
          {"AFRT", "384"},
          {"SCAN", "600"}};
}

ScanGeometry urg04lx() {
  const auto geometry = ScanGeometry::fromParameters(urg04lxParameters());
  EXPECT_TRUE(geometry.ok()) << geometry.reason();
  return geometry.ok() ? geometry.value() : ScanGeometry{};
}

TEST(ScanGeometryTest, AnglesAndPeriodOfTheUrg04lxFromItsParameters) {
  const ScanGeometry g = urg04lx();
  EXPECT_EQ(g.measuredSteps(), 682);
  EXPECT_DOUBLE_EQ(g.stepAngleRad(384), 0.0);  // AFRT: straight ahead
  EXPECT_NEAR(g.stepAngleRad(44), -340 * 2 * M_PI / 1024, 1e-12);
  EXPECT_NEAR(g.stepAngleRad(725), 341 * 0.3515625 * M_PI / 180, 1e-12);
  EXPECT_DOUBLE_EQ(g.scanPeriodS(), 0.1);
  EXPECT_DOUBLE_EQ(g.stepDurationS(), 0.1 / 1024);
}

TEST(ScanGeometryTest, RejectsMissingNonNumericAndInconsistentParameters) {
  KeyValues missing = urg04lxParameters();
  missing.erase("AFRT");
  EXPECT_NE(ScanGeometry::fromParameters(missing).reason().find("no AFRT"), std::string::npos);
  KeyValues text = urg04lxParameters();
  text["SCAN"] = "600rpm";
  EXPECT_NE(ScanGeometry::fromParameters(text).reason().find("SCAN"), std::string::npos);
  KeyValues inverted = urg04lxParameters();
  inverted["AMIN"] = "800";
  EXPECT_FALSE(ScanGeometry::fromParameters(inverted).ok());
  KeyValues no_span = urg04lxParameters();
  no_span["DMAX"] = "20";
  EXPECT_FALSE(ScanGeometry::fromParameters(no_span).ok());
  KeyValues still = urg04lxParameters();
  still["SCAN"] = "0";
  EXPECT_FALSE(ScanGeometry::fromParameters(still).ok());
}

TEST(RangeConversionTest, ErrorCodesNoEchoAndDistances) {
  const ScanGeometry g = urg04lx();
  EXPECT_TRUE(std::isnan(rangeToMetres(7, g, ZeroRange::kInvalid)));   // error code
  EXPECT_TRUE(std::isnan(rangeToMetres(19, g, ZeroRange::kInvalid)));  // just below DMIN
  EXPECT_FLOAT_EQ(rangeToMetres(20, g, ZeroRange::kInvalid), 0.02f);
  EXPECT_FLOAT_EQ(rangeToMetres(5600, g, ZeroRange::kInvalid), 5.6f);
  EXPECT_TRUE(std::isinf(rangeToMetres(5601, g, ZeroRange::kInvalid)));  // beyond DMAX
  EXPECT_TRUE(std::isnan(rangeToMetres(0, g, ZeroRange::kInvalid)));
  EXPECT_TRUE(std::isinf(rangeToMetres(0, g, ZeroRange::kNoReturn)));
  EXPECT_TRUE(std::isnan(rangeToMetres(1, g, ZeroRange::kNoReturn)));  // other codes stay invalid
}

TEST(ToLaserScanTest, FullScanGeometryAndLimits) {
  const ScanGeometry g = urg04lx();
  ScanRequest request;
  request.start_step = 44;
  request.end_step = 725;
  const LaserScan scan =
      toLaserScan(std::vector<std::uint32_t>(682, 1000), g, request, ZeroRange::kInvalid);
  ASSERT_EQ(scan.ranges_m.size(), 682u);
  EXPECT_NEAR(scan.angle_min_rad, g.stepAngleRad(44), 1e-12);
  EXPECT_NEAR(scan.angle_increment_rad, 2 * M_PI / 1024, 1e-12);
  EXPECT_NEAR(scan.beamAngle(681), g.stepAngleRad(725), 1e-12);
  EXPECT_DOUBLE_EQ(scan.range_min_m, 0.02);
  EXPECT_DOUBLE_EQ(scan.range_max_m, 5.6);
  EXPECT_FLOAT_EQ(scan.ranges_m[100], 1.0f);
}

TEST(ToLaserScanTest, ClusteredBeamsPointAtTheMiddleOfTheirCluster) {
  const ScanGeometry g = urg04lx();
  ScanRequest request;
  request.start_step = 100;
  request.end_step = 399;
  request.cluster = 3;
  const LaserScan scan =
      toLaserScan(std::vector<std::uint32_t>(100, 500), g, request, ZeroRange::kInvalid);
  EXPECT_NEAR(scan.angle_min_rad, g.stepAngleRad(101), 1e-12);
  EXPECT_NEAR(scan.angle_increment_rad, 3 * 2 * M_PI / 1024, 1e-12);
  EXPECT_NEAR(scan.beamAngle(99), g.stepAngleRad(398), 1e-12);
}

}  // namespace
}  // namespace mrslam::drivers::scip
