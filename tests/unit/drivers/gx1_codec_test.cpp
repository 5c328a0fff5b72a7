// The 3DM-GX1 codec against frames built by hand from the documented layout (PROTOCOLS.md).

#include "mrslam/drivers/gx1_codec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace mrslam::drivers::gx1 {
namespace {

using Bytes = std::vector<std::uint8_t>;

constexpr double kTolerance = 1e-12;
const Gains kTypicalGains{10000.0, 8500.0, 2000.0};

double degrees(double radians) {
  return radians * 180.0 / M_PI;
}

Frame decoded(const Bytes& bytes) {
  const std::optional<Frame> frame = decodeFrame(bytes.data(), bytes.size());
  EXPECT_TRUE(frame.has_value());
  return frame.value_or(Frame{});
}

// 0x0E: roll 1820, pitch -1000, yaw -32768, ticks 0x1234;
// checksum 0x0E + 0x071C + 0xFC18 + 0x8000 + 0x1234 = 0x19576 → 0x9576.
const Bytes kEulerFrame = {0x0E, 0x07, 0x1C, 0xFC, 0x18, 0x80, 0x00, 0x12, 0x34, 0x95, 0x76};

// 0x31: roll 256, pitch -256, yaw 16384; accel 3855, 0, -3855; rate 3277, -3277, 0;
// ticks 0xFFFE; checksum 0x402F.
const Bytes kEulerVectorsFrame = {0x31, 0x01, 0x00, 0xFF, 0x00, 0x40, 0x00, 0x0F,
                                  0x0F, 0x00, 0x00, 0xF0, 0xF1, 0x0C, 0xCD, 0xF3,
                                  0x33, 0x00, 0x00, 0xFF, 0xFE, 0x40, 0x2F};

// 0x0C: q = (5793, 0, 0, 5793)/8192 (90° about z); mag 16384, 0, -8192; accel 0, 0, -3855;
// rate 0, 0, 1638; ticks 7; checksum 0x44AC.
const Bytes kQuaternionFrame = {0x0C, 0x16, 0xA1, 0x00, 0x00, 0x00, 0x00, 0x16, 0xA1, 0x40, 0x00,
                                0x00, 0x00, 0xE0, 0x00, 0x00, 0x00, 0x00, 0x00, 0xF0, 0xF1, 0x00,
                                0x00, 0x00, 0x00, 0x06, 0x66, 0x00, 0x07, 0x44, 0xAC};

TEST(Gx1CodecTest, FrameSizesFollowTheTable) {
  EXPECT_EQ(frameSize(kEulerCommand), 11u);
  EXPECT_EQ(frameSize(kEulerVectorsCommand), 23u);
  EXPECT_EQ(frameSize(kQuaternionVectorsCommand), 31u);
  EXPECT_EQ(frameSize(kEepromReadCommand), 7u);
  EXPECT_EQ(frameSize(kContinuousCommand), 7u);
  EXPECT_EQ(frameSize(0x00), 0u);
  EXPECT_EQ(frameSize(0x01), 0u);  // raw ADC: not read by this codec
}

TEST(Gx1CodecTest, ChecksumIsHeaderPlusBigEndianWords) {
  EXPECT_EQ(checksum(kEulerFrame.data(), kEulerFrame.size()), 0x9576);
  EXPECT_EQ(checksum(kEulerVectorsFrame.data(), kEulerVectorsFrame.size()), 0x402F);
  EXPECT_EQ(checksum(kQuaternionFrame.data(), kQuaternionFrame.size()), 0x44AC);
}

TEST(Gx1CodecTest, DecodesStabilisedEulerAsSignedAngles) {
  const Frame frame = decoded(kEulerFrame);
  ASSERT_EQ(frame.word_count, 4u);
  EXPECT_EQ(frame.ticks(), 0x1234);
  const auto reading = decodeReading(frame, kTypicalGains);
  ASSERT_TRUE(reading);
  EXPECT_NEAR(degrees(reading->roll_rad), 1820.0 * 360.0 / 65536.0, kTolerance);
  EXPECT_NEAR(degrees(reading->pitch_rad), -1000.0 * 360.0 / 65536.0, kTolerance);
  EXPECT_NEAR(degrees(reading->yaw_rad), -180.0, kTolerance);
  EXPECT_FALSE(reading->has_vectors);
  EXPECT_FALSE(reading->has_quaternion);
}

TEST(Gx1CodecTest, DecodesEulerWithVectorsScaledByTheGains) {
  const auto reading = decodeReading(decoded(kEulerVectorsFrame), kTypicalGains);
  ASSERT_TRUE(reading);
  EXPECT_EQ(reading->ticks, 0xFFFE);
  EXPECT_NEAR(degrees(reading->roll_rad), 256.0 * 360.0 / 65536.0, kTolerance);
  EXPECT_NEAR(degrees(reading->pitch_rad), -256.0 * 360.0 / 65536.0, kTolerance);
  EXPECT_NEAR(degrees(reading->yaw_rad), 90.0, kTolerance);
  ASSERT_TRUE(reading->has_vectors);
  // value / (32768000 / gain)
  EXPECT_NEAR(reading->acceleration_g.x(), 3855.0 / (32768000.0 / 8500.0), kTolerance);
  EXPECT_NEAR(reading->acceleration_g.y(), 0.0, kTolerance);
  EXPECT_NEAR(reading->acceleration_g.z(), -3855.0 / (32768000.0 / 8500.0), kTolerance);
  EXPECT_NEAR(reading->angular_rate_rad_s.x(), 3277.0 / 3276.8, kTolerance);
  EXPECT_NEAR(reading->angular_rate_rad_s.y(), -3277.0 / 3276.8, kTolerance);
  EXPECT_NEAR(reading->angular_rate_rad_s.z(), 0.0, kTolerance);
}

TEST(Gx1CodecTest, DecodesQuaternionAndVectors) {
  const auto reading = decodeReading(decoded(kQuaternionFrame), kTypicalGains);
  ASSERT_TRUE(reading);
  EXPECT_EQ(reading->ticks, 7);
  ASSERT_TRUE(reading->has_quaternion);
  EXPECT_NEAR(reading->q_earth_sensor.w(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(reading->q_earth_sensor.z(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(degrees(reading->yaw_rad), 90.0, 1e-9);
  EXPECT_NEAR(reading->roll_rad, 0.0, 1e-12);
  EXPECT_NEAR(reading->pitch_rad, 0.0, 1e-12);
  EXPECT_NEAR(reading->magnetic_gauss.x(), 1.0, kTolerance);  // 16384 / (32768000 / 2000)
  EXPECT_NEAR(reading->magnetic_gauss.z(), -0.5, kTolerance);
  EXPECT_NEAR(reading->acceleration_g.z(), -3855.0 * 8500.0 / 32768000.0, kTolerance);
  EXPECT_NEAR(reading->angular_rate_rad_s.z(), 1638.0 * 10000.0 / 32768000.0, kTolerance);
  // The other convention (unsure) reads the inverse rotation.
  const auto inverse =
      decodeReading(decoded(kQuaternionFrame), kTypicalGains, QuaternionConvention::kEarthToSensor);
  ASSERT_TRUE(inverse);
  EXPECT_NEAR(degrees(inverse->yaw_rad), -90.0, 1e-9);
}

TEST(Gx1CodecTest, RejectsAZeroQuaternion) {
  const Bytes frame = encodeFrame(kQuaternionVectorsCommand, std::vector<std::uint16_t>(14, 0));
  EXPECT_FALSE(decodeReading(decoded(frame), kTypicalGains));
}

TEST(Gx1CodecTest, DecodesEepromReadAndContinuousConfirmation) {
  // 0x28, value 10000, ticks 1, checksum 0x28 + 0x2710 + 0x0001 = 0x2739
  const Bytes eeprom = {0x28, 0x27, 0x10, 0x00, 0x01, 0x27, 0x39};
  EXPECT_EQ(decodeEepromValue(decoded(eeprom)), 10000);
  // Assumed layout: 0x10, word 0x0031, ticks 0x0102, checksum 0x10 + 0x31 + 0x0102 = 0x0143
  const Bytes confirmation = {0x10, 0x00, 0x31, 0x01, 0x02, 0x01, 0x43};
  EXPECT_EQ(decodeContinuousConfirmation(decoded(confirmation)), 0x31);
  EXPECT_FALSE(decodeEepromValue(decoded(confirmation)));
  EXPECT_FALSE(decodeReading(decoded(eeprom), kTypicalGains));
}

TEST(Gx1CodecTest, RejectsBadChecksumsAndWrongSizes) {
  Bytes corrupt = kEulerFrame;
  corrupt[3] ^= 0x01;
  EXPECT_FALSE(decodeFrame(corrupt.data(), corrupt.size()));
  EXPECT_FALSE(decodeFrame(kEulerFrame.data(), kEulerFrame.size() - 1));
  const Bytes unknown = {0x01, 0x00, 0x00, 0x00, 0x01};
  EXPECT_FALSE(decodeFrame(unknown.data(), unknown.size()));
}

TEST(Gx1CodecTest, EncodesTheBytesOfTheHandBuiltFrames) {
  EXPECT_EQ(encodeFrame(kEulerCommand, {1820, 0xFC18, 0x8000, 0x1234}), kEulerFrame);
  DeviceState state;
  state.roll_rad = angleFromWord(256);
  state.pitch_rad = angleFromWord(-256);
  state.yaw_rad = M_PI / 2.0;
  state.acceleration_g = {vectorFromWord(3855, 8500.0), 0.0, vectorFromWord(-3855, 8500.0)};
  state.angular_rate_rad_s = {vectorFromWord(3277, 10000.0), vectorFromWord(-3277, 10000.0), 0.0};
  EXPECT_EQ(encodeReading(kEulerVectorsCommand, state, kTypicalGains, 0xFFFE), kEulerVectorsFrame);
}

TEST(Gx1CodecTest, ScalingRoundsAndSaturates) {
  EXPECT_EQ(angleToWord(M_PI), -32768);  // 180° and -180° are one word
  EXPECT_EQ(angleToWord(-M_PI / 2.0), -16384);
  EXPECT_EQ(vectorToWord(100.0, 8500.0), 32767);  // beyond ±8.5 g saturates
  EXPECT_EQ(vectorToWord(-100.0, 8500.0), -32768);
  EXPECT_EQ(quaternionToWord(1.0), 8192);
  EXPECT_EQ(quaternionToWord(-0.5), -4096);
}

TEST(Gx1CodecTest, QuaternionOfAnAttitudeGivesItsEulerAnglesBack) {
  DeviceState state;
  state.roll_rad = 0.3;
  state.pitch_rad = -0.2;
  state.yaw_rad = 2.5;
  const Bytes frame = encodeReading(kQuaternionVectorsCommand, state, kTypicalGains, 0);
  const auto reading = decodeReading(decoded(frame), kTypicalGains);
  ASSERT_TRUE(reading);
  // The quaternion has 1/8192 resolution: about 2e-4 rad.
  EXPECT_NEAR(reading->roll_rad, 0.3, 5e-4);
  EXPECT_NEAR(reading->pitch_rad, -0.2, 5e-4);
  EXPECT_NEAR(reading->yaw_rad, 2.5, 5e-4);
}

TEST(Gx1CodecTest, RequestsAreCommandAndBigEndianAddress) {
  EXPECT_EQ(eepromReadRequest(130), (std::array<std::uint8_t, 3>{0x28, 0x00, 0x82}));
  EXPECT_EQ(eepromReadRequest(232), (std::array<std::uint8_t, 3>{0x28, 0x00, 0xE8}));
  EXPECT_EQ(continuousRequest(0x31), (std::array<std::uint8_t, 3>{0x10, 0x00, 0x31}));
  EXPECT_EQ(continuousRequest(0), (std::array<std::uint8_t, 3>{0x10, 0x00, 0x00}));
}

}  // namespace
}  // namespace mrslam::drivers::gx1
