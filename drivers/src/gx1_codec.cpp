#include "mrslam/drivers/gx1_codec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mrslam::drivers::gx1 {

namespace {

constexpr double kTicksPerTurn = 65536.0;    // Euler: 360° per 65536 counts
constexpr double kVectorScale = 32768000.0;  // vectors: value / (32768000 / gain)
constexpr double kQuaternionScale = 8192.0;  // quaternion: value / 8192
constexpr double kMinQuaternionNorm = 0.5;   // a smaller one is not an attitude

std::int16_t saturate(double value) {
  const double rounded = std::round(value);
  const double low = std::numeric_limits<std::int16_t>::min();
  const double high = std::numeric_limits<std::int16_t>::max();
  return static_cast<std::int16_t>(std::clamp(rounded, low, high));
}

std::uint16_t bits(std::int16_t word) {
  return static_cast<std::uint16_t>(word);
}

Eigen::Vector3d vectorAt(const Frame& frame, std::size_t first, double gain) {
  return {vectorFromWord(frame.signedWord(first), gain),
          vectorFromWord(frame.signedWord(first + 1), gain),
          vectorFromWord(frame.signedWord(first + 2), gain)};
}

void appendVector(std::vector<std::uint16_t>& words, const Eigen::Vector3d& value, double gain) {
  for (int axis = 0; axis < 3; ++axis) {
    words.push_back(bits(vectorToWord(value[axis], gain)));
  }
}

// ZYX angles of a rotation: R = Rz(yaw) · Ry(pitch) · Rx(roll).
void eulerFromQuaternion(const Eigen::Quaterniond& q, Reading& reading) {
  const Eigen::Matrix3d r = q.toRotationMatrix();
  reading.roll_rad = std::atan2(r(2, 1), r(2, 2));
  reading.pitch_rad = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  reading.yaw_rad = std::atan2(r(1, 0), r(0, 0));
}

Eigen::Quaterniond quaternionFromEuler(double roll, double pitch, double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
}

bool decodeQuaternionFrame(const Frame& frame, const Gains& gains, QuaternionConvention convention,
                           Reading& reading) {
  Eigen::Quaterniond q(
      quaternionFromWord(frame.signedWord(0)), quaternionFromWord(frame.signedWord(1)),
      quaternionFromWord(frame.signedWord(2)), quaternionFromWord(frame.signedWord(3)));
  if (q.norm() < kMinQuaternionNorm) {
    return false;
  }
  q.normalize();
  reading.q_earth_sensor = convention == QuaternionConvention::kSensorToEarth ? q : q.conjugate();
  reading.has_quaternion = true;
  eulerFromQuaternion(reading.q_earth_sensor, reading);
  reading.magnetic_gauss = vectorAt(frame, 4, gains.mag);
  reading.acceleration_g = vectorAt(frame, 7, gains.accel);
  reading.angular_rate_rad_s = vectorAt(frame, 10, gains.gyro);
  reading.has_vectors = true;
  return true;
}

}  // namespace

std::size_t frameSize(std::uint8_t header) {
  switch (header) {
    case kEulerCommand:
      return 11;
    case kEulerVectorsCommand:
      return 23;
    case kQuaternionVectorsCommand:
      return 31;
    case kEepromReadCommand:
    case kContinuousCommand:
      return 7;
    default:
      return 0;
  }
}

bool isOrientationCommand(std::uint8_t command) {
  return command == kEulerCommand || command == kEulerVectorsCommand ||
         command == kQuaternionVectorsCommand;
}

std::uint16_t checksum(const std::uint8_t* frame, std::size_t size) {
  std::uint32_t sum = frame[0];
  for (std::size_t i = 1; i + 2 < size; i += 2) {  // data words: bytes 1 .. size-3
    sum += static_cast<std::uint32_t>(frame[i] << 8 | frame[i + 1]);
  }
  return static_cast<std::uint16_t>(sum & 0xFFFFu);
}

std::optional<Frame> decodeFrame(const std::uint8_t* bytes, std::size_t size) {
  if (size < 5 || size != frameSize(bytes[0])) {
    return std::nullopt;
  }
  const std::uint16_t sent = static_cast<std::uint16_t>(bytes[size - 2] << 8 | bytes[size - 1]);
  if (sent != checksum(bytes, size)) {
    return std::nullopt;
  }
  Frame frame;
  frame.header = bytes[0];
  frame.word_count = (size - 3) / 2;
  for (std::size_t w = 0; w < frame.word_count; ++w) {
    frame.words[w] = static_cast<std::uint16_t>(bytes[1 + 2 * w] << 8 | bytes[2 + 2 * w]);
  }
  return frame;
}

