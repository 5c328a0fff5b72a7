#include "mrslam/drivers/line_reader.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace mrslam::drivers {
namespace {

constexpr std::size_t kChunkBytes = 64 * 1024;

std::string zlibError(gzFile file) {
  int code = Z_OK;
  const char* message = gzerror(file, &code);
  return message != nullptr && *message != '\0' ? message : "unknown zlib error";
}

/// Drops one leading '+' (std::from_chars accepts only '-').
std::string_view withoutPlus(std::string_view text) {
  if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+') {
    text.remove_prefix(1);
  }
  return text;
}

bool allDigits(std::string_view text) {
  for (const char c : text) {
    if (c < '0' || c > '9') {
      return false;
    }
  }
  return true;
}

}  // namespace

LineReader::LineReader(std::string path, std::size_t max_line_bytes)
    : path_(std::move(path)), max_line_bytes_(max_line_bytes), buffer_(kChunkBytes) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path_, ignored)) {
    throw std::runtime_error(path_ + ": cannot open (it is a folder)");
  }
  errno = 0;
  file_ = gzopen(path_.c_str(), "rb");
  if (file_ == nullptr) {
    const std::string reason = errno != 0 ? std::strerror(errno) : "out of memory";
    throw std::runtime_error(path_ + ": cannot open (" + reason + ")");
  }
  gzbuffer(file_, 128 * 1024);
  file_bytes_ = static_cast<double>(std::filesystem::file_size(path_, ignored));
}

double LineReader::fractionRead() const {
  if (file_bytes_ <= 0.0) {
    return 0.0;
  }
  const double offset = static_cast<double>(gzoffset(file_));
  return offset < 0.0 ? 0.0 : std::min(1.0, offset / file_bytes_);
}

LineReader::~LineReader() {
  if (file_ != nullptr) {
    gzclose(file_);
  }
}

bool LineReader::fill() {
  const int got = gzread(file_, buffer_.data(), static_cast<unsigned>(buffer_.size()));
  if (got < 0) {
    throw std::runtime_error(path_ + ": read error after line " + std::to_string(line_number_) +
                             ": " + zlibError(file_));
  }
  if (got == 0) {
    int code = Z_OK;
    gzerror(file_, &code);
    if (code != Z_OK) {  // Z_BUF_ERROR: the gzip stream ends in the middle
      throw std::runtime_error(path_ + ": read error after line " + std::to_string(line_number_) +
                               ": " + zlibError(file_));
    }
    return false;
  }
  begin_ = 0;
  end_ = static_cast<std::size_t>(got);
  return true;
}

bool LineReader::next(std::string& line) {
  line.clear();
  cut_ = false;
  bool any = false;
  for (;;) {
    if (begin_ == end_ && !fill()) {
      if (!any) {
        return false;
      }
      break;  // the last line has no end of line
    }
    any = true;
    const char* start = buffer_.data() + begin_;
    const auto* newline = static_cast<const char*>(std::memchr(start, '\n', end_ - begin_));
    const std::size_t length =
        newline != nullptr ? static_cast<std::size_t>(newline - start) : end_ - begin_;
    const std::size_t room = max_line_bytes_ - line.size();
    if (length > room) {
      cut_ = true;
    }
    line.append(start, length < room ? length : room);
    begin_ += length;
    if (newline != nullptr) {
      ++begin_;
      break;
    }
  }
  if (!line.empty() && line.back() == '\r' && !cut_) {
    line.pop_back();
  }
  ++line_number_;
  return true;
}

void writeGzipFile(const std::string& path, std::string_view content) {
  gzFile file = gzopen(path.c_str(), "wb");
  if (file == nullptr) {
    throw std::runtime_error(path + ": cannot open for writing");
  }
  while (!content.empty()) {
    const auto chunk =
        static_cast<unsigned>(content.size() < kChunkBytes ? content.size() : kChunkBytes);
    if (gzwrite(file, content.data(), chunk) != static_cast<int>(chunk)) {
      const std::string reason = zlibError(file);
      gzclose(file);
      throw std::runtime_error(path + ": write error: " + reason);
    }
    content.remove_prefix(chunk);
  }
  if (gzclose(file) != Z_OK) {
    throw std::runtime_error(path + ": write error on close");
  }
}

void splitFields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) {
      ++i;
    }
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') {
      ++i;
    }
    if (i > start) {
      fields.push_back(line.substr(start, i - start));
    }
  }
}

std::optional<std::int64_t> parseInteger(std::string_view text) {
  text = withoutPlus(text);
  std::int64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    return std::nullopt;
  }
  return value;
}

std::optional<double> parseNumber(std::string_view text) {
  text = withoutPlus(text);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || (error != std::errc() && error != std::errc::result_out_of_range) ||
      end != text.data() + text.size()) {
    return std::nullopt;
  }
  if (error == std::errc::result_out_of_range) {
    // A number all the same (1e400, 1e-400): strtod gives its infinity or zero.
    return std::strtod(std::string(text).c_str(), nullptr);
  }
  return value;
}

std::optional<Stamp> parseStampSeconds(std::string_view text) {
  const std::size_t e = text.find_first_of("eE");
  if (e == std::string_view::npos) {
    return Stamp::parseSeconds(text);
  }
  // Rewrite "d.ddde±x" as a plain decimal and let Stamp parse that exactly.
  const std::optional<std::int64_t> exponent = parseInteger(text.substr(e + 1));
  std::string_view mantissa = text.substr(0, e);
  std::string sign;
  if (!mantissa.empty() && (mantissa[0] == '-' || mantissa[0] == '+')) {
    sign = mantissa[0] == '-' ? "-" : "";
    mantissa.remove_prefix(1);
  }
  const std::size_t dot = mantissa.find('.');
  const std::string_view whole = mantissa.substr(0, dot);
  const std::string_view fraction =
      dot == std::string_view::npos ? std::string_view() : mantissa.substr(dot + 1);
  if (!exponent || whole.size() + fraction.size() == 0 || !allDigits(whole) ||
      !allDigits(fraction)) {
    return std::nullopt;
  }
  constexpr std::int64_t kMaxShift = 64;  // far beyond both ends of Stamp's range
  if (*exponent > kMaxShift) {
    return std::nullopt;
  }
  if (*exponent < -kMaxShift) {
    return Stamp{0};  // below a nanosecond
  }
  const std::string digits = std::string(whole) + std::string(fraction);
  const std::int64_t point = static_cast<std::int64_t>(whole.size()) + *exponent;
  std::string plain = sign;
  if (point <= 0) {
    plain += "0.";
    plain.append(static_cast<std::size_t>(-point), '0');
    plain += digits;
  } else if (static_cast<std::size_t>(point) >= digits.size()) {
    plain += digits;
    plain.append(static_cast<std::size_t>(point) - digits.size(), '0');
  } else {
    plain += digits.substr(0, static_cast<std::size_t>(point));
    plain += '.';
    plain += digits.substr(static_cast<std::size_t>(point));
  }
  return Stamp::parseSeconds(plain);
}

}  // namespace mrslam::drivers
