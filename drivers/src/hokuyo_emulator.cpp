#include "mrslam/drivers/hokuyo_emulator.hpp"

#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

namespace mrslam::drivers {
namespace {

using std::chrono::milliseconds;

constexpr int kMaxWaitMs = 5;
constexpr std::size_t kMaxLineChars = 256;  // a longer "line" is noise
constexpr milliseconds kWriteTimeout{100};

speed_t speedOf(int baud) {
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
    default:
      return B0;
  }
}

std::vector<std::string> splitLines(const std::string& reply) {
  std::vector<std::string> lines;
  std::size_t at = 0;
  while (at < reply.size()) {
    const std::size_t end = reply.find('\n', at);
    lines.push_back(reply.substr(at, end - at));
    at = end + 1;
  }
  return lines;
}

std::string joinLines(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) {
    text += line + "\n";
  }
  return text;
}

/// The reply with the sum char of its first data line (echo, status, stamp, data) changed.
std::string withBadChecksum(const std::string& reply) {
  std::vector<std::string> lines = splitLines(reply);
  std::string& line = lines.size() > 3 ? lines[3] : lines.back();
  if (!line.empty()) {
    char& sum = line.back();
    sum = static_cast<char>(((sum - 0x30 + 1) & 0x3F) + 0x30);
  }
  return joinLines(lines);
}

/// The reply without the second half of its data lines (echo, status, stamp kept).
std::string truncated(const std::string& reply) {
  std::vector<std::string> lines = splitLines(reply);  // … data, "" (the end)
  const std::size_t data_lines = lines.size() > 4 ? lines.size() - 4 : 0;
  const std::size_t keep = 3 + data_lines / 2;
  lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(std::min(keep, lines.size() - 1)),
              lines.end() - 1);
  return joinLines(lines);
}

}  // namespace

HokuyoEmulator::HokuyoEmulator(HokuyoEmulatorSettings settings, const std::string& link_path)
    : settings_(std::move(settings)),
      link_path_(link_path),
      pty_(link_path),
      responder_(settings_.model,
                 settings_.ranges ? settings_.ranges : hokuyoRangePattern("ramp", settings_.model),
                 settings_.protocol),
      random_(settings_.seed) {}

HokuyoEmulator::~HokuyoEmulator() {
  stop();
}

void HokuyoEmulator::start() {
  if (!running_.exchange(true)) {
    thread_ = std::thread([this] { run(); });
  }
}

void HokuyoEmulator::stop() {
  running_ = false;
  if (thread_.joinable()) {
    thread_.join();
  }
  runTasks();  // anything posted while stopping
}

std::string HokuyoEmulator::devicePath() const {
  std::lock_guard<std::mutex> lock(log_mutex_);
  return pty_.devicePath();
}

std::vector<std::string> HokuyoEmulator::receivedCommands() const {
  std::lock_guard<std::mutex> lock(log_mutex_);
  return commands_;
}

std::uint32_t HokuyoEmulator::clockMs() const {
  return counterAt(Clock::now());
}

std::uint32_t HokuyoEmulator::counterAt(Clock::time_point time) const {
  const auto elapsed = std::chrono::duration_cast<milliseconds>(time - started_).count();
  return static_cast<std::uint32_t>(
      (settings_.clock_start_ms + static_cast<std::uint64_t>(elapsed)) & 0xFFFFFFu);
}

void HokuyoEmulator::onThread(std::function<void()> task) {
  std::unique_lock<std::mutex> lock(tasks_mutex_);
  tasks_.push_back(std::move(task));
  const std::uint64_t ticket = ++tasks_posted_;
  if (!running_) {
    lock.unlock();
    runTasks();
    return;
  }
  tasks_done_.wait_for(lock, std::chrono::seconds(5),
                       [&] { return tasks_finished_ >= ticket || !running_; });
}

void HokuyoEmulator::runTasks() {
  std::unique_lock<std::mutex> lock(tasks_mutex_);
  while (!tasks_.empty()) {
    auto task = std::move(tasks_.front());
    tasks_.pop_front();
    lock.unlock();
    task();
    lock.lock();
    ++tasks_finished_;
  }
  tasks_done_.notify_all();
}

void HokuyoEmulator::corruptChecksums(int scans) {
  onThread([this, scans] { corrupt_checksums_ += scans; });
}

void HokuyoEmulator::truncateScans(int scans) {
  onThread([this, scans] { truncate_scans_ += scans; });
}

void HokuyoEmulator::injectGarbage(std::size_t bytes) {
  onThread([this, bytes] { pending_garbage_ += bytes; });
}

void HokuyoEmulator::injectStatus(const std::string& status, int scans) {
  onThread([this, status, scans] {
    injected_status_ = status;
    status_scans_ += scans;
  });
}

void HokuyoEmulator::stall(milliseconds duration) {
  onThread([this, duration] { stalled_until_ = Clock::now() + duration; });
}

void HokuyoEmulator::unplug() {
  onThread([this] {
    std::lock_guard<std::mutex> lock(log_mutex_);
    pty_.unplug();
    if (!link_path_.empty()) {
      ::unlink(link_path_.c_str());  // as udev removes the name of an unplugged device
    }
  });
}

void HokuyoEmulator::replug() {
  onThread([this] {
    {
      std::lock_guard<std::mutex> lock(log_mutex_);
      pty_.replug();
    }
    powerOn();
  });
}

