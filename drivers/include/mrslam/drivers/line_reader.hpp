#pragma once
// Text logs line by line, plain or gzip-compressed alike, and the field helpers the log readers
// share (whitespace splitting, strict number parsing, decimal time stamps).

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mrslam/common/stamp.hpp"

struct gzFile_s;  // zlib's file handle (gzFile); zlib itself stays out of this header

namespace mrslam::drivers {

/// Reads the lines of a plain or gzip text file (zlib tells them apart by content), of any length.
class LineReader {
 public:
  static constexpr std::size_t kUnlimited = std::numeric_limits<std::size_t>::max();

  /// Opens `path`; throws std::runtime_error("path: cannot open ...") when it cannot.
  /// Lines longer than `max_line_bytes` are cut there (see lastLineCut()).
  explicit LineReader(std::string path, std::size_t max_line_bytes = kUnlimited);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  /// The next line, without its "\n" or "\r\n", into `line`; false at the end of the file.
  /// Throws std::runtime_error("path: ...") when the file cannot be read on (e.g. a truncated
  /// gzip stream).
  bool next(std::string& line);

  /// 1-based number of the line last returned by next() (0 before the first).
  std::size_t lineNumber() const { return line_number_; }
  /// Whether the line last returned was longer than max_line_bytes and was cut.
  bool lastLineCut() const { return cut_; }
  const std::string& path() const { return path_; }
  /// Share of the file read so far (compressed bytes for a .gz file), 0…1.
  double fractionRead() const;

 private:
  bool fill();

  std::string path_;
  std::size_t max_line_bytes_;
  double file_bytes_ = 0.0;  ///< size of the file on disk
  gzFile_s* file_ = nullptr;
  std::vector<char> buffer_;
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  std::size_t line_number_ = 0;
  bool cut_ = false;
};

/// Writes `content` as a gzip file (tools and tests that make compressed logs); throws
/// std::runtime_error("path: ...") on failure.
void writeGzipFile(const std::string& path, std::string_view content);

/// Splits `line` at runs of spaces, tabs and carriage returns into `fields` (views into `line`).
void splitFields(std::string_view line, std::vector<std::string_view>& fields);

/// A whole field as a decimal integer ("-12", "+7"); nothing if any character is left over.
std::optional<std::int64_t> parseInteger(std::string_view text);

/// A whole field as a decimal number ("1.5", "-2e-3", also "nan" and "inf": the caller checks
/// finiteness); nothing if any character is left over.
std::optional<double> parseNumber(std::string_view text);

/// A time stamp in seconds written in decimal ("32.9068") or exponent form ("1.13486e+09"),
/// converted exactly (no binary floating point) to the nanosecond; nothing if not a number.
std::optional<Stamp> parseStampSeconds(std::string_view text);

}  // namespace mrslam::drivers
