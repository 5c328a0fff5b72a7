#pragma once
// Counting bad input: every problem of a kind is counted; the first is logged, and later ones
// at most once per `log_interval` so a flood of corrupt frames cannot flood the log.

#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

namespace mrslam {

class ErrorCounter {
 public:
  explicit ErrorCounter(std::string component,
                        std::chrono::steady_clock::duration log_interval = std::chrono::seconds(5));

  /// Counts one problem of `kind` and logs `message` (rate-limited per kind) as a warning.
  void report(const std::string& kind, const std::string& message);

  std::uint64_t count(const std::string& kind) const;
  std::uint64_t total() const;
  /// Every kind with its count.
  std::map<std::string, std::uint64_t> counts() const;

 private:
  struct Kind {
    std::uint64_t count = 0;
    std::uint64_t count_at_last_log = 0;
    std::chrono::steady_clock::time_point last_log{};
  };

  std::string component_;
  std::chrono::steady_clock::duration log_interval_;
  mutable std::mutex mutex_;
  std::map<std::string, Kind> kinds_;
};

}  // namespace mrslam
