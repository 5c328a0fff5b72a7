#include "mrslam/drivers/serial_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace mrslam::drivers {

namespace {

speed_t baudConstant(int baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    case 460800:
      return B460800;
    case 500000:
      return B500000;
    case 576000:
      return B576000;
    case 921600:
      return B921600;
    default:
      return B0;
  }
}

}  // namespace

SerialPort::~SerialPort() {
  close();
}

SerialPort::SerialPort(SerialPort&& other) noexcept
    : fd_(other.fd_), device_(std::move(other.device_)), error_(std::move(other.error_)) {
  other.fd_ = -1;
}

SerialPort& SerialPort::operator=(SerialPort&& other) noexcept {
  if (this != &other) {
    close();
    fd_ = other.fd_;
    device_ = std::move(other.device_);
    error_ = std::move(other.error_);
    other.fd_ = -1;
  }
  return *this;
}

SerialPort::Status SerialPort::fail(const std::string& what, int error_number) {
  error_ = device_ + ": " + what +
           (error_number != 0 ? std::string(": ") + std::strerror(error_number) : "");
  const bool gone = error_number == EIO || error_number == ENXIO || error_number == ENODEV ||
                    error_number == EBADF;
  return gone ? Status::kDisconnected : Status::kError;
}

bool SerialPort::open(const std::string& device, int baud) {
  close();
  device_ = device;
  if (baudConstant(baud) == B0) {
    fail("unsupported baud rate " + std::to_string(baud), 0);
    return false;
  }
  fd_ = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    fail("cannot open", errno);
    return false;
  }
  termios options{};
  if (tcgetattr(fd_, &options) != 0) {
    fail("not a terminal", errno);
    close();
    return false;
  }
  cfmakeraw(&options);
  options.c_cflag |= CLOCAL | CREAD;
  options.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | CRTSCTS);
  options.c_cc[VMIN] = 0;
  options.c_cc[VTIME] = 0;
  cfsetispeed(&options, baudConstant(baud));
  cfsetospeed(&options, baudConstant(baud));
  if (tcsetattr(fd_, TCSANOW, &options) != 0) {
    fail("cannot configure", errno);
    close();
    return false;
  }
  tcflush(fd_, TCIOFLUSH);
  error_.clear();
  return true;
}

bool SerialPort::setBaud(int baud) {
  termios options{};
  if (fd_ < 0 || baudConstant(baud) == B0 || tcgetattr(fd_, &options) != 0) {
    fail("cannot set baud rate " + std::to_string(baud), errno);
    return false;
  }
  cfsetispeed(&options, baudConstant(baud));
  cfsetospeed(&options, baudConstant(baud));
  if (tcsetattr(fd_, TCSANOW, &options) != 0) {
    fail("cannot set baud rate " + std::to_string(baud), errno);
    return false;
  }
  return true;
}

void SerialPort::close() {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

SerialPort::ReadResult SerialPort::read(std::uint8_t* buffer, std::size_t size,
                                        std::chrono::milliseconds timeout) {
  if (fd_ < 0) {
    return {fail("not open", EBADF), 0};
  }
  pollfd request{fd_, POLLIN, 0};
  const int ready = ::poll(&request, 1, static_cast<int>(timeout.count()));
  if (ready < 0) {
    return {errno == EINTR ? Status::kTimeout : fail("poll failed", errno), 0};
  }
  if (ready == 0) {
    return {Status::kTimeout, 0};
  }
  const ssize_t count = ::read(fd_, buffer, size);
  if (count > 0) {
    return {Status::kOk, static_cast<std::size_t>(count)};
  }
  if (count < 0 && (errno == EAGAIN || errno == EINTR)) {
    return {Status::kTimeout, 0};
  }
  if ((request.revents & (POLLHUP | POLLERR)) != 0 || count == 0) {
    return {fail("device gone (hang-up)", count < 0 ? errno : EIO), 0};
  }
  return {fail("read failed", errno), 0};
}

SerialPort::Status SerialPort::writeAll(const void* data, std::size_t size,
                                        std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  std::size_t written = 0;
  while (written < size) {
    if (fd_ < 0) {
      return fail("not open", EBADF);
    }
    const ssize_t count = ::write(fd_, bytes + written, size - written);
    if (count > 0) {
      written += static_cast<std::size_t>(count);
      continue;
    }
    if (count < 0 && errno != EAGAIN && errno != EINTR) {
      return fail("write failed", errno);
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      return Status::kTimeout;
    }
    pollfd request{fd_, POLLOUT, 0};
    ::poll(&request, 1, static_cast<int>(left.count()));
  }
  return Status::kOk;
}

void SerialPort::discardInput() {
  if (fd_ >= 0) {
    tcflush(fd_, TCIFLUSH);
  }
}

std::chrono::milliseconds Backoff::next() {
  const std::chrono::milliseconds delay = next_;
  next_ = std::min(maximum_, next_ * 2);
  return delay;
}

PtyPair::PtyPair(std::string link_path) : link_path_(std::move(link_path)) {
  openPair();
}

PtyPair::~PtyPair() {
  unplug();
  if (!link_path_.empty()) {
    ::unlink(link_path_.c_str());
  }
}

void PtyPair::openPair() {
  master_fd_ = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master_fd_ < 0 || grantpt(master_fd_) != 0 || unlockpt(master_fd_) != 0) {
    throw std::runtime_error(std::string("cannot create a pseudo-terminal: ") +
                             std::strerror(errno));
  }
  char name[128];
  if (ptsname_r(master_fd_, name, sizeof(name)) != 0) {
    throw std::runtime_error("cannot name the pseudo-terminal");
  }
  // Raw mode on both sides: a default pty echoes and turns LF into CR LF.
  slave_keepalive_fd_ = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
  termios options{};
  if (slave_keepalive_fd_ >= 0 && tcgetattr(slave_keepalive_fd_, &options) == 0) {
    cfmakeraw(&options);
    tcsetattr(slave_keepalive_fd_, TCSANOW, &options);
  }
  if (tcgetattr(master_fd_, &options) == 0) {
    cfmakeraw(&options);
    tcsetattr(master_fd_, TCSANOW, &options);
  }
  ::fcntl(master_fd_, F_SETFL, ::fcntl(master_fd_, F_GETFL) | O_NONBLOCK);
  device_path_ = name;
  if (!link_path_.empty()) {
    const std::string temporary = link_path_ + ".new";
    ::unlink(temporary.c_str());
    if (::symlink(name, temporary.c_str()) != 0 ||
        ::rename(temporary.c_str(), link_path_.c_str()) != 0) {
      throw std::runtime_error("cannot link " + link_path_ + " to " + name + ": " +
                               std::strerror(errno));
    }
    device_path_ = link_path_;
  }
}

void PtyPair::unplug() {
  if (slave_keepalive_fd_ >= 0) {
    ::close(slave_keepalive_fd_);
    slave_keepalive_fd_ = -1;
  }
  if (master_fd_ >= 0) {
    ::close(master_fd_);
    master_fd_ = -1;
  }
}

void PtyPair::replug() {
  unplug();
  openPair();
}

}  // namespace mrslam::drivers
