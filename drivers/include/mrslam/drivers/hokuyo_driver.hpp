#pragma once
// Hokuyo laser ranger driver (SCIP 2.0: URG-04LX, UBG-04LX-F01, UBG-05LN class), thread-free:
// the caller calls poll() in its own loop and gets the next scan or nothing.
//
// Start-up (connect()):
//  1. open the device; probe each baud rate with QT; a reply that is not a SCIP 2.0 "00"
//     (SCIP 1.1's "E", garbage, nothing) → send "SCIP2.0" and QT again;
//  2. VV (identity), PP (geometry: every angle and limit comes from it), II (state, optional);
//  3. TM time sync (optional: firmware without TM is fine), see SensorClock;
//  4. BM (laser on; "already on" is fine). poll() then starts MD (continuous scans).
// Each MD scan reply is verified (echo, status, every line's sum, the value count) before it
// becomes a LaserScan; anything else is dropped and counted by kind. The device is lost on a
// hang-up / EIO, when no reply came for `stall_scan_periods` scan periods, or when only bad
// replies came for 10 times that; poll() then reopens it with a doubling back-off and redoes
// the start-up.
// Stamps: the host time (device_clock::hostNow: Unix-epoch ns, never going back) of the first beam,
// from the sensor's 24-bit ms counter aligned to the host clock as SensorClock describes; they
// always increase.

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mrslam/common/config.hpp"
#include "mrslam/common/error_counter.hpp"
#include "mrslam/common/result.hpp"
#include "mrslam/common/samples.hpp"
#include "mrslam/drivers/scip_geometry.hpp"
#include "mrslam/drivers/scip_protocol.hpp"
#include "mrslam/drivers/sensor_clock.hpp"
#include "mrslam/drivers/serial_port.hpp"

namespace mrslam::drivers {

struct HokuyoSettings {
  std::string device;                                  ///< e.g. /dev/ttyACM0 or a udev link
  int baud = 115200;                                   ///< rate tried first (no effect on USB)
  std::vector<int> probe_bauds{19200, 38400, 115200};  ///< then these, in order
  int start_step = -1;                                 ///< first step measured; -1: AMIN from PP
  int end_step = -1;                                   ///< last step measured; -1: AMAX from PP
  int cluster = 1;     ///< adjacent steps merged into one beam (1…99)
  int skip_scans = 0;  ///< MD interval: scans skipped between two sent (0…9)
  std::chrono::milliseconds read_timeout{1000};  ///< longest wait for a reply to a command
  int stall_scan_periods = 5;  ///< no reply for this many scan periods: device lost
  std::chrono::milliseconds reconnect_backoff_min{100};   ///< first delay before reopening
  std::chrono::milliseconds reconnect_backoff_max{5000};  ///< the delay doubles up to this
  int time_sync_round_trips = 5;  ///< TM round trips at start-up (0: no TM; scans only)
  /// What a raw range of 0 means (*unsure*, firmware dependent): kInvalid is the safe default.
  scip::ZeroRange zero_range = scip::ZeroRange::kInvalid;
  bool reset_on_stop = false;  ///< RS after QT when stopping
};

/// Reads HokuyoSettings from a config section (keys as the fields; timeouts in seconds:
/// read_timeout_s, reconnect_backoff_min_s, reconnect_backoff_max_s; zero_range: invalid |
/// no_return). Throws ConfigError.
HokuyoSettings loadHokuyoSettings(const Config& section);

/// What the device said about itself at start-up.
struct HokuyoIdentity {
  scip::KeyValues version;     ///< VV: VEND, PROD, FIRM, PROT, SERI
  scip::KeyValues parameters;  ///< PP: MODL, DMIN, DMAX, ARES, AMIN, AMAX, AFRT, SCAN
  scip::KeyValues state;       ///< II: MODL, LASR, SCSP, MESM, SBPS, TIME, STAT (empty if none)
  scip::ScanGeometry geometry;
  int baud = 0;                       ///< the rate it answered at
  bool switched_from_scip11 = false;  ///< it answered SCIP 1.1 and was switched to 2.0
  bool time_synchronised = false;     ///< TM round trips set the clock offset
};

enum class HokuyoState {
  kDisconnected,  ///< not started, or stopped
  kConnected,     ///< start-up done (streaming or idle)
  kReconnecting,  ///< the device failed or was lost; poll() reopens it with back-off
};

/// Dropped replies and link events, by kind.
struct HokuyoCounters {
  std::uint64_t scans = 0;             ///< scans handed out
  std::uint64_t checksum = 0;          ///< replies with a bad sum char
  std::uint64_t truncated = 0;         ///< replies missing lines or values
  std::uint64_t status = 0;            ///< replies with an error status
  std::uint64_t garbage = 0;           ///< noise, bad echoes, unparseable replies
  std::uint64_t timeout = 0;           ///< no reply in time (start-up) or no scan in time (stall)
  std::uint64_t disconnect = 0;        ///< hang-ups / I/O errors of the device
  std::uint64_t reconnects = 0;        ///< successful start-ups after a failure or loss
  std::uint64_t connect_attempts = 0;  ///< start-ups tried (successful or not)
};

struct HokuyoHealth {
  HokuyoState state = HokuyoState::kDisconnected;
  HokuyoCounters counters;
  std::string last_error;  ///< the most recent problem (empty if none yet)
};

class HokuyoLink;

class HokuyoDriver {
 public:
  /// Checks the settings (throws std::invalid_argument); does not touch the device.
  explicit HokuyoDriver(HokuyoSettings settings);
  /// Stops the device (QT) if it is open.
  ~HokuyoDriver();
  HokuyoDriver(const HokuyoDriver&) = delete;
  HokuyoDriver& operator=(const HokuyoDriver&) = delete;

