#pragma once
// MicroStrain 3DM-GX1 wire format (docs: PROTOCOLS.md): pure encoding and decoding, no I/O.
//
// Every reply is the command byte echoed as header, big-endian 16-bit words, then a 16-bit
// checksum = (header + Σ data words) & 0xFFFF. The last data word is the 16-bit timer tick.
//   0x0E  stabilised Euler        11 bytes: roll, pitch, yaw, ticks, checksum
//   0x31  Euler + accel + rate    23 bytes: roll, pitch, yaw, accel×3, rate×3, ticks, checksum
//   0x0C  quaternion + vectors    31 bytes: q0..q3, mag×3, accel×3, rate×3, ticks, checksum
//   0x28  EEPROM read              7 bytes: value, ticks, checksum
//   0x10  continuous-mode confirmation, 7 bytes. *Unsure* layout (only byte 2 = <cmd> is known);
//         assumed: header 0x10, word 0x00 <cmd>, ticks, checksum by the usual rule.
// Scaling: Euler int16 × 360/65536 °; vectors int16 / (32768000 / gain) with the gains of EEPROM
// addresses 130 (gyro → rad/s), 230 (accel → g), 232 (mag → Gauss); quaternion int16 / 8192.
// Values are in the device's own axes; the driver maps them to the robot's convention.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace mrslam::drivers::gx1 {

constexpr std::uint8_t kEulerCommand = 0x0E;              ///< stabilised Euler angles
constexpr std::uint8_t kEulerVectorsCommand = 0x31;       ///< Euler + accel + angular rate
constexpr std::uint8_t kQuaternionVectorsCommand = 0x0C;  ///< quaternion + mag + accel + rate
constexpr std::uint8_t kEepromReadCommand = 0x28;         ///< 0x28 addr_hi addr_lo
constexpr std::uint8_t kContinuousCommand = 0x10;         ///< 0x10 0x00 <cmd>; <cmd> 0 stops

constexpr std::uint16_t kGyroGainAddress = 130;
constexpr std::uint16_t kAccelGainAddress = 230;
constexpr std::uint16_t kMagGainAddress = 232;

constexpr std::size_t kMaxFrameSize = 31;
constexpr std::size_t kMaxDataWords = (kMaxFrameSize - 3) / 2;  ///< without the checksum

/// Size of the reply that starts with `header`; 0 for a header this codec does not read.
std::size_t frameSize(std::uint8_t header);
/// True for the orientation commands 0x0E, 0x31 and 0x0C.
bool isOrientationCommand(std::uint8_t command);

/// One reply with a verified checksum: its header and data words (the last is the tick count).
struct Frame {
  std::uint8_t header = 0;
  std::array<std::uint16_t, kMaxDataWords> words{};
  std::size_t word_count = 0;

  std::uint16_t ticks() const { return words[word_count - 1]; }
  std::int16_t signedWord(std::size_t i) const { return static_cast<std::int16_t>(words[i]); }
};

/// (header + Σ big-endian words) & 0xFFFF over all bytes of `frame` but the last two.
std::uint16_t checksum(const std::uint8_t* frame, std::size_t size);
/// A frame of exactly frameSize(bytes[0]) bytes; nothing when its checksum is wrong.
std::optional<Frame> decodeFrame(const std::uint8_t* bytes, std::size_t size);
/// Header, the words big-endian, and their checksum.
std::vector<std::uint8_t> encodeFrame(std::uint8_t header, const std::vector<std::uint16_t>& words);

/// The raw EEPROM gains that scale the vectors (value / (32768000 / gain)).
struct Gains {
  double gyro = 10000.0;  ///< EEPROM 130: angular rate → rad/s
  double accel = 8500.0;  ///< EEPROM 230: acceleration → g
  double mag = 2000.0;    ///< EEPROM 232: magnetic field → Gauss
};

/// What the quaternion of 0x0C describes. *Unsure*: the sources do not say; kSensorToEarth
/// is assumed (its ZYX Euler angles are the 0x0E angles); kEarthToSensor takes the inverse.
enum class QuaternionConvention { kSensorToEarth, kEarthToSensor };

