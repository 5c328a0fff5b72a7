#pragma once
// Shared by the log reader fuzz targets: the input becomes a log file that a reader reads to
// the end under both malformed-line policies. Only LogFormatError may escape (policy stop).

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "mrslam/drivers/log_format.hpp"

namespace mrslam::fuzz {

/// A per-process scratch file for the input.
inline const std::string& scratchLogPath() {
  static const std::string path =
      "/tmp/mrslam-fuzz-" + std::to_string(static_cast<long>(getpid())) + ".log";
  return path;
}

template <class Reader, class Settings>
void readWholeLog(const std::uint8_t* data, std::size_t size) {
  const std::string& path = scratchLogPath();
  {
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (file == nullptr) {
      return;
    }
    std::fwrite(data, 1, size, file);
    std::fclose(file);
  }
  for (const auto policy : {drivers::MalformedPolicy::kSkip, drivers::MalformedPolicy::kStop}) {
    Settings settings;
    settings.path = path;
    settings.malformed_policy = policy;
    try {
      Reader reader(settings);
      while (reader.next()) {
      }
    } catch (const drivers::LogFormatError&) {
      // A malformed line under the stop policy: the expected outcome.
    }
  }
}

}  // namespace mrslam::fuzz