void HokuyoEmulator::powerOn() {
  responder_.powerOn();
  line_buffer_.clear();
  pending_garbage_ = 0;
}

void HokuyoEmulator::run() {
  while (running_) {
    runTasks();
    if (!pty_.isPlugged()) {
      std::this_thread::sleep_for(milliseconds(kMaxWaitMs));
      continue;
    }
    int wait_ms = kMaxWaitMs;
    if (responder_.streaming()) {
      const auto until_turn = std::chrono::duration_cast<milliseconds>(next_turn_ - Clock::now());
      wait_ms = static_cast<int>(std::clamp<long long>(until_turn.count(), 0, kMaxWaitMs));
    }
    serveInput(wait_ms);
    streamIfDue();
  }
}

void HokuyoEmulator::serveInput(int wait_ms) {
  pollfd request{pty_.masterFd(), POLLIN, 0};
  if (::poll(&request, 1, wait_ms) <= 0 || (request.revents & POLLIN) == 0) {
    return;
  }
  char buffer[512];
  const ssize_t count = ::read(pty_.masterFd(), buffer, sizeof(buffer));
  if (count <= 0 || Clock::now() < stalled_until_) {
    return;  // nothing, or a stalled device loses what it is sent
  }
  if (!baudMatches()) {  // the device reads noise and answers noise
    send(noise(static_cast<std::size_t>(count)));
    return;
  }
  for (ssize_t i = 0; i < count; ++i) {
    const char c = buffer[i];
    if (c == '\n' || c == '\r') {
      handleLine(line_buffer_);
      line_buffer_.clear();
    } else if (line_buffer_.size() < kMaxLineChars) {
      line_buffer_.push_back(c);
    }
  }
}

void HokuyoEmulator::handleLine(const std::string& line) {
  if (line.empty()) {
    return;
  }
  {
    std::lock_guard<std::mutex> lock(log_mutex_);
    commands_.push_back(line);
  }
  const bool was_streaming = responder_.streaming();
  const std::string reply = responder_.respond(line, clockMs());
  if (reply.size() > 3 && (line.rfind("GD", 0) == 0 || line.rfind("GS", 0) == 0) &&
      reply.find("\n00P\n") != std::string::npos) {
    ++scans_sent_;
  }
  send(reply);
  if (!was_streaming && responder_.streaming()) {  // the first full turn after the request
    const auto period = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(settings_.model.geometry.scanPeriodS()));
    const auto turns = (Clock::now() - started_) / period + 1;
    next_turn_ = started_ + turns * period;
  }
}

void HokuyoEmulator::streamIfDue() {
  if (!responder_.streaming()) {
    return;
  }
  const scip::ScanGeometry& g = settings_.model.geometry;
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(g.scanPeriodS()));
  const auto send_delay = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(g.stepDurationS() * (responder_.stream()->end_step + 1)));
  const auto now = Clock::now();
  if (now < next_turn_ + send_delay) {
    return;
  }
  while (now >= next_turn_ + period + send_delay) {  // turns missed (stalled): lost
    next_turn_ += period;
  }
  const std::uint32_t stamp = counterAt(next_turn_);
  next_turn_ += period;
  if (now < stalled_until_) {
    return;
  }
  if (auto reply = responder_.streamTurn(stamp)) {
    ++scans_sent_;
    send(applyScanFaults(std::move(*reply)));
  }
}

std::string HokuyoEmulator::applyScanFaults(std::string reply) {
  if (status_scans_ > 0) {
    --status_scans_;
    return scip::formatReply(reply.substr(0, reply.find('\n')), injected_status_, {});
  }
  if (corrupt_checksums_ > 0) {
    --corrupt_checksums_;
    reply = withBadChecksum(reply);
  }
  if (truncate_scans_ > 0) {
    --truncate_scans_;
    reply = truncated(reply);
  }
  return reply;
}

void HokuyoEmulator::send(std::string bytes) {
  if (pending_garbage_ > 0) {
    bytes = noise(pending_garbage_) + bytes;
    pending_garbage_ = 0;
  }
  if (!baudMatches()) {
    bytes = noise(bytes.size());
  }
  const auto deadline = Clock::now() + kWriteTimeout;
  std::size_t written = 0;
  while (written < bytes.size() && pty_.isPlugged() && Clock::now() < deadline) {
    const ssize_t count = ::write(pty_.masterFd(), bytes.data() + written, bytes.size() - written);
    if (count > 0) {
      written += static_cast<std::size_t>(count);
    } else if (count < 0 && errno != EAGAIN && errno != EINTR) {
      return;  // nobody listens: the bytes are lost, as on a real link
    } else {
      pollfd request{pty_.masterFd(), POLLOUT, 0};
      ::poll(&request, 1, kMaxWaitMs);
    }
  }
}

bool HokuyoEmulator::baudMatches() const {
  if (settings_.device_baud == 0) {
    return true;
  }
  termios options{};
  return tcgetattr(pty_.masterFd(), &options) == 0 &&
         cfgetospeed(&options) == speedOf(settings_.device_baud);
}

std::string HokuyoEmulator::noise(std::size_t bytes) {
  std::string text(bytes, '\0');
  for (char& c : text) {
    c = static_cast<char>(random_() & 0xFF);
  }
  return text;
}

}  // namespace mrslam::drivers
