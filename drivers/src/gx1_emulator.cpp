// The 3DM-GX1 emulator: a thread answering on the master side of a pty.

#include "mrslam/drivers/gx1_emulator.hpp"

#include <poll.h>
#include <unistd.h>

#include <spdlog/spdlog.h>
#include <algorithm>
#include <cerrno>

namespace mrslam::drivers {

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kPollMs = 5;
constexpr int kWriteWaitMs = 20;
// Stray bytes sent before a frame: some look like headers, so the parser must resynchronise.
const std::vector<std::uint8_t> kStrayBytes = {0x00, 0x31, 0xFF, 0x0E, 0x55, 0x0C, 0xAA};

// Same size and header as the frame, but 0xFF words and a zero checksum: never valid.
std::vector<std::uint8_t> garbageLike(const std::vector<std::uint8_t>& frame) {
  std::vector<std::uint8_t> garbage(frame.size(), 0xFF);
  garbage.front() = frame.front();
  garbage[garbage.size() - 1] = 0x00;
  garbage[garbage.size() - 2] = 0x00;
  return garbage;
}

void corrupt(Gx1Fault fault, std::vector<std::uint8_t>& frame) {
  switch (fault) {
    case Gx1Fault::kBadChecksum:
      frame.back() ^= 0xFF;
      break;
    case Gx1Fault::kTruncated:
      frame.resize(frame.size() / 2);
      break;
    case Gx1Fault::kStrayBytes:
      frame.insert(frame.begin(), kStrayBytes.begin(), kStrayBytes.end());
      break;
    case Gx1Fault::kGarbageReply:
      frame = garbageLike(frame);
      break;
  }
}

}  // namespace

Gx1Emulator::Gx1Emulator(Gx1EmulatorSettings settings, StateSource source)
    : settings_(std::move(settings)),
      source_(std::move(source)),
      pty_(std::make_unique<PtyPair>(settings_.link_path)),
      ticks_(settings_.initial_ticks),
      power_on_(Clock::now()) {}

Gx1Emulator::~Gx1Emulator() {
  stop();
}

void Gx1Emulator::start() {
  if (running_) {
    return;
  }
  running_ = true;
  thread_ = std::thread([this] { run(); });
}

void Gx1Emulator::stop() {
  if (!running_) {
    return;
  }
  running_ = false;
  thread_.join();
}

std::string Gx1Emulator::devicePath() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return pty_->devicePath();
}

void Gx1Emulator::injectFault(Gx1Fault fault, int count) {
  std::lock_guard<std::mutex> lock(mutex_);
  faults_.push_back({fault, count});
}

void Gx1Emulator::setStalled(bool stalled) {
  std::lock_guard<std::mutex> lock(mutex_);
  stalled_ = stalled;
}

void Gx1Emulator::unplug() {
  requestPlug(false);
}

void Gx1Emulator::replug() {
  requestPlug(true);
}

bool Gx1Emulator::streaming() const {
  return streamingCommand().has_value();
}

std::optional<std::uint8_t> Gx1Emulator::streamingCommand() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return streaming_;
}

Gx1EmulatorCounters Gx1Emulator::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

void Gx1Emulator::requestPlug(bool plugged) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!running_) {
    plug(plugged);
    return;
  }
  plug_request_ = plugged;
  plug_done_.wait(lock, [this] { return !plug_request_.has_value(); });
}

void Gx1Emulator::applyPlugRequest() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (plug_request_) {
    plug(*plug_request_);
    plug_request_.reset();
    plug_done_.notify_all();
  }
}

void Gx1Emulator::plug(bool plugged) {
  // Called with mutex_ held: the device powers off (and on again, with a new pty).
  streaming_.reset();
  input_.clear();
  output_.clear();
  ticks_ = settings_.initial_ticks;
  power_on_ = Clock::now();
  try {
    if (plugged) {
      pty_->replug();
    } else {
      pty_->unplug();
    }
  } catch (const std::exception& error) {
    spdlog::error("gx1 emulator: {}", error.what());
  }
}

void Gx1Emulator::run() {
  while (running_) {
    applyPlugRequest();
    const int fd = pty_->masterFd();  // only this thread changes the pty while running
    if (fd < 0) {
      ::usleep(kPollMs * 1000);
      continue;
    }
    pollfd request{fd, POLLIN, 0};
    const int ready = ::poll(&request, 1, kPollMs);
    if (ready > 0 && (request.revents & POLLIN) != 0) {
      handleInput(fd);
    } else if (ready > 0) {
      ::usleep(kPollMs * 1000);  // hang-up without data: nobody on the other side
    }
    stream();
    writeOut(fd);
  }
}

void Gx1Emulator::handleInput(int fd) {
  std::uint8_t buffer[256];
  const ssize_t count = ::read(fd, buffer, sizeof(buffer));
  if (count > 0) {
    input_.insert(input_.end(), buffer, buffer + count);
    handleCommands();
  }
}