  /// Opens the device and runs the start-up. Blocks at most about
  /// (2 · bauds probed + 8 + time_sync_round_trips) · read_timeout.
  Result<HokuyoIdentity> connect();
  /// The next verified scan within `timeout`, or nothing. (Re)connects as needed; a start-up
  /// attempt may overrun `timeout` by its own bounded duration.
  std::optional<LaserScan> poll(std::chrono::milliseconds timeout);
  /// One scan by GD (MD streaming is stopped first), for device checks.
  Result<LaserScan> singleScan();
  /// QT (and RS when reset_on_stop), then closes the device. poll() would start it again.
  void stop();

  HokuyoHealth health() const;
  /// Set once a start-up succeeded.
  const std::optional<HokuyoIdentity>& identity() const { return identity_; }
  /// The MD/GD request in use (steps and cluster), once connected.
  const scip::ScanRequest& scanRequest() const { return request_; }

 private:
  enum class Mode { kClosed, kIdle, kStreaming };

  bool ensureStreaming(std::chrono::steady_clock::time_point deadline);
  bool attemptConnect();
  bool startStreaming();
  bool stopStreaming();
  std::optional<LaserScan> handleStreamBlock(std::string_view block);
  std::optional<LaserScan> toStampedScan(const scip::ScanData& data);
  /// Why the stream counts as lost (empty: it does not).
  std::string stallReason() const;
  void loseDevice(const std::string& kind, const std::string& reason);
  void report(const std::string& kind, const std::string& reason);
  std::chrono::steady_clock::duration stallLimit() const;

  const HokuyoSettings settings_;
  std::unique_ptr<HokuyoLink> link_;
  Mode mode_ = Mode::kClosed;
  HokuyoState state_ = HokuyoState::kDisconnected;
  std::optional<HokuyoIdentity> identity_;
  scip::ScanRequest request_;
  SensorClock clock_;
  Backoff backoff_;
  std::chrono::steady_clock::time_point next_attempt_{};
  std::chrono::steady_clock::time_point last_valid_scan_{};
  std::chrono::steady_clock::time_point last_reply_{};
  ErrorCounter errors_;
  std::uint64_t scans_ = 0;
  std::uint64_t reconnects_ = 0;
  std::uint64_t connect_attempts_ = 0;
  std::string last_error_;
};

}  // namespace mrslam::drivers
