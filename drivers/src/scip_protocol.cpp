#include "mrslam/drivers/scip_protocol.hpp"

#include <cstdio>

#include "mrslam/drivers/scip_codec.hpp"

namespace mrslam::drivers::scip {
namespace {

constexpr std::string_view kReplyEnd = "\n\n";
constexpr std::size_t kTimestampChars = 4;
constexpr std::size_t kStatusLineChars = 3;

std::string quoted(std::string_view text) {
  constexpr std::size_t kShown = 24;
  std::string shown;
  for (const char c : text.substr(0, kShown)) {
    shown += (c >= 0x20 && c < 0x7F) ? c : '?';
  }
  return "'" + shown + (text.size() > kShown ? "...'" : "'");
}

/// Splits `block` into its lines up to the first empty line; false when none ends the block.
bool splitLines(std::string_view block, std::vector<std::string_view>& lines) {
  std::size_t at = 0;
  while (at < block.size()) {
    const std::size_t end = block.find('\n', at);
    if (end == std::string_view::npos) {
      return false;
    }
    if (end == at) {
      return true;  // the empty line that ends the reply
    }
    lines.push_back(block.substr(at, end - at));
    at = end + 1;
  }
  return false;
}

Parsed<std::string> parseStatusLine(std::string_view line) {
  if (line.size() != kStatusLineChars) {
    return Parsed<std::string>::failure(
        ErrorKind::kGarbage, "status line " + quoted(line) + " is not a SCIP 2.0 status");
  }
  if (!hasValidChecksum(line)) {
    return Parsed<std::string>::failure(ErrorKind::kChecksum,
                                        "bad checksum on status line " + quoted(line));
  }
  return Parsed<std::string>::success(std::string(line.substr(0, 2)));
}

Parsed<std::string> parseDataLine(std::string_view line, LineCheck check) {
  if (line.size() < 2 || (check == LineCheck::kData && line.size() > kMaxDataLineChars + 1)) {
    return Parsed<std::string>::failure(
        ErrorKind::kGarbage,
        "data line of " + std::to_string(line.size()) + " chars: " + quoted(line));
  }
  const bool valid =
      check == LineCheck::kData ? hasValidChecksum(line) : hasValidKeyValueChecksum(line);
  if (!valid) {
    return Parsed<std::string>::failure(ErrorKind::kChecksum,
                                        "bad checksum on data line " + quoted(line));
  }
  return Parsed<std::string>::success(std::string(line.substr(0, line.size() - 1)));
}

bool isDigits(std::string_view text) {
  for (const char c : text) {
    if (c < '0' || c > '9') {
      return false;
    }
  }
  return !text.empty();
}

/// Checks the echo of a scan reply; MD/MS echoes end with the remaining count.
Parsed<std::optional<int>> checkScanEcho(std::string_view echo, const ScanRequest& request) {
  const std::string prefix = request.echoPrefix();
  const std::size_t count_chars = request.continuous() ? 2 : 0;
  const std::string_view count = echo.substr(std::min(echo.size(), prefix.size()));
  if (echo.substr(0, prefix.size()) != prefix || count.size() != count_chars ||
      (count_chars > 0 && !isDigits(count))) {
    return Parsed<std::optional<int>>::failure(
        ErrorKind::kGarbage,
        "echo " + quoted(echo) + " does not match request " + quoted(request.text()));
  }
  if (count_chars == 0) {
    return Parsed<std::optional<int>>::success(std::nullopt);
  }
  return Parsed<std::optional<int>>::success((count[0] - '0') * 10 + (count[1] - '0'));
}

/// Joins the value lines of a scan; every line but the last must be full (64 chars).
Parsed<std::string> joinValueLines(const std::vector<std::string>& data, std::size_t expected) {
  std::string joined;
  joined.reserve(expected);
  for (std::size_t i = 1; i < data.size(); ++i) {
    if (i + 1 < data.size() && data[i].size() != kMaxDataLineChars) {
      return Parsed<std::string>::failure(ErrorKind::kTruncated,
                                          "scan data line " + std::to_string(i) + " has only " +
                                              std::to_string(data[i].size()) + " chars");
    }
    joined += data[i];
  }
  if (joined.size() < expected) {
    return Parsed<std::string>::failure(ErrorKind::kTruncated,
                                        "scan data has " + std::to_string(joined.size()) +
                                            " chars, expected " + std::to_string(expected));
  }
  if (joined.size() > expected) {
    return Parsed<std::string>::failure(ErrorKind::kGarbage,
                                        "scan data has " + std::to_string(joined.size()) +
                                            " chars, expected " + std::to_string(expected));
  }
  return Parsed<std::string>::success(std::move(joined));
}

}  // namespace

const char* errorKindName(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::kChecksum:
      return "checksum";
    case ErrorKind::kTruncated:
      return "truncated";
    case ErrorKind::kStatus:
      return "status";
    case ErrorKind::kGarbage:
      break;
  }
  return "garbage";
}