std::vector<std::uint8_t> encodeFrame(std::uint8_t header,
                                      const std::vector<std::uint16_t>& words) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(3 + 2 * words.size());
  bytes.push_back(header);
  std::uint32_t sum = header;
  for (const std::uint16_t word : words) {
    bytes.push_back(static_cast<std::uint8_t>(word >> 8));
    bytes.push_back(static_cast<std::uint8_t>(word & 0xFFu));
    sum += word;
  }
  bytes.push_back(static_cast<std::uint8_t>((sum >> 8) & 0xFFu));
  bytes.push_back(static_cast<std::uint8_t>(sum & 0xFFu));
  return bytes;
}

std::optional<Reading> decodeReading(const Frame& frame, const Gains& gains,
                                     QuaternionConvention convention) {
  if (!isOrientationCommand(frame.header) || frame.word_count == 0) {
    return std::nullopt;
  }
  Reading reading;
  reading.command = frame.header;
  reading.ticks = frame.ticks();
  if (frame.header == kQuaternionVectorsCommand) {
    if (!decodeQuaternionFrame(frame, gains, convention, reading)) {
      return std::nullopt;
    }
    return reading;
  }
  reading.roll_rad = angleFromWord(frame.signedWord(0));
  reading.pitch_rad = angleFromWord(frame.signedWord(1));
  reading.yaw_rad = angleFromWord(frame.signedWord(2));
  if (frame.header == kEulerVectorsCommand) {
    reading.acceleration_g = vectorAt(frame, 3, gains.accel);
    reading.angular_rate_rad_s = vectorAt(frame, 6, gains.gyro);
    reading.has_vectors = true;
  }
  return reading;
}

std::optional<std::uint16_t> decodeEepromValue(const Frame& frame) {
  if (frame.header != kEepromReadCommand || frame.word_count != 2) {
    return std::nullopt;
  }
  return frame.words[0];
}

std::optional<std::uint8_t> decodeContinuousConfirmation(const Frame& frame) {
  if (frame.header != kContinuousCommand || frame.word_count != 2 || frame.words[0] > 0xFF) {
    return std::nullopt;
  }
  return static_cast<std::uint8_t>(frame.words[0]);
}

double angleFromWord(std::int16_t word) {
  return static_cast<double>(word) * 2.0 * M_PI / kTicksPerTurn;
}

std::int16_t angleToWord(double angle_rad) {
  // Angles are periodic: 180° and -180° are the same word (-32768).
  const long long counts = std::llround(angle_rad * kTicksPerTurn / (2.0 * M_PI));
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(counts & 0xFFFF));
}

double vectorFromWord(std::int16_t word, double gain) {
  return static_cast<double>(word) * gain / kVectorScale;
}

std::int16_t vectorToWord(double value, double gain) {
  return saturate(value * kVectorScale / gain);
}

double quaternionFromWord(std::int16_t word) {
  return static_cast<double>(word) / kQuaternionScale;
}

std::int16_t quaternionToWord(double value) {
  return saturate(value * kQuaternionScale);
}

std::vector<std::uint8_t> encodeReading(std::uint8_t command, const DeviceState& state,
                                        const Gains& gains, std::uint16_t ticks) {
  std::vector<std::uint16_t> words;
  if (command == kQuaternionVectorsCommand) {
    const Eigen::Quaterniond q =
        quaternionFromEuler(state.roll_rad, state.pitch_rad, state.yaw_rad);
    for (const double value : {q.w(), q.x(), q.y(), q.z()}) {
      words.push_back(bits(quaternionToWord(value)));
    }
    appendVector(words, state.magnetic_gauss, gains.mag);
  } else if (command == kEulerCommand || command == kEulerVectorsCommand) {
    for (const double angle : {state.roll_rad, state.pitch_rad, state.yaw_rad}) {
      words.push_back(bits(angleToWord(angle)));
    }
  } else {
    return {};
  }
  if (command != kEulerCommand) {
    appendVector(words, state.acceleration_g, gains.accel);
    appendVector(words, state.angular_rate_rad_s, gains.gyro);
  }
  words.push_back(ticks);
  return encodeFrame(command, words);
}

std::array<std::uint8_t, 3> eepromReadRequest(std::uint16_t address) {
  return {kEepromReadCommand, static_cast<std::uint8_t>(address >> 8),
          static_cast<std::uint8_t>(address & 0xFFu)};
}

std::array<std::uint8_t, 3> continuousRequest(std::uint8_t command) {
  return {kContinuousCommand, 0x00, command};
}

}  // namespace mrslam::drivers::gx1