/// An orientation reply (0x0E, 0x31, 0x0C) in the device's axes and units.
struct Reading {
  std::uint8_t command = 0;
  std::uint16_t ticks = 0;
  double roll_rad = 0.0;  ///< ZYX Euler angles (0x0C: computed from the quaternion)
  double pitch_rad = 0.0;
  double yaw_rad = 0.0;
  bool has_vectors = false;  ///< 0x31 and 0x0C
  Eigen::Vector3d acceleration_g = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_rate_rad_s = Eigen::Vector3d::Zero();
  bool has_quaternion = false;  ///< 0x0C
  Eigen::Quaterniond q_earth_sensor = Eigen::Quaterniond::Identity();
  Eigen::Vector3d magnetic_gauss = Eigen::Vector3d::Zero();
};

std::optional<Reading> decodeReading(
    const Frame& frame, const Gains& gains,
    QuaternionConvention convention = QuaternionConvention::kSensorToEarth);
/// The value of an EEPROM read reply (0x28).
std::optional<std::uint16_t> decodeEepromValue(const Frame& frame);
/// The command a continuous-mode confirmation (0x10) echoes (0: streaming stopped).
std::optional<std::uint8_t> decodeContinuousConfirmation(const Frame& frame);

// Scaling both ways (round to nearest, saturating at the int16 limits).
double angleFromWord(std::int16_t word);
std::int16_t angleToWord(double angle_rad);
double vectorFromWord(std::int16_t word, double gain);
std::int16_t vectorToWord(double value, double gain);
double quaternionFromWord(std::int16_t word);
std::int16_t quaternionToWord(double value);

/// What a device measures, in its own axes: the emulator's input.
struct DeviceState {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double yaw_rad = 0.0;
  Eigen::Vector3d acceleration_g = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_rate_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d magnetic_gauss = Eigen::Vector3d::Zero();
};

/// The reply a device sends to `command` (0x0E, 0x31, 0x0C); empty for other commands.
std::vector<std::uint8_t> encodeReading(std::uint8_t command, const DeviceState& state,
                                        const Gains& gains, std::uint16_t ticks);

/// The bytes of requests.
std::array<std::uint8_t, 3> eepromReadRequest(std::uint16_t address);
std::array<std::uint8_t, 3> continuousRequest(std::uint8_t command);  ///< 0 stops streaming

/// Problems a stream parser counts.
struct ParserCounters {
  std::uint64_t frames = 0;            ///< frames with a good checksum handed out
  std::uint64_t garbage_bytes = 0;     ///< bytes passed over that cannot start a frame
  std::uint64_t bad_checksums = 0;     ///< candidate frames with a wrong checksum
  std::uint64_t truncated_frames = 0;  ///< partial frames dropped by discardPartial()
};

/// Finds replies in a byte stream. A byte that is not an accepted header is garbage; a candidate
/// whose checksum fails is dropped one byte at a time (the next header may be inside it), so the
/// parser resynchronises on the next good frame. It never returns a frame with a bad checksum.
class StreamParser {
 public:
  /// Looks for every header the codec knows.
  StreamParser();
  /// Looks only for `headers` (others count as garbage).
  explicit StreamParser(const std::vector<std::uint8_t>& headers);

  void accept(const std::vector<std::uint8_t>& headers);
  void push(const std::uint8_t* data, std::size_t size);
  /// The next good frame, or nothing until more bytes arrive.
  std::optional<Frame> next();
  /// Drops a partial frame left when the device fell silent (counted as truncated).
  void discardPartial();
  /// Drops every buffered byte without counting (a new connection).
  void clear();
  std::size_t pending() const { return buffer_.size() - head_; }
  const ParserCounters& counters() const { return counters_; }

 private:
  void compact();

  std::array<bool, 256> accepted_{};
  std::vector<std::uint8_t> buffer_;
  std::size_t head_ = 0;
  ParserCounters counters_;
};

}  // namespace mrslam::drivers::gx1