Parsed<Reply> parseReply(std::string_view block, LineCheck check) {
  std::vector<std::string_view> lines;
  if (!splitLines(block, lines)) {
    return Parsed<Reply>::failure(ErrorKind::kTruncated, "reply does not end with an empty line");
  }
  if (lines.size() < 2) {
    return Parsed<Reply>::failure(ErrorKind::kTruncated,
                                  "reply " + quoted(block) + " has no status line");
  }
  auto status = parseStatusLine(lines[1]);
  if (!status) {
    return Parsed<Reply>::failure(status.error(), status.reason());
  }
  Reply reply;
  reply.echo = std::string(lines[0]);
  reply.status = std::move(status.value());
  reply.data.reserve(lines.size() - 2);
  for (std::size_t i = 2; i < lines.size(); ++i) {
    auto line = parseDataLine(lines[i], check);
    if (!line) {
      return Parsed<Reply>::failure(line.error(), line.reason());
    }
    reply.data.push_back(std::move(line.value()));
  }
  return Parsed<Reply>::success(std::move(reply));
}

std::size_t findEcho(std::string_view block, std::string_view echo_prefix) {
  return echo_prefix.empty() ? std::string_view::npos : block.find(echo_prefix);
}

std::size_t ScanRequest::valueCount() const {
  if (end_step < start_step || cluster < 1) {
    return 0;
  }
  const int steps = end_step - start_step + 1;
  return static_cast<std::size_t>((steps + cluster - 1) / cluster);
}

std::string ScanRequest::text() const {
  char text[32];
  if (continuous()) {
    std::snprintf(text, sizeof(text), "%.2s%04d%04d%02d%01d%02d", command.c_str(), start_step,
                  end_step, cluster, interval, count);
  } else {
    std::snprintf(text, sizeof(text), "%.2s%04d%04d%02d", command.c_str(), start_step, end_step,
                  cluster);
  }
  return text;
}

std::string ScanRequest::echoPrefix() const {
  std::string line = text();
  return continuous() ? line.substr(0, line.size() - 2) : line;
}

Parsed<ScanData> decodeScanReply(const Reply& reply, const ScanRequest& request) {
  auto remaining = checkScanEcho(reply.echo, request);
  if (!remaining) {
    return Parsed<ScanData>::failure(remaining.error(), remaining.reason());
  }
  const char* wanted = request.continuous() ? "99" : "00";
  if (reply.status != wanted) {
    return Parsed<ScanData>::failure(ErrorKind::kStatus,
                                     request.command + " status " + reply.status + ": " +
                                         statusText(request.command, reply.status));
  }
  if (reply.data.empty() || reply.data[0].size() != kTimestampChars) {
    return Parsed<ScanData>::failure(ErrorKind::kTruncated, "scan reply has no time stamp");
  }
  const std::size_t width = static_cast<std::size_t>(request.valueChars());
  auto joined = joinValueLines(reply.data, request.valueCount() * width);
  if (!joined) {
    return Parsed<ScanData>::failure(joined.error(), joined.reason());
  }
  ScanData scan;
  scan.remaining_scans = remaining.value();
  const auto stamp = decode(reply.data[0]);
  if (!stamp || !decodeValues(joined.value(), request.valueChars(), scan.ranges_mm)) {
    return Parsed<ScanData>::failure(ErrorKind::kGarbage, "scan data has invalid chars");
  }
  scan.timestamp_ms = *stamp;
  return Parsed<ScanData>::success(std::move(scan));
}

