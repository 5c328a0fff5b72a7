#pragma once
// Which kind of log a file holds, a reader for it, and the malformed-line handling the log
// readers share: `file:line: what is wrong`, stopped or counted as MalformedPolicy says.

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "mrslam/common/error_counter.hpp"
#include "mrslam/drivers/sample_source.hpp"

namespace mrslam::drivers {

/// A malformed log line under MalformedPolicy::kStop; what() is `path:line: problem`.
class LogFormatError : public std::runtime_error {
 public:
  LogFormatError(const std::string& path, std::size_t line, const std::string& problem);

  const std::string& path() const { return path_; }
  std::size_t line() const { return line_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string path_;
  std::size_t line_;
  std::string problem_;
};

/// What is wrong with one line: a short kind for the counters ("field count", "not a number",
/// ...) and the message.
struct LineProblem {
  std::string kind;
  std::string what;
};

/// Applies a MalformedPolicy to malformed lines: throws LogFormatError (kStop), or counts the
/// line by kind and logs it with a rate limit (kSkip).
class MalformedLineHandler {
 public:
  MalformedLineHandler(std::string component, MalformedPolicy policy);

  void handle(const std::string& path, std::size_t line, const LineProblem& problem);
  std::uint64_t count() const { return errors_.total(); }
  std::map<std::string, std::uint64_t> countsByKind() const { return errors_.counts(); }

 private:
  MalformedPolicy policy_;
  ErrorCounter errors_;
};

enum class LogFormat { kBreezySlam, kCarmen, kMrslam, kUnknown };

/// "breezyslam", "carmen", "mrslam" or "unknown".
const char* logFormatName(LogFormat format);

/// The format of a log, plain or gzip: kMrslam when its first line is kMrslamLogMagic; otherwise
/// judged by its first meaningful line (empty and '#' lines are passed over): a known CARMEN
/// message name (PARAM, ODOM, FLASER, ...) means kCarmen; a line of at least 26 numbers starting
/// with an integer time stamp means kBreezySlam; anything else kUnknown. Throws
/// std::runtime_error("path: cannot open ...") when the file cannot be read.
LogFormat detectLogFormat(const std::string& path);

/// The reader for the log at `path` with its default settings and `policy`. Throws
/// std::runtime_error when the file cannot be opened or its format is unknown.
std::unique_ptr<SampleSource> openLogReader(const std::string& path, MalformedPolicy policy);

}  // namespace mrslam::drivers
