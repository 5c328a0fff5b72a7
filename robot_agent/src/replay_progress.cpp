#include "mrslam/robot/replay_progress.hpp"

#include <algorithm>
#include <cmath>

namespace mrslam::robot {

namespace {

constexpr std::chrono::milliseconds kTerminalPeriod{250};
constexpr double kMinElapsedS = 0.5;  // before this, the speed and time left are guesses

std::string clockText(double seconds) {
  const long long total = std::llround(std::max(0.0, seconds));
  char text[32];
  if (total >= 3600) {
    std::snprintf(text, sizeof(text), "%lld:%02lld:%02lld", total / 3600, (total / 60) % 60,
                  total % 60);
  } else {
    std::snprintf(text, sizeof(text), "%lld:%02lld", total / 60, total % 60);
  }
  return text;
}

}  // namespace

std::string formatProgress(double fraction, std::optional<double> speed_factor,
                           std::optional<double> seconds_left) {
  char text[96];
  std::snprintf(text, sizeof(text), "%3.0f %%", 100.0 * std::clamp(fraction, 0.0, 1.0));
  std::string line = text;
  if (speed_factor) {
    std::snprintf(text, sizeof(text), " · %.1f× real time", *speed_factor);
    line += text;
  }
  if (seconds_left) {
    line += " · " + clockText(*seconds_left) + " left";
  }
  return line;
}

ReplayProgress::ReplayProgress(std::string name, std::FILE* stream, bool terminal)
    : name_(std::move(name)), stream_(stream), terminal_(terminal) {}

void ReplayProgress::update(std::optional<double> fraction, Stamp stamp, Clock::time_point now) {
  if (!fraction || stream_ == nullptr) {
    return;
  }
  if (!started_) {
    started_ = now;
    first_stamp_ = stamp;
  }
  const int tenth = static_cast<int>(std::floor(10.0 * *fraction));
  const bool due = terminal_ ? now - last_write_ >= kTerminalPeriod : tenth > last_tenth_;
  if (due) {
    last_tenth_ = tenth;
    write(*fraction, stamp, now);
  }
}

void ReplayProgress::write(double fraction, Stamp stamp, Clock::time_point now) {
  const double elapsed_s = std::chrono::duration<double>(now - *started_).count();
  std::optional<double> speed;
  std::optional<double> left;
  if (elapsed_s >= kMinElapsedS && fraction > 0.0) {
    speed = (stamp.seconds() - first_stamp_->seconds()) / elapsed_s;
    left = elapsed_s * (1.0 - fraction) / fraction;
  }
  const std::string line = name_ + ": " + formatProgress(fraction, speed, left);
  if (terminal_) {
    std::fprintf(stream_, "\r%s\033[K", line.c_str());
  } else {
    std::fprintf(stream_, "%s\n", line.c_str());
  }
  std::fflush(stream_);
  last_write_ = now;
  wrote_ = true;
}

void ReplayProgress::finish() {
  if (terminal_ && wrote_ && stream_ != nullptr) {
    std::fprintf(stream_, "\n");
    std::fflush(stream_);
  }
}

}  // namespace mrslam::robot
