#pragma once
// The byte link to a Hokuyo ranger: a serial port, the reply framer, and request / reply
// exchanges that wait for the reply echoing the request (other replies, e.g. scans still
// streaming, are skipped). Private to the driver.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "mrslam/common/stamp.hpp"
#include "mrslam/drivers/scip_protocol.hpp"
#include "mrslam/drivers/serial_port.hpp"

namespace mrslam::drivers {

/// The host clock the driver stamps with: the one the other device drivers use (Unix-epoch ns,
/// the system clock read once and advanced by the steady clock, so it never goes back).
Stamp hostNow();

struct CommandResult {
  SerialPort::Status link = SerialPort::Status::kOk;  ///< kTimeout: no reply in time
  std::optional<scip::Parsed<scip::Reply>> reply;     ///< set when link is kOk
  Stamp sent;                                         ///< when the request was written
  Stamp received;                                     ///< when the reply's last bytes arrived

  /// A reply that parsed (whatever its status).
  bool parsed() const { return link == SerialPort::Status::kOk && reply && reply->ok(); }
};

class HokuyoLink {
 public:
  bool open(const std::string& device, int baud) { return port_.open(device, baud); }
  void close() { port_.close(); }
  bool isOpen() const { return port_.isOpen(); }
  bool setBaud(int baud) { return port_.setBaud(baud); }
  const std::string& error() const { return port_.error(); }

  /// Writes `line` and LF.
  SerialPort::Status send(const std::string& line, std::chrono::milliseconds timeout);
  /// Reads what arrives within `wait` into the framer.
  SerialPort::Status readSome(std::chrono::milliseconds wait);
  /// Drops unread input and whatever the framer holds.
  void discardInput();
  scip::ReplyFramer& framer() { return framer_; }
  /// When the bytes last read arrived.
  Stamp lastReceive() const { return last_receive_; }
  /// Bytes read since the link was made.
  std::uint64_t bytesReceived() const { return bytes_received_; }

  /// Sends `request` and waits up to `timeout` for the reply that echoes it.
  CommandResult command(const std::string& request, scip::LineCheck check,
                        std::chrono::milliseconds timeout);

 private:
  SerialPort port_;
  scip::ReplyFramer framer_;
  Stamp last_receive_;
  std::uint64_t bytes_received_ = 0;
};

}  // namespace mrslam::drivers
