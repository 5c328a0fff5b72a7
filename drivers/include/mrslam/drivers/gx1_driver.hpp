#pragma once
// MicroStrain 3DM-GX1 driver over a serial port, thread-free: the caller calls poll(timeout).
//
// Start-up (again after every reconnection):
//   1. open the port (38400 8N1 raw), send 0x10 0x00 0x00 in case the device still streams;
//   2. read the gyro, accel and mag gains from EEPROM 130, 230, 232 (0x28 addr_hi addr_lo);
//   3. continuous mode: send 0x10 0x00 <cmd> and wait for the confirmation or a first frame.
// Then each poll() sends <cmd> (polled mode) or reads the stream (continuous mode) and turns
// frames into ImuSamples; close() or the destructor send 0x10 0x00 0x00 in continuous mode.
// A hang-up or EIO, or `max_silent_timeouts` read time-outs in a row without a single byte, lose
// the device: the driver closes it and retries the whole start-up with exponential back-off.
// Corrupt frames are dropped and counted (a polled request is sent again after the time-out).
// Stamps: the host clock aligned with the device's unwrapped timer (TickClock below).
//
// Axes: the device reports a compass-like frame (x forward, y right, z down, heading clockwise);
// ImuSample is z up, counter-clockwise (REP 103). With `device_z_down` (*unsure*, default) the
// driver turns the frame by π about x: roll stays, pitch and yaw change sign, and y and z of
// acceleration and rate change sign (a level device at rest then reads +1 g on z).
// 0x0E carries no vectors: its samples have NaN (unknown) acceleration and rate, never zeros.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "mrslam/common/error_counter.hpp"
#include "mrslam/common/samples.hpp"
#include "mrslam/common/stamp.hpp"
#include "mrslam/drivers/gx1_codec.hpp"
#include "mrslam/drivers/serial_port.hpp"

namespace mrslam {
class Config;
}

namespace mrslam::drivers {

/// Host time stamps for the device's 16-bit timer ticks. Method:
///   1. unwrap: Δ = (ticks − previous) mod 2^16, plus the whole wraps the host clock says passed
///      (frames more than one wrap apart: 65536 ticks ≈ 7 min at 6.5536 ms);
///   2. device time t_dev = unwrapped ticks × tick period; candidate offset c = t_host − t_dev,
///      t_host being when the frame was read (always after the device sampled it);
///   3. offset = the least c seen (the least delayed frame shows the true offset best), allowed
///      to rise by `drift_allowance` × Δt_dev so clock drift is followed; when 8 frames in a row
///      exceed it by more than `max_error_s` (wrong tick period, device reset) it restarts at
///      the least c of them (a resync; one late burst of frames does not count);
///   4. stamp = t_dev + offset, never later than t_host, and always after the previous stamp.
class TickClock {
 public:
  struct Settings {
    double tick_period_s = 6.5536e-3;  ///< device timer period (*unsure*: 6.5536 or 10 ms)
    double drift_allowance = 1e-3;     ///< how fast the offset may rise (s per s of device time)
    double max_error_s = 0.05;         ///< lag behind the host that, persisting, resyncs
  };

  explicit TickClock(Settings settings) : settings_(settings) {}

  /// The host stamp of a frame with `ticks` read at `host`.
  Stamp stamp(std::uint16_t ticks, Stamp host);
  /// Ticks since the first frame plus the first frame's ticks (no wraps).
  std::uint64_t unwrappedTicks() const { return unwrapped_; }
  std::uint64_t resyncs() const { return resyncs_; }
  /// Forgets the device (a new connection: the counter may have restarted).
  void reset();

 private:
  std::uint64_t unwrap(std::uint16_t ticks, Stamp host) const;

  Settings settings_;
  bool started_ = false;
  std::uint16_t last_ticks_ = 0;
  std::uint64_t first_unwrapped_ = 0;
  std::uint64_t unwrapped_ = 0;
  Stamp last_host_;
  std::int64_t offset_ns_ = 0;
  int lagging_frames_ = 0;           ///< frames in a row lagging more than max_error_s
  std::int64_t lagging_min_ns_ = 0;  ///< the least candidate offset among them
  Stamp last_stamp_;
  std::uint64_t resyncs_ = 0;
};

enum class Gx1Mode { kPolled, kContinuous };

struct Gx1Settings {
  std::string device;                                ///< e.g. /dev/ttyS0 or a udev link
  int baud = 38400;                                  ///< the device's default rate
  Gx1Mode mode = Gx1Mode::kPolled;                   ///< ask for every reading, or let it stream
  std::uint8_t command = gx1::kEulerVectorsCommand;  ///< 0x0E, 0x31 or 0x0C
  double tick_period_s = 6.5536e-3;             ///< *unsure* (6.5536 ms or 10 ms in the sources)
  std::chrono::milliseconds read_timeout{200};  ///< a reply or frame must come within this
  int max_silent_timeouts = 3;  ///< time-outs in a row without any byte that lose the device
  std::chrono::milliseconds reconnect_initial{100};  ///< first delay before reconnecting
  std::chrono::milliseconds reconnect_max{5000};     ///< longest delay before reconnecting
  bool device_z_down = true;  ///< *unsure*: device axes z down, heading clockwise (see above)
  gx1::QuaternionConvention quaternion = gx1::QuaternionConvention::kSensorToEarth;  ///< *unsure*
  /// *Unsure* confirmation layout: when true, start-up of continuous mode waits for the 0x10
  /// reply (or a first data frame); when false it does not look for 0x10 frames at all.
  bool expect_continuous_confirmation = true;
  double clock_drift_allowance = 1e-3;  ///< see TickClock
  double max_clock_error_s = 0.05;      ///< see TickClock