Parsed<KeyValues> parseKeyValues(const Reply& reply) {
  KeyValues values;
  for (const std::string& line : reply.data) {
    std::string_view text = line;
    if (!text.empty() && text.back() == ';') {
      text.remove_suffix(1);
    }
    const std::size_t colon = text.find(':');
    if (colon == 0 || colon == std::string_view::npos) {
      return Parsed<KeyValues>::failure(ErrorKind::kGarbage,
                                        "line " + quoted(line) + " is not KEY:value");
    }
    values[std::string(text.substr(0, colon))] = std::string(text.substr(colon + 1));
  }
  return Parsed<KeyValues>::success(std::move(values));
}

std::string formatReply(std::string_view echo, std::string_view status,
                        const std::vector<std::string>& data_lines) {
  std::string text;
  text.reserve(echo.size() + 8 + data_lines.size() * (kMaxDataLineChars + 2));
  text.append(echo).push_back('\n');
  text.append(withChecksum(status)).push_back('\n');
  for (const std::string& line : data_lines) {
    text.append(line).push_back('\n');
  }
  text.push_back('\n');
  return text;
}

std::string keyValueLine(std::string_view key, std::string_view value) {
  std::string line(key);
  line.push_back(':');
  line.append(value);
  const char sum = checksum(line);
  line.push_back(';');
  line.push_back(sum);
  return line;
}

std::vector<std::string> scanDataLines(std::uint32_t timestamp_ms,
                                       const std::vector<std::uint32_t>& values, int width) {
  std::string encoded;
  encoded.reserve(values.size() * static_cast<std::size_t>(width));
  for (const std::uint32_t value : values) {
    encoded += encode(value, width);
  }
  std::vector<std::string> lines;
  lines.reserve(2 + encoded.size() / kMaxDataLineChars);
  lines.push_back(withChecksum(encode(timestamp_ms, static_cast<int>(kTimestampChars))));
  for (std::size_t at = 0; at < encoded.size(); at += kMaxDataLineChars) {
    lines.push_back(withChecksum(std::string_view(encoded).substr(at, kMaxDataLineChars)));
  }
  return lines;
}

void ReplyFramer::append(const char* bytes, std::size_t size) {
  buffer_.append(bytes, size);
}

std::optional<std::string> ReplyFramer::next() {
  const std::size_t leading_lfs = buffer_.find_first_not_of('\n');
  if (leading_lfs == std::string::npos) {
    buffer_.clear();
    searched_ = 0;
    return std::nullopt;
  }
  if (leading_lfs > 0) {
    buffer_.erase(0, leading_lfs);
    searched_ = searched_ > leading_lfs ? searched_ - leading_lfs : 0;
  }
  const std::size_t end = buffer_.find(kReplyEnd, searched_ > 0 ? searched_ - 1 : 0);
  if (end != std::string::npos) {
    std::string block = buffer_.substr(0, end + kReplyEnd.size());
    buffer_.erase(0, end + kReplyEnd.size());
    searched_ = 0;
    return block;
  }
  searched_ = buffer_.size();
  if (buffer_.size() > max_buffered_) {
    dropped_bytes_ += buffer_.size();
    buffer_.clear();
    searched_ = 0;
  }
  return std::nullopt;
}

void ReplyFramer::clear() {
  buffer_.clear();
  searched_ = 0;
}

}  // namespace mrslam::drivers::scip
