#include "mrslam/drivers/scip_responder.hpp"

#include <gtest/gtest.h>

#include "mrslam/drivers/scip_codec.hpp"

namespace mrslam::drivers {
namespace {

using scip::LineCheck;

scip::Reply reply(const std::string& text, LineCheck check = LineCheck::kData) {
  auto parsed = scip::parseReply(text, check);
  EXPECT_TRUE(parsed.ok()) << parsed.reason() << " in " << text;
  return parsed.ok() ? parsed.value() : scip::Reply{};
}

scip::ScanRequest requestOf(const std::string& line) {
  scip::ScanRequest request;
  request.command = line.substr(0, 2);
  request.start_step = std::stoi(line.substr(2, 4));
  request.end_step = std::stoi(line.substr(6, 4));
  request.cluster = std::stoi(line.substr(10, 2));
  return request;
}

class ScipResponderTest : public ::testing::Test {
 protected:
  HokuyoModel model_ = HokuyoModel::urg04lx();
  RangeSource ramp_ = hokuyoRangePattern("ramp", model_);
};

TEST_F(ScipResponderTest, StartsInScip11WhenAskedAndSwitchesOnScip20) {
  ScipResponder responder(model_, ramp_, {true, true, false});
  EXPECT_EQ(responder.respond("QT", 0), "QT\nE\n\n");
  EXPECT_FALSE(responder.speaksScip2());
  EXPECT_EQ(responder.respond("SCIP2.0", 0), "SCIP2.0\n0\n\n");
  EXPECT_EQ(responder.respond("QT", 0), "QT\n00P\n\n");
  responder.powerOn();
  EXPECT_FALSE(responder.speaksScip2());
}

TEST_F(ScipResponderTest, IdentityAndParametersParseAsTheDriverReadsThem) {
  ScipResponder responder(HokuyoModel::ubg05ln(), nullptr);
  const auto version =
      scip::parseKeyValues(reply(responder.respond("VV", 0), LineCheck::kKeyValue));
  ASSERT_TRUE(version.ok());
  EXPECT_EQ(version.value().at("PROT"), "SCIP 2.0");
  EXPECT_EQ(version.value().at("PROD"), "SOKUIKI Sensor UBG-05LN");
  const auto parameters =
      scip::parseKeyValues(reply(responder.respond("PP", 0), LineCheck::kKeyValue));
  const auto geometry = scip::ScanGeometry::fromParameters(parameters.value());
  ASSERT_TRUE(geometry.ok()) << geometry.reason();
  EXPECT_EQ(geometry.value().measuredSteps(), 513);
  EXPECT_EQ(geometry.value().dmax_mm, 4500);
  EXPECT_EQ(geometry.value().ares, 1000);
  EXPECT_EQ(geometry.value().afrt - geometry.value().amin, 256);
  const auto state = scip::parseKeyValues(reply(responder.respond("II", 0), LineCheck::kKeyValue));
  EXPECT_EQ(state.value().at("LASR"), "OFF");
}

TEST_F(ScipResponderTest, SingleScanNeedsTheLaserOnAndCarriesThePattern) {
  ScipResponder responder(model_, ramp_);
  EXPECT_EQ(reply(responder.respond("GD0044072501", 0)).status, "10");
  EXPECT_EQ(reply(responder.respond("BM", 0)).status, "00");
  EXPECT_EQ(reply(responder.respond("BM", 0)).status, "02");
  const auto scan = scip::decodeScanReply(reply(responder.respond("GD0044072501", 4321)),
                                          requestOf("GD0044072501"));
  ASSERT_TRUE(scan.ok()) << scan.reason();
  EXPECT_EQ(scan.value().timestamp_ms, 4321u);
  EXPECT_EQ(scan.value().ranges_mm, ramp_(0));
}

TEST_F(ScipResponderTest, ClustersReportTheirSmallestValue) {
  ScipResponder responder(model_, ramp_);
  responder.respond("BM", 0);
  const auto scan =
      scip::decodeScanReply(reply(responder.respond("GD0100019905", 0)), requestOf("GD0100019905"));
  ASSERT_TRUE(scan.ok()) << scan.reason();
  ASSERT_EQ(scan.value().ranges_mm.size(), 20u);
  const auto ranges = ramp_(0);
  for (std::size_t i = 0; i < 20; ++i) {
    const auto first = ranges.begin() + static_cast<std::ptrdiff_t>(100 - 44 + 5 * i);
    EXPECT_EQ(scan.value().ranges_mm[i], *std::min_element(first, first + 5)) << i;
  }
}

TEST_F(ScipResponderTest, StreamsTheRequestedCountWithTheRemainingCountInTheEcho) {
  ScipResponder responder(model_, ramp_);
  EXPECT_EQ(responder.respond("MD0044072501002", 0), "MD0044072501002\n00P\n\n");
  ASSERT_TRUE(responder.streaming());
  const auto first = responder.streamTurn(100);
  const auto second = responder.streamTurn(200);
  ASSERT_TRUE(first && second);
  EXPECT_EQ(reply(*first).echo, "MD0044072501001");
  EXPECT_EQ(reply(*second).echo, "MD0044072501000");
  EXPECT_EQ(reply(*second).status, "99");
  EXPECT_FALSE(responder.streaming());
  EXPECT_FALSE(responder.streamTurn(300).has_value());
}

TEST_F(ScipResponderTest, TheIntervalSkipsTurnsAndQtStopsTheStream) {
  ScipResponder responder(model_, ramp_);
  responder.respond("MD0044072501200", 0);  // interval 2: one turn in three
  int sent = 0;
  for (int turn = 0; turn < 9; ++turn) {
    sent += responder.streamTurn(static_cast<std::uint32_t>(turn * 100)).has_value() ? 1 : 0;
  }
  EXPECT_EQ(sent, 3);
  EXPECT_EQ(responder.respond("QT", 0), "QT\n00P\n\n");
  EXPECT_FALSE(responder.streaming());
  EXPECT_FALSE(responder.laserOn());
}

TEST_F(ScipResponderTest, ParameterErrorsAndUnknownCommands) {
  ScipResponder responder(model_, ramp_);
  EXPECT_EQ(reply(responder.respond("MDxx44072501000", 0)).status, "01");
  EXPECT_EQ(reply(responder.respond("MD0044yy2501000", 0)).status, "02");
  EXPECT_EQ(reply(responder.respond("MD004407250x000", 0)).status, "03");
  EXPECT_EQ(reply(responder.respond("MD0044099901000", 0)).status, "04");
  EXPECT_EQ(reply(responder.respond("MD0400010001000", 0)).status, "05");
  EXPECT_EQ(reply(responder.respond("MD00440725010x0", 0)).status, "07");
  EXPECT_EQ(reply(responder.respond("MD0044", 0)).status, "0C");
  EXPECT_EQ(reply(responder.respond("ZZ", 0)).status, "0E");
  EXPECT_FALSE(responder.streaming());
}

TEST_F(ScipResponderTest, TimeSyncModeAnswersTheCounter) {
  ScipResponder responder(model_, ramp_);
  EXPECT_EQ(reply(responder.respond("TM1", 5)).status, "01");  // not in time-sync mode
  EXPECT_EQ(reply(responder.respond("TM0", 5)).status, "00");
  const scip::Reply stamp = reply(responder.respond("TM1", 0xABCDEF));
  ASSERT_EQ(stamp.data.size(), 1u);
  EXPECT_EQ(scip::decode(stamp.data[0]), 0xABCDEFu);
  EXPECT_EQ(reply(responder.respond("TM2", 5)).status, "00");
  ScipResponder old_firmware(model_, ramp_, {false, false, false});
  EXPECT_EQ(reply(old_firmware.respond("TM0", 5)).status, "0E");
}

TEST(HokuyoRangePatternTest, PatternsFitTheModelAndUnknownNamesThrow) {
  const HokuyoModel model = HokuyoModel::ubg05ln();
  for (const char* name : {"ramp", "room", "constant"}) {
    EXPECT_EQ(hokuyoRangePattern(name, model)(3).size(), 513u) << name;
  }
  const auto room = hokuyoRangePattern("room", model)(0);
  EXPECT_EQ(room[256], 1500u);  // straight ahead: the wall 1.5 m away
  EXPECT_THROW(hokuyoRangePattern("spiral", model), std::invalid_argument);
}

}  // namespace
}  // namespace mrslam::drivers