  /// Reads a config section (keys as the fields, durations in seconds: read_timeout_s, ...).
  static Gx1Settings fromConfig(const Config& section);
  /// Empty when the settings are usable, else what is wrong.
  std::string check() const;
};

enum class Gx1State {
  kDisconnected,  ///< not started, or lost: start-up is retried with back-off
  kRunning,       ///< started up; samples flow
  kClosed,        ///< close() was called
};

struct Gx1Health {
  Gx1State state = Gx1State::kDisconnected;
  std::uint64_t samples = 0;             ///< samples handed out
  std::uint64_t startups = 0;            ///< successful start-ups
  std::uint64_t failed_startups = 0;     ///< start-ups that failed (no device, no answer, garbage)
  std::uint64_t disconnects = 0;         ///< running device lost (hang-up, EIO, silence)
  std::uint64_t timeouts = 0;            ///< replies or frames that did not come in time
  std::uint64_t implausible_frames = 0;  ///< good checksum, impossible values (zero quaternion)
  std::uint64_t clock_resyncs = 0;       ///< TickClock restarts (wrong tick period?)
  gx1::ParserCounters parser;            ///< over all connections
  std::string last_error;  ///< the latest problem: why a start-up failed or the device was lost
  std::string last_loss;   ///< why the running device was last lost (empty: never)
};

class Gx1Driver {
 public:
  /// Throws std::invalid_argument when the settings are not usable. Opens nothing yet.
  explicit Gx1Driver(Gx1Settings settings);
  /// Stops continuous mode and closes the port.
  ~Gx1Driver();
  Gx1Driver(const Gx1Driver&) = delete;
  Gx1Driver& operator=(const Gx1Driver&) = delete;

  /// Works for up to `timeout` (a start-up may take a few read time-outs longer): connects or
  /// reconnects when due, asks for and reads frames. Returns the first complete sample. In
  /// continuous mode call it at least as often as frames come: unread frames queue in the port
  /// (their stamps stay right, but they get old).
  std::optional<ImuSample> poll(std::chrono::milliseconds timeout);
  /// Stops continuous mode (0x10 0x00 0x00) and closes the port; poll() does nothing after.
  void close();

  Gx1State state() const { return health_.state; }
  Gx1Health health() const;
  /// The gains read at the last start-up.
  const gx1::Gains& gains() const { return gains_; }
  /// The tick count of the last sample, unwrapped, and as the device sent it.
  std::uint64_t lastUnwrappedTicks() const { return clock_.unwrappedTicks(); }
  std::uint16_t lastRawTicks() const { return last_raw_ticks_; }
  const Gx1Settings& settings() const { return settings_; }

 private:
  using SteadyTime = std::chrono::steady_clock::time_point;

  bool connectWhenDue(SteadyTime deadline);
  bool startUp();
  std::optional<std::uint16_t> readGain(std::uint16_t address, const char* name);
  bool startContinuous();
  template <class Wanted>
  std::optional<gx1::Frame> awaitFrame(Wanted wanted, const std::string& what);
  std::optional<ImuSample> readSample(SteadyTime deadline);
  std::optional<ImuSample> takeSample();
  bool readBytes(std::chrono::milliseconds wait);
  bool send(const std::uint8_t* bytes, std::size_t size);
  void onSilence();
  void reportProblems();
  void lose(const std::string& reason);
  ImuSample toSample(const gx1::Reading& reading, Stamp host) const;

  const Gx1Settings settings_;
  ErrorCounter problems_;         ///< rate-limited log of dropped data
  gx1::ParserCounters reported_;  ///< parser counts already logged
  SerialPort port_;
  Backoff backoff_;
  SteadyTime next_attempt_{};
  gx1::StreamParser parser_;
  TickClock clock_;
  gx1::Gains gains_;
  Gx1Health health_;
  bool request_pending_ = false;
  SteadyTime reply_due_{};
  int silent_timeouts_ = 0;             ///< time-outs in a row without a single byte
  std::size_t received_in_window_ = 0;  ///< bytes since the last frame or time-out
  Stamp last_read_host_;
  std::uint16_t last_raw_ticks_ = 0;
};

}  // namespace mrslam::drivers
