#include "mrslam/common/error_counter.hpp"

#include <spdlog/spdlog.h>

namespace mrslam {

ErrorCounter::ErrorCounter(std::string component, std::chrono::steady_clock::duration log_interval)
    : component_(std::move(component)), log_interval_(log_interval) {}

void ErrorCounter::report(const std::string& kind, const std::string& message) {
  std::uint64_t suppressed = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    Kind& entry = kinds_[kind];
    ++entry.count;
    const auto now = std::chrono::steady_clock::now();
    const bool first = entry.count == 1;
    if (!first && now - entry.last_log < log_interval_) {
      return;
    }
    suppressed = entry.count - entry.count_at_last_log - 1;
    entry.count_at_last_log = entry.count;
    entry.last_log = now;
  }
  if (suppressed > 0) {
    spdlog::warn("{}: {} ({} more '{}' since the last report)", component_, message, suppressed,
                 kind);
  } else {
    spdlog::warn("{}: {}", component_, message);
  }
}

std::uint64_t ErrorCounter::count(const std::string& kind) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto found = kinds_.find(kind);
  return found == kinds_.end() ? 0 : found->second.count;
}

std::uint64_t ErrorCounter::total() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::uint64_t sum = 0;
  for (const auto& entry : kinds_) {
    sum += entry.second.count;
  }
  return sum;
}

std::map<std::string, std::uint64_t> ErrorCounter::counts() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::map<std::string, std::uint64_t> result;
  for (const auto& entry : kinds_) {
    result[entry.first] = entry.second.count;
  }
  return result;
}

}  // namespace mrslam
