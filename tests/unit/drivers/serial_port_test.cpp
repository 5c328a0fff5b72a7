#include "mrslam/drivers/serial_port.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

#include "test_data.hpp"

namespace mrslam::drivers {
namespace {

using namespace std::chrono_literals;

std::string readFromMaster(int master_fd, std::size_t expected) {
  std::string text;
  for (int attempt = 0; attempt < 100 && text.size() < expected; ++attempt) {
    char buffer[256];
    const ssize_t count = ::read(master_fd, buffer, sizeof(buffer));
    if (count > 0) {
      text.append(buffer, static_cast<std::size_t>(count));
    } else {
      ::usleep(10000);
    }
  }
  return text;
}

std::string readFromPort(SerialPort& port, std::size_t expected) {
  std::string text;
  for (int attempt = 0; attempt < 50 && text.size() < expected; ++attempt) {
    std::uint8_t buffer[256];
    const auto result = port.read(buffer, sizeof(buffer), 20ms);
    text.append(reinterpret_cast<const char*>(buffer), result.bytes);
  }
  return text;
}

TEST(SerialPortTest, BytesPassBothWaysUnchangedInRawMode) {
  PtyPair pty;
  SerialPort port;
  ASSERT_TRUE(port.open(pty.devicePath(), 115200)) << port.error();
  // LF and CR must arrive untouched (a cooked pty would echo and turn LF into CR LF).
  const std::string request = "MD0044072501000\n";
  ASSERT_EQ(port.writeAll(request, 100ms), SerialPort::Status::kOk);
  EXPECT_EQ(readFromMaster(pty.masterFd(), request.size()), request);
  const std::string reply = "MD0044072501000\n00P\n\n\r\x01\xff";
  ASSERT_EQ(::write(pty.masterFd(), reply.data(), reply.size()),
            static_cast<ssize_t>(reply.size()));
  EXPECT_EQ(readFromPort(port, reply.size()), reply);
}

TEST(SerialPortTest, ReadTimesOutWhenNothingArrives) {
  PtyPair pty;
  SerialPort port;
  ASSERT_TRUE(port.open(pty.devicePath(), 38400));
  std::uint8_t buffer[8];
  const auto result = port.read(buffer, sizeof(buffer), 30ms);
  EXPECT_EQ(result.status, SerialPort::Status::kTimeout);
  EXPECT_EQ(result.bytes, 0u);
}

TEST(SerialPortTest, UnplugIsDetectedAndReplugIsReachableAtTheSamePath) {
  const std::string link = (test::scratchFolder("pty") / "ttyACM-test").string();
  PtyPair pty(link);
  SerialPort port;
  ASSERT_TRUE(port.open(link, 115200)) << port.error();
  pty.unplug();
  std::uint8_t buffer[8];
  SerialPort::Status status = SerialPort::Status::kTimeout;
  for (int attempt = 0; attempt < 20 && status == SerialPort::Status::kTimeout; ++attempt) {
    status = port.read(buffer, sizeof(buffer), 20ms).status;
  }
  EXPECT_EQ(status, SerialPort::Status::kDisconnected);
  EXPECT_FALSE(port.error().empty());
  port.close();

  pty.replug();
  ASSERT_TRUE(port.open(link, 115200)) << port.error();
  ASSERT_EQ(::write(pty.masterFd(), "ok", 2), 2);
  EXPECT_EQ(readFromPort(port, 2), "ok");
}

TEST(SerialPortTest, MissingDeviceAndBadBaudAreClearErrors) {
  SerialPort port;
  EXPECT_FALSE(port.open("/dev/nonexistent-mrslam", 115200));
  EXPECT_NE(port.error().find("/dev/nonexistent-mrslam: cannot open"), std::string::npos);
  PtyPair pty;
  EXPECT_FALSE(port.open(pty.devicePath(), 12345));
  EXPECT_NE(port.error().find("unsupported baud rate 12345"), std::string::npos);
  EXPECT_FALSE(port.open("/dev/null", 115200));  // not a terminal
  EXPECT_NE(port.error().find("not a terminal"), std::string::npos);
}

TEST(BackoffTest, DoublesUpToTheMaximumAndResets) {
  Backoff backoff(100ms, 700ms);
  EXPECT_EQ(backoff.next(), 100ms);
  EXPECT_EQ(backoff.next(), 200ms);
  EXPECT_EQ(backoff.next(), 400ms);
  EXPECT_EQ(backoff.next(), 700ms);
  EXPECT_EQ(backoff.next(), 700ms);
  backoff.reset();
  EXPECT_EQ(backoff.next(), 100ms);
}

}  // namespace
}  // namespace mrslam::drivers
