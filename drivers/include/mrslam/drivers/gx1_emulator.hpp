#pragma once
// A MicroStrain 3DM-GX1 on the master side of a pseudo-terminal, answering in its own thread:
// EEPROM reads (0x28) of the gains, polled orientation commands (0x0E, 0x31, 0x0C) and
// continuous mode (0x10 0x00 <cmd>, confirmed with the assumed layout of gx1_codec.hpp).
// What it measures comes from a callback (tests: fixed values; the simulator: its truth).
// Faults for tests: corrupt checksums, truncated frames, stray bytes, garbage replies, a stall,
// and unplugging / replugging the device (a new pty behind the same link path).

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "mrslam/drivers/gx1_codec.hpp"
#include "mrslam/drivers/serial_port.hpp"

namespace mrslam::drivers {

struct Gx1EmulatorSettings {
  std::string link_path;              ///< stable device path (a symlink); empty: /dev/pts/N
  std::uint16_t gyro_gain = 10000;    ///< EEPROM 130
  std::uint16_t accel_gain = 8500;    ///< EEPROM 230
  std::uint16_t mag_gain = 2000;      ///< EEPROM 232
  std::uint16_t initial_ticks = 0;    ///< the timer at power-up (e.g. 65530: wraps soon)
  std::uint16_t ticks_per_frame = 0;  ///< fixed timer step per frame sent; 0: real time
  double tick_period_s = 6.5536e-3;   ///< timer period when the timer runs in real time
  std::chrono::microseconds continuous_interval{10000};  ///< between frames when streaming
  bool confirm_continuous = true;  ///< reply to 0x10 with a confirmation frame
};

/// Faults applied to the next frames the emulator sends (replies and streamed frames).
enum class Gx1Fault {
  kBadChecksum,   ///< the checksum's low byte is flipped
  kTruncated,     ///< only the first half of the frame is sent
  kStrayBytes,    ///< a few stray bytes (some look like headers) come before the frame
  kGarbageReply,  ///< the frame is replaced by bytes that are no valid frame
};

struct Gx1EmulatorCounters {
  std::uint64_t eeprom_reads = 0;       ///< 0x28 requests answered
  std::uint64_t polled_replies = 0;     ///< 0x0E / 0x31 / 0x0C requests answered
  std::uint64_t streamed_frames = 0;    ///< frames sent in continuous mode
  std::uint64_t continuous_starts = 0;  ///< 0x10 0x00 <cmd> with cmd != 0
  std::uint64_t continuous_stops = 0;   ///< 0x10 0x00 0x00
  std::uint64_t unknown_bytes = 0;      ///< bytes that are no known command
  std::uint64_t faults_applied = 0;
};

class Gx1Emulator {
 public:
  using StateSource = std::function<gx1::DeviceState()>;

  /// Creates the pty (throws std::runtime_error when it cannot). `source` is called on the
  /// emulator's thread for every frame.
  Gx1Emulator(Gx1EmulatorSettings settings, StateSource source);
  ~Gx1Emulator();
  Gx1Emulator(const Gx1Emulator&) = delete;
  Gx1Emulator& operator=(const Gx1Emulator&) = delete;

  void start();
  void stop();

  /// The path a driver opens (the link when one was asked for).
  std::string devicePath() const;
  /// Applies `fault` to the next `count` frames sent.
  void injectFault(Gx1Fault fault, int count = 1);
  /// A stalled device reads its input but sends nothing.
  void setStalled(bool stalled);
  /// Closes the master side: the driver sees the device vanish. Streaming stops.
  void unplug();
  /// A new pty behind the same link; the device starts afresh (not streaming).
  void replug();

  bool streaming() const;
  std::optional<std::uint8_t> streamingCommand() const;
  Gx1EmulatorCounters counters() const;

 private:
  struct Fault {
    Gx1Fault kind;
    int remaining;
  };

  void requestPlug(bool plugged);
  void applyPlugRequest();
  void plug(bool plugged);
  void run();
  void handleInput(int fd);
  void handleCommands();
  void answerPolled(std::uint8_t command);
  void answerEeprom(std::uint8_t address_hi, std::uint8_t address_lo);
  void answerContinuous(std::uint8_t command);
  void stream();
  bool isStalled() const;
  std::vector<std::uint8_t> reading(std::uint8_t command);
  std::uint16_t nextTicks();
  void send(std::vector<std::uint8_t> frame);
  void writeOut(int fd);

  const Gx1EmulatorSettings settings_;
  const StateSource source_;
  std::unique_ptr<PtyPair> pty_;

  mutable std::mutex mutex_;
  std::condition_variable plug_done_;
  std::optional<bool> plug_request_;  ///< true: replug, false: unplug
  std::vector<Fault> faults_;
  bool stalled_ = false;
  std::optional<std::uint8_t> streaming_;
  Gx1EmulatorCounters counters_;

  // The emulator thread's own (or the caller's while the thread is not running):
  std::vector<std::uint8_t> input_;   ///< request bytes not yet handled
  std::vector<std::uint8_t> output_;  ///< frames to write in this round
  std::uint16_t ticks_ = 0;
  std::chrono::steady_clock::time_point power_on_;
  std::chrono::steady_clock::time_point next_stream_{};
  std::atomic<bool> running_{false};
  std::thread thread_;
};

}  // namespace mrslam::drivers
