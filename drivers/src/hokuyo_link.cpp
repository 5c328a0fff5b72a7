#include "hokuyo_link.hpp"

#include "mrslam/drivers/device_host_clock.hpp"

#include <algorithm>
#include <cstdint>

namespace mrslam::drivers {
namespace {

using Clock = std::chrono::steady_clock;

std::chrono::milliseconds leftUntil(Clock::time_point deadline) {
  return std::max(std::chrono::milliseconds(0),
                  std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()));
}

}  // namespace

Stamp hostNow() {
  return device_clock::hostNow();  // the clock every device driver stamps on
}

SerialPort::Status HokuyoLink::send(const std::string& line, std::chrono::milliseconds timeout) {
  return port_.writeAll(line + "\n", timeout);
}

SerialPort::Status HokuyoLink::readSome(std::chrono::milliseconds wait) {
  std::uint8_t buffer[4096];
  const auto result = port_.read(buffer, sizeof(buffer), wait);
  if (result.bytes > 0) {
    last_receive_ = hostNow();
    bytes_received_ += result.bytes;
    framer_.append(reinterpret_cast<const char*>(buffer), result.bytes);
  }
  return result.status;
}

void HokuyoLink::discardInput() {
  port_.discardInput();
  framer_.clear();
}

CommandResult HokuyoLink::command(const std::string& request, scip::LineCheck check,
                                  std::chrono::milliseconds timeout) {
  CommandResult result;
  const auto deadline = Clock::now() + timeout;
  result.sent = hostNow();
  result.link = send(request, timeout);
  const std::string echo_line = request + "\n";
  while (result.link == SerialPort::Status::kOk) {
    while (auto block = framer_.next()) {
      const std::size_t at = scip::findEcho(*block, echo_line);
      if (at != std::string::npos) {
        result.received = last_receive_;
        result.reply = scip::parseReply(std::string_view(*block).substr(at), check);
        return result;
      }
    }
    if (Clock::now() >= deadline) {
      result.link = SerialPort::Status::kTimeout;
      break;
    }
    const auto status = readSome(leftUntil(deadline));
    if (status == SerialPort::Status::kDisconnected || status == SerialPort::Status::kError) {
      result.link = status;
    }
  }
  return result;
}

}  // namespace mrslam::drivers
