#include "mrslam/common/config_keys.hpp"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace mrslam {

namespace {

std::atomic<ConfigKeyLog*> active_log{nullptr};

// "robots[2].id" -> "robots[].id"
std::string listPattern(const std::string& key) {
  std::string pattern;
  std::size_t at = 0;
  while (at < key.size()) {
    if (key[at] == '[') {
      const std::size_t close = key.find(']', at);
      if (close != std::string::npos) {
        pattern += "[]";
        at = close + 1;
        continue;
      }
    }
    pattern += key[at++];
  }
  return pattern;
}

}  // namespace

const char* configKeyKindName(ConfigKeyKind kind) {
  switch (kind) {
    case ConfigKeyKind::kNumber:
      return "number";
    case ConfigKeyKind::kInteger:
      return "integer";
    case ConfigKeyKind::kBool:
      return "bool";
    case ConfigKeyKind::kString:
      return "string";
    case ConfigKeyKind::kChoice:
      return "choice";
    case ConfigKeyKind::kNumbers:
      return "numbers";
    case ConfigKeyKind::kPath:
      return "path";
    case ConfigKeyKind::kSection:
      return "section";
    case ConfigKeyKind::kSectionList:
      return "section list";
  }
  return "unknown";
}

ConfigKeyLog::ConfigKeyLog() {
  ConfigKeyLog* expected = nullptr;
  if (!active_log.compare_exchange_strong(expected, this)) {
    throw std::logic_error("ConfigKeyLog: another log is already recording");
  }
}

ConfigKeyLog::~ConfigKeyLog() {
  active_log.store(nullptr);
}

std::vector<ConfigKeyUse> ConfigKeyLog::uses() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return uses_;
}

void ConfigKeyLog::clear() {
  const std::lock_guard<std::mutex> lock(mutex_);
  uses_.clear();
}

bool ConfigKeyLog::recording() {
  return active_log.load(std::memory_order_relaxed) != nullptr;
}

void ConfigKeyLog::record(ConfigKeyUse use) {
  ConfigKeyLog* log = active_log.load();
  if (log == nullptr) {
    return;
  }
  use.key = listPattern(use.key);
  const std::lock_guard<std::mutex> lock(log->mutex_);
  log->uses_.push_back(std::move(use));
}

std::string yamlNumber(double value) {
  if (std::isnan(value)) {
    return ".nan";
  }
  if (std::isinf(value)) {
    return value > 0 ? ".inf" : "-.inf";
  }
  if (value == 0.0) {
    return "0";  // also -0
  }
  const double magnitude = std::fabs(value);
  const bool fixed = magnitude >= 1e-4 && magnitude < 1e15;
  const std::chars_format format = fixed ? std::chars_format::fixed : std::chars_format::scientific;
  char buffer[400];
  std::to_chars_result result{};
  if (magnitude <= std::numeric_limits<float>::max() &&
      static_cast<double>(static_cast<float>(value)) == value) {
    // A default held in a float (0.85f) reads as written: 0.85, not 0.850000023841858.
    result = std::to_chars(buffer, buffer + sizeof buffer, static_cast<float>(value), format);
  } else {
    // Rounded to 15 digits: a default computed as 0.5 degrees from radians reads 0.5.
    std::snprintf(buffer, sizeof buffer, "%.15g", value);
    result = std::to_chars(buffer, buffer + sizeof buffer, std::strtod(buffer, nullptr), format);
  }
  const std::string text(buffer, result.ptr);
  if (fixed) {
    return text;
  }
  // 1e-06 -> 1e-6, 9e+15 -> 9e15
  const std::size_t e = text.find('e');
  std::string exponent = text.substr(e + 1);
  std::string sign;
  if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) {
    sign = exponent[0] == '-' ? "-" : "";
    exponent.erase(0, 1);
  }
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return text.substr(0, e) + "e" + sign + exponent;
}

std::string yamlString(const std::string& text) {
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      quoted += '\\';
    }
    quoted += c;
  }
  return quoted + "\"";
}

std::string yamlNumbers(const std::vector<double>& values) {
  std::string text = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    text += (i == 0 ? "" : ", ") + yamlNumber(values[i]);
  }
  return text + "]";
}

}  // namespace mrslam