void Gx1Emulator::handleCommands() {
  std::size_t i = 0;
  while (i < input_.size()) {
    const std::uint8_t command = input_[i];
    if (gx1::isOrientationCommand(command)) {
      answerPolled(command);
      i += 1;
    } else if (command == gx1::kEepromReadCommand || command == gx1::kContinuousCommand) {
      if (input_.size() - i < 3) {
        break;  // the rest of the request is on its way
      }
      if (command == gx1::kEepromReadCommand) {
        answerEeprom(input_[i + 1], input_[i + 2]);
      } else {
        answerContinuous(input_[i + 2]);
      }
      i += 3;
    } else {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.unknown_bytes;
      i += 1;
    }
  }
  input_.erase(input_.begin(), input_.begin() + static_cast<std::ptrdiff_t>(i));
}

void Gx1Emulator::answerPolled(std::uint8_t command) {
  if (isStalled()) {
    return;
  }
  send(reading(command));
  std::lock_guard<std::mutex> lock(mutex_);
  ++counters_.polled_replies;
}

void Gx1Emulator::answerEeprom(std::uint8_t address_hi, std::uint8_t address_lo) {
  if (isStalled()) {
    return;
  }
  const auto address = static_cast<std::uint16_t>(address_hi << 8 | address_lo);
  std::uint16_t value = 0;  // other EEPROM cells are not emulated
  if (address == gx1::kGyroGainAddress) {
    value = settings_.gyro_gain;
  } else if (address == gx1::kAccelGainAddress) {
    value = settings_.accel_gain;
  } else if (address == gx1::kMagGainAddress) {
    value = settings_.mag_gain;
  }
  send(gx1::encodeFrame(gx1::kEepromReadCommand, {value, nextTicks()}));
  std::lock_guard<std::mutex> lock(mutex_);
  ++counters_.eeprom_reads;
}

void Gx1Emulator::answerContinuous(std::uint8_t command) {
  if (isStalled()) {
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (command == 0) {
      streaming_.reset();
      ++counters_.continuous_stops;
    } else if (gx1::isOrientationCommand(command)) {
      streaming_ = command;
      ++counters_.continuous_starts;
    } else {
      return;
    }
  }
  next_stream_ = Clock::now() + settings_.continuous_interval;
  if (settings_.confirm_continuous) {
    send(gx1::encodeFrame(gx1::kContinuousCommand, {command, nextTicks()}));
  }
}

void Gx1Emulator::stream() {
  const std::optional<std::uint8_t> command = streamingCommand();
  if (!command || isStalled() || Clock::now() < next_stream_) {
    return;
  }
  send(reading(*command));
  next_stream_ = std::max(next_stream_ + settings_.continuous_interval, Clock::now());
  std::lock_guard<std::mutex> lock(mutex_);
  ++counters_.streamed_frames;
}

bool Gx1Emulator::isStalled() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stalled_;
}

std::vector<std::uint8_t> Gx1Emulator::reading(std::uint8_t command) {
  const gx1::Gains gains{static_cast<double>(settings_.gyro_gain),
                         static_cast<double>(settings_.accel_gain),
                         static_cast<double>(settings_.mag_gain)};
  return gx1::encodeReading(command, source_(), gains, nextTicks());
}

std::uint16_t Gx1Emulator::nextTicks() {
  if (settings_.ticks_per_frame > 0) {
    const std::uint16_t ticks = ticks_;
    ticks_ = static_cast<std::uint16_t>(ticks_ + settings_.ticks_per_frame);
    return ticks;
  }
  const double elapsed = std::chrono::duration<double>(Clock::now() - power_on_).count();
  const auto counted = static_cast<std::uint64_t>(elapsed / settings_.tick_period_s);
  return static_cast<std::uint16_t>(settings_.initial_ticks + counted);
}

void Gx1Emulator::send(std::vector<std::uint8_t> frame) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!faults_.empty()) {
      corrupt(faults_.front().kind, frame);
      ++counters_.faults_applied;
      if (--faults_.front().remaining <= 0) {
        faults_.erase(faults_.begin());
      }
    }
  }
  output_.insert(output_.end(), frame.begin(), frame.end());
}

void Gx1Emulator::writeOut(int fd) {
  std::size_t written = 0;
  while (written < output_.size()) {
    const ssize_t count = ::write(fd, output_.data() + written, output_.size() - written);
    if (count > 0) {
      written += static_cast<std::size_t>(count);
      continue;
    }
    if (count < 0 && errno != EAGAIN && errno != EINTR) {
      break;  // unplugged under us: the frames are lost, as on a real cable
    }
    pollfd request{fd, POLLOUT, 0};
    if (::poll(&request, 1, kWriteWaitMs) <= 0) {
      break;  // nobody reads: drop the rest
    }
  }
  output_.clear();
}

}  // namespace mrslam::drivers
