#include "mrslam/robot/replay_progress.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace mrslam::robot {
namespace {

using Clock = ReplayProgress::Clock;

// What a ReplayProgress wrote into a memory stream.
class CapturedStream {
 public:
  CapturedStream() : stream_(open_memstream(&buffer_, &size_)) {}
  ~CapturedStream() {
    std::fclose(stream_);
    std::free(buffer_);
  }
  std::FILE* get() { return stream_; }
  std::string text() {
    std::fflush(stream_);
    return std::string(buffer_, size_);
  }

 private:
  char* buffer_ = nullptr;
  std::size_t size_ = 0;
  std::FILE* stream_;
};

TEST(ReplayProgressTest, FormatsPercentSpeedAndTimeLeft) {
  EXPECT_EQ(formatProgress(0.42, 12.34, 35.2), " 42 % · 12.3× real time · 0:35 left");
  EXPECT_EQ(formatProgress(1.0, std::nullopt, std::nullopt), "100 %");
  EXPECT_EQ(formatProgress(0.5, 1.0, 3725.0), " 50 % · 1.0× real time · 1:02:05 left");
  EXPECT_EQ(formatProgress(1.7, std::nullopt, std::nullopt), "100 %");  // clamped
}

TEST(ReplayProgressTest, WithoutATerminalAPlainLineAtEveryTenth) {
  CapturedStream captured;
  ReplayProgress progress("robot1", captured.get(), false);
  const Clock::time_point start = Clock::now();
  // 100 samples 0.1 s apart on the log's clock, replayed in 1 s: 10× real time.
  for (int i = 1; i <= 100; ++i) {
    progress.update(i / 100.0, Stamp::fromSeconds(0.1 * i),
                    start + std::chrono::milliseconds(10 * i));
  }
  progress.update(std::nullopt, Stamp::fromSeconds(11.0), start + std::chrono::seconds(2));
  progress.finish();
  const std::string text = captured.text();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 10) << text;
  EXPECT_EQ(text.find('\r'), std::string::npos);
  EXPECT_NE(text.find("robot1:  10 %\n"), std::string::npos) << text;  // too early for a speed
  EXPECT_NE(text.find("robot1:  60 % · 10.0× real time · 0:00 left\n"), std::string::npos) << text;
  EXPECT_NE(text.find("robot1: 100 % · 10.0× real time · 0:00 left\n"), std::string::npos) << text;
}

TEST(ReplayProgressTest, OnATerminalOneLineIsRewrittenAtMostFourTimesASecond) {
  CapturedStream captured;
  ReplayProgress progress("robot2", captured.get(), true);
  const Clock::time_point start = Clock::now();
  for (int i = 1; i <= 100; ++i) {  // 100 samples over 5 s
    progress.update(i / 100.0, Stamp::fromSeconds(0.5 * i),
                    start + std::chrono::milliseconds(50 * i));
  }
  progress.finish();
  const std::string text = captured.text();
  const auto rewrites = std::count(text.begin(), text.end(), '\r');
  EXPECT_GE(rewrites, 19);  // every 250 ms of 5 s
  EXPECT_LE(rewrites, 21);
  EXPECT_EQ(text.back(), '\n');  // finish() ends the line
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1);
}

}  // namespace
}  // namespace mrslam::robot
