#pragma once
// An emulated Hokuyo ranger on a pseudo-terminal: answers SCIP 2.0 (optionally starting in
// SCIP 1.1) on the master side of a PtyPair from its own thread, streams MD scans at the
// model's scan rate, stamps them with its own 24-bit millisecond counter, and injects faults
// on request: bad sum chars, truncated replies, noise, error statuses, stalls, unplug/replug.
// The driver under test opens devicePath() like a device.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "mrslam/drivers/scip_responder.hpp"
#include "mrslam/drivers/serial_port.hpp"

namespace mrslam::drivers {

struct HokuyoEmulatorSettings {
  HokuyoModel model = HokuyoModel::urg04lx();  ///< what VV and PP report
  RangeSource ranges;                          ///< ranges of each scan; empty: the "ramp" pattern
  ScipResponder::Options protocol;   ///< SCIP 1.1 at power-on, TM support, laser malfunction
  int device_baud = 0;               ///< RS-232 rate of the device: a host at another rate
                                     ///< gets garbage; 0 = USB (any rate works)
  std::uint32_t clock_start_ms = 0;  ///< the 24-bit counter at start (near 2^24: wrap test)
  std::uint64_t seed = 1;            ///< seed of the noise bytes
};

class HokuyoEmulator {
 public:
  /// Creates the pseudo-terminal (and `link_path`, a stable link to it, when given).
  explicit HokuyoEmulator(HokuyoEmulatorSettings settings, const std::string& link_path = "");
  /// Stops the thread.
  ~HokuyoEmulator();
  HokuyoEmulator(const HokuyoEmulator&) = delete;
  HokuyoEmulator& operator=(const HokuyoEmulator&) = delete;

  void start();
  /// Ends the thread (it wakes at least every 5 ms).
  void stop();
  /// What the driver opens: the link path, or the slave device.
  std::string devicePath() const;

  // Faults: thread-safe, applied by the emulator thread; each call returns once applied.
  /// The next `scans` scan replies carry a wrong sum char on their first data line.
  void corruptChecksums(int scans);
  /// The next `scans` scan replies lose their second half of data lines (then end normally).
  void truncateScans(int scans);
  /// `bytes` random bytes go out before the next reply.
  void injectGarbage(std::size_t bytes);
  /// The next `scans` scan replies carry `status` (e.g. "50") and no data.
  void injectStatus(const std::string& status, int scans);
  /// Sends and answers nothing for `duration`: requests are lost, scans are missed.
  void stall(std::chrono::milliseconds duration);
  /// Closes the master (PtyPair::unplug): the driver sees a hang-up; the link path goes away.
  void unplug();
  /// A new pseudo-terminal behind the same link (PtyPair::replug), device powered on afresh.
  void replug();

  /// Request lines received so far (in order).
  std::vector<std::string> receivedCommands() const;
  /// Scan replies sent (MD stream and GD).
  std::uint64_t scansSent() const { return scans_sent_.load(); }
  /// The device's 24-bit millisecond counter now.
  std::uint32_t clockMs() const;

 private:
  using Clock = std::chrono::steady_clock;

  void run();
  void runTasks();
  void onThread(std::function<void()> task);
  void serveInput(int wait_ms);
  void handleLine(const std::string& line);
  void streamIfDue();
  std::string applyScanFaults(std::string reply);
  void send(std::string bytes);
  bool baudMatches() const;
  std::string noise(std::size_t bytes);
  std::uint32_t counterAt(Clock::time_point time) const;
  void powerOn();

  const HokuyoEmulatorSettings settings_;
  const std::string link_path_;
  PtyPair pty_;
  ScipResponder responder_;
  const Clock::time_point started_ = Clock::now();
  std::mt19937_64 random_;

  // Emulator-thread state.
  std::string line_buffer_;
  Clock::time_point next_turn_{};
  Clock::time_point stalled_until_{};
  int corrupt_checksums_ = 0;
  int truncate_scans_ = 0;
  int status_scans_ = 0;
  std::string injected_status_;
  std::size_t pending_garbage_ = 0;

  std::thread thread_;
  std::atomic<bool> running_{false};
  std::atomic<std::uint64_t> scans_sent_{0};
  std::mutex tasks_mutex_;
  std::condition_variable tasks_done_;
  std::deque<std::function<void()>> tasks_;
  std::uint64_t tasks_finished_ = 0;
  std::uint64_t tasks_posted_ = 0;
  mutable std::mutex log_mutex_;
  std::vector<std::string> commands_;
};

}  // namespace mrslam::drivers
