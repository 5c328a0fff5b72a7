#pragma once
// SCIP 2.0 replies: framing a byte stream into replies, splitting a reply into echo, status and
// verified data lines, key:value parameters (VV, PP, II) and scan data (MD/MS/GD/GS).
// Pure functions, no I/O.
//
// A reply is: echo of the request LF, status (2 chars + sum) LF, data lines (each ending in a
// sum char) LF, and an empty line: it ends with LF LF. A scan reply's first data line is the
// 24-bit time stamp (4 chars); then the values, at most 64 chars a line, a value possibly split
// across two lines.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mrslam::drivers::scip {

/// What was wrong with a reply; names the driver's error counters.
enum class ErrorKind {
  kChecksum,   ///< a line's sum char does not match
  kTruncated,  ///< lines or values missing
  kStatus,     ///< the device reported an error status
  kGarbage,    ///< not a reply to what was asked (bad echo, bad chars, SCIP 1.1, noise)
};

/// "checksum", "truncated", "status" or "garbage".
const char* errorKindName(ErrorKind kind);

/// A parsed value, or what kind of problem prevented it and why.
template <class T>
class Parsed {
 public:
  static Parsed success(T value) { return Parsed(std::move(value), ErrorKind::kGarbage, {}); }
  static Parsed failure(ErrorKind kind, std::string reason) {
    return Parsed(std::nullopt, kind, std::move(reason));
  }

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  const T& value() const { return *value_; }
  T& value() { return *value_; }
  ErrorKind error() const { return error_; }
  const std::string& reason() const { return reason_; }

 private:
  Parsed(std::optional<T> value, ErrorKind error, std::string reason)
      : value_(std::move(value)), error_(error), reason_(std::move(reason)) {}

  std::optional<T> value_;
  ErrorKind error_;
  std::string reason_;
};

/// One reply, its lines verified.
struct Reply {
  std::string echo;               ///< the request line as the device echoed it
  std::string status;             ///< two chars: "00" OK, "99" scan data, others errors
  std::vector<std::string> data;  ///< data lines without their sum chars
};

/// How data lines are summed.
enum class LineCheck {
  kData,      ///< sum over every byte before the sum char; at most 64 chars + sum
  kKeyValue,  ///< `KEY:value;S`: with or without the ';' (see hasValidKeyValueChecksum)
};

/// Splits one reply block (as ReplyFramer::next() returns it) and verifies its lines.
Parsed<Reply> parseReply(std::string_view block, LineCheck check);

/// The first occurrence of `echo_prefix` at which a reply may start (block start, after a LF,
/// or glued to noise before it); npos when absent.
std::size_t findEcho(std::string_view block, std::string_view echo_prefix);

/// A scan command: MD/MS (continuous) or GD/GS (one scan).
struct ScanRequest {
  std::string command = "MD";  ///< "MD", "MS", "GD" or "GS"
  int start_step = 0;
  int end_step = 0;
  int cluster = 1;   ///< adjacent steps merged into one value (1…99)
  int interval = 0;  ///< MD/MS: scans skipped between two sent (0…9)
  int count = 0;     ///< MD/MS: scans to send (0 = until QT; 0…99)

  bool continuous() const { return command == "MD" || command == "MS"; }
  /// Chars a value takes: 3 for MD/GD, 2 for MS/GS.
  int valueChars() const { return command[1] == 'D' ? 3 : 2; }
  /// Values a scan of this request carries.
  std::size_t valueCount() const;
  /// The request line without LF, e.g. "MD0044072501000".
  std::string text() const;
  /// What every echo of this request starts with (MD/MS echoes carry the remaining count).
  std::string echoPrefix() const;
};

/// The decoded data of one scan reply.
struct ScanData {
  std::uint32_t timestamp_ms = 0;        ///< the sensor's 24-bit millisecond counter
  std::vector<std::uint32_t> ranges_mm;  ///< raw values: < DMIN are error codes
  std::optional<int> remaining_scans;    ///< MD/MS: the count in the echo
};

/// Decodes the scan in `reply` for `request`: echo, status ("99" for MD/MS, "00" for GD/GS),
/// time stamp, exactly request.valueCount() values.
Parsed<ScanData> decodeScanReply(const Reply& reply, const ScanRequest& request);

using KeyValues = std::map<std::string, std::string>;

/// The `KEY:value` lines of a VV, PP or II reply (parsed with LineCheck::kKeyValue).
Parsed<KeyValues> parseKeyValues(const Reply& reply);

// ---- Writing replies (the emulator, tests, benchmarks) ----

/// A whole reply: echo LF, status + sum LF, each data line LF, LF. `data_lines` already carry
/// their sum chars.
std::string formatReply(std::string_view echo, std::string_view status,
                        const std::vector<std::string>& data_lines);

/// `KEY:value;S` with the sum over `KEY:value` (the specification's convention).
std::string keyValueLine(std::string_view key, std::string_view value);

/// The data lines of a scan: the 4-char time stamp, then the values (`width` chars each) cut
/// into lines of 64 chars; each line with its sum char.
std::vector<std::string> scanDataLines(std::uint32_t timestamp_ms,
                                       const std::vector<std::uint32_t>& values, int width);

/// Cuts a byte stream into reply blocks ending in LF LF. Leading LFs are skipped; a stream that
/// runs on for `max_buffered` bytes without a reply end is dropped (counted as dropped bytes).
class ReplyFramer {
 public:
  explicit ReplyFramer(std::size_t max_buffered = 64 * 1024) : max_buffered_(max_buffered) {}

  void append(const char* bytes, std::size_t size);
  /// The next complete block (through its LF LF), or nothing yet.
  std::optional<std::string> next();
  void clear();
  std::size_t pendingBytes() const { return buffer_.size(); }
  std::uint64_t droppedBytes() const { return dropped_bytes_; }

 private:
  std::size_t max_buffered_;
  std::string buffer_;
  std::size_t searched_ = 0;  ///< bytes already searched for the end of a block
  std::uint64_t dropped_bytes_ = 0;
};

}  // namespace mrslam::drivers::scip
