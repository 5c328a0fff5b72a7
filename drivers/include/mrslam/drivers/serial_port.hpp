#pragma once
// A serial port in raw mode (termios): configurable baud rate, poll-based read time-outs, and
// detection of an unplugged device (EIO or hang-up). Also the pseudo-terminal pair the device
// emulators and the driver tests use in place of a real device.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

namespace mrslam::drivers {

class SerialPort {
 public:
  enum class Status {
    kOk,            ///< bytes were read or written
    kTimeout,       ///< nothing arrived in time
    kDisconnected,  ///< the device is gone (EIO, hang-up, closed by the other side)
    kError,         ///< another error; see error()
  };

  struct ReadResult {
    Status status = Status::kTimeout;
    std::size_t bytes = 0;
  };

  SerialPort() = default;
  ~SerialPort();
  SerialPort(SerialPort&& other) noexcept;
  SerialPort& operator=(SerialPort&& other) noexcept;
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  /// Opens `device` in raw 8N1 mode at `baud` (pseudo-terminals accept any rate). False with
  /// error() set when the device cannot be opened or configured.
  bool open(const std::string& device, int baud);
  void close();
  bool isOpen() const { return fd_ >= 0; }
  const std::string& device() const { return device_; }
  /// The reason of the last failure.
  const std::string& error() const { return error_; }

  /// Reads what is available (up to `size` bytes), waiting at most `timeout`.
  ReadResult read(std::uint8_t* buffer, std::size_t size, std::chrono::milliseconds timeout);
  /// Writes every byte, waiting at most `timeout` in all.
  Status writeAll(const void* data, std::size_t size, std::chrono::milliseconds timeout);
  Status writeAll(const std::string& text, std::chrono::milliseconds timeout) {
    return writeAll(text.data(), text.size(), timeout);
  }
  /// Drops whatever is waiting to be read.
  void discardInput();
  /// Changes the baud rate of an open port.
  bool setBaud(int baud);

 private:
  Status fail(const std::string& what, int error_number);

  int fd_ = -1;
  std::string device_;
  std::string error_;
};

/// Delays between reconnection attempts: doubling from `initial` up to `maximum`.
class Backoff {
 public:
  Backoff(std::chrono::milliseconds initial, std::chrono::milliseconds maximum)
      : initial_(initial), maximum_(maximum), next_(initial) {}
  /// The delay to wait now; the following one is twice as long (at most `maximum`).
  std::chrono::milliseconds next();
  void reset() { next_ = initial_; }

 private:
  std::chrono::milliseconds initial_;
  std::chrono::milliseconds maximum_;
  std::chrono::milliseconds next_;
};

/// A pseudo-terminal pair standing in for a serial device: the emulator owns the master side,
/// the driver opens slavePath() like a device. Both sides are raw (no echo, no CR/LF changes).
/// `link_path`, when given, is a symbolic link to the slave kept up to date, so a device
/// "unplugged" and "replugged" (a new pair) keeps one stable path, as a udev name does.
class PtyPair {
 public:
  explicit PtyPair(std::string link_path = "");
  ~PtyPair();
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;

  int masterFd() const { return master_fd_; }
  /// The slave device (/dev/pts/N) or, when a link was asked for, the link.
  const std::string& devicePath() const { return device_path_; }
  /// Closes the master: the driver sees the device vanish (EIO / hang-up).
  void unplug();
  /// A new pair behind the same link (after unplug()).
  void replug();
  bool isPlugged() const { return master_fd_ >= 0; }

 private:
  void openPair();

  std::string link_path_;
  std::string device_path_;
  int master_fd_ = -1;
  int slave_keepalive_fd_ = -1;  ///< keeps the slave side valid until a driver opens it
};

}  // namespace mrslam::drivers
