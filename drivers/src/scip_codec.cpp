#include "mrslam/drivers/scip_codec.hpp"

#include <stdexcept>

namespace mrslam::drivers::scip {
namespace {

constexpr char kCharOffset = 0x30;
constexpr std::uint32_t kSixBits = 0x3F;

bool isScanCommand(std::string_view command) {
  return command == "MD" || command == "MS" || command == "GD" || command == "GS";
}

/// Errors any command can report (specification: common status codes).
std::optional<std::string> commonStatusText(std::string_view status) {
  static const struct {
    const char* code;
    const char* text;
  } kCommon[] = {
      {"0A", "cannot create the reply internally"},
      {"0B", "buffer shortage, or a command repeated that is being processed"},
      {"0C", "command with insufficient parameters"},
      {"0D", "undefined command"},
      {"0E", "undefined command"},
      {"0F", "command with insufficient parameters"},
      {"0G", "command string longer than 16 characters"},
      {"0H", "command string has invalid characters"},
      {"0I", "sensor is in firmware update mode"},
  };
  for (const auto& entry : kCommon) {
    if (status == entry.code) {
      return std::string(entry.text);
    }
  }
  return std::nullopt;
}

std::optional<std::string> scanStatusText(std::string_view status) {
  static const char* const kParameterErrors[] = {
      "start step is not a number",       "end step is not a number",
      "cluster count is not a number",    "end step is out of range",
      "end step is below the start step", "scan interval is not a number",
      "number of scans is not a number",
  };
  if (status.size() == 2 && status[0] == '0' && status[1] >= '1' && status[1] <= '7') {
    return "parameter error: " + std::string(kParameterErrors[status[1] - '1']);
  }
  if (status == "10") {
    return std::string("laser is off");
  }
  return std::nullopt;
}

std::optional<int> twoDigitNumber(std::string_view status) {
  if (status.size() != 2 || status[0] < '0' || status[0] > '9' || status[1] < '0' ||
      status[1] > '9') {
    return std::nullopt;
  }
  return (status[0] - '0') * 10 + (status[1] - '0');
}

}  // namespace

char checksum(std::string_view bytes) {
  std::uint32_t sum = 0;
  for (const char c : bytes) {
    sum += static_cast<std::uint8_t>(c);
  }
  return static_cast<char>((sum & kSixBits) + kCharOffset);
}

bool hasValidChecksum(std::string_view line) {
  return line.size() >= 2 && checksum(line.substr(0, line.size() - 1)) == line.back();
}

bool hasValidKeyValueChecksum(std::string_view line) {
  if (hasValidChecksum(line)) {
    return true;
  }
  // The specification's convention: the ';' before the sum char is not summed.
  return line.size() >= 3 && line[line.size() - 2] == ';' &&
         checksum(line.substr(0, line.size() - 2)) == line.back();
}

std::string withChecksum(std::string_view line) {
  std::string text(line);
  text.push_back(checksum(line));
  return text;
}

std::string encode(std::uint32_t value, int chars) {
  if (chars < 1 || chars > 4 || (value >> (6 * chars)) != 0) {
    throw std::invalid_argument("SCIP encode: " + std::to_string(value) + " does not fit in " +
                                std::to_string(chars) + " chars");
  }
  std::string text(static_cast<std::size_t>(chars), '0');
  for (int i = chars - 1; i >= 0; --i) {
    text[static_cast<std::size_t>(i)] = static_cast<char>((value & kSixBits) + kCharOffset);
    value >>= 6;
  }
  return text;
}

std::optional<std::uint32_t> decode(std::string_view chars) {
  if (chars.empty() || chars.size() > 4) {
    return std::nullopt;
  }
  std::uint32_t value = 0;
  for (const char c : chars) {
    const auto group = static_cast<std::uint32_t>(static_cast<std::uint8_t>(c)) - kCharOffset;
    if (group > kSixBits) {  // also catches chars below 0x30 (unsigned wrap-around)
      return std::nullopt;
    }
    value = (value << 6) | group;
  }
  return value;
}

bool decodeValues(std::string_view chars, int width, std::vector<std::uint32_t>& values) {
  const auto step = static_cast<std::size_t>(width);
  if (width < 1 || width > 4 || chars.size() % step != 0) {
    return false;
  }
  const std::size_t first_new = values.size();
  values.reserve(first_new + chars.size() / step);
  for (std::size_t at = 0; at < chars.size(); at += step) {
    const auto value = decode(chars.substr(at, step));
    if (!value) {
      values.resize(first_new);
      return false;
    }
    values.push_back(*value);
  }
  return true;
}

std::string statusText(std::string_view command, std::string_view status) {
  if (status == "00") {
    return "OK";
  }
  if (status == "99") {
    return "scan data follows";
  }
  if (command == "BM" && status == "01") {
    return "laser malfunction";
  }
  if (command == "BM" && status == "02") {
    return "laser already on";
  }
  if (isScanCommand(command)) {
    if (auto text = scanStatusText(status)) {
      return *text;
    }
  }
  const auto number = twoDigitNumber(status);
  if (number && *number >= 50 && *number <= 97) {
    return "hardware fault (status " + std::string(status) + ")";
  }
  if (auto text = commonStatusText(status)) {
    return *text;
  }
  return "unknown status " + std::string(status);
}

bool isSuccessStatus(std::string_view command, std::string_view status) {
  return status == "00" || status == "99" || (command == "BM" && status == "02");
}

}  // namespace mrslam::drivers::scip
