#pragma once
// How far a replay has got, for the person watching it: percent of the log, speed against the
// log's own clock and time left. On a terminal one line is rewritten in place (at most four
// times a second); otherwise a plain line is written at every 10 %.

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

#include "mrslam/common/stamp.hpp"

namespace mrslam::robot {

/// E.g. "42 % · 12.3× real time · 0:35 left" (the speed and time left when they are known).
std::string formatProgress(double fraction, std::optional<double> speed_factor,
                           std::optional<double> seconds_left);

class ReplayProgress {
 public:
  using Clock = std::chrono::steady_clock;

  /// Writes to `stream`, prefixing lines with `name`; `terminal`: rewrite one line in place.
  ReplayProgress(std::string name, std::FILE* stream, bool terminal);

  /// After each sample: the source's progress and the sample's stamp; `now` for tests.
  void update(std::optional<double> fraction, Stamp stamp, Clock::time_point now = Clock::now());
  /// Ends the line on a terminal.
  void finish();

 private:
  void write(double fraction, Stamp stamp, Clock::time_point now);

  std::string name_;
  std::FILE* stream_;
  bool terminal_;
  std::optional<Clock::time_point> started_;
  std::optional<Stamp> first_stamp_;
  Clock::time_point last_write_{};
  int last_tenth_ = 0;
  bool wrote_ = false;
};

}  // namespace mrslam::robot
