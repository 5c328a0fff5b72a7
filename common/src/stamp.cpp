#include "mrslam/common/stamp.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace mrslam {

Stamp Stamp::fromSeconds(double seconds) {
  return Stamp{static_cast<std::int64_t>(std::llround(seconds * 1e9))};
}

std::optional<Stamp> Stamp::parseSeconds(std::string_view text) {
  std::size_t i = 0;
  bool negative = false;
  if (i < text.size() && (text[i] == '-' || text[i] == '+')) {
    negative = text[i] == '-';
    ++i;
  }
  constexpr std::int64_t kMaxWholeSeconds =
      std::numeric_limits<std::int64_t>::max() / 1000000000 - 1;
  std::int64_t whole = 0;
  std::size_t whole_digits = 0;
  for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i, ++whole_digits) {
    whole = whole * 10 + (text[i] - '0');
    if (whole > kMaxWholeSeconds) {
      return std::nullopt;
    }
  }
  std::int64_t fraction_ns = 0;
  std::size_t fraction_digits = 0;
  if (i < text.size() && text[i] == '.') {
    ++i;
    std::int64_t scale = 100000000;
    for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i, ++fraction_digits) {
      fraction_ns += (text[i] - '0') * scale;
      scale /= 10;
    }
  }
  if (i != text.size() || whole_digits + fraction_digits == 0) {
    return std::nullopt;
  }
  const std::int64_t ns = whole * 1000000000 + fraction_ns;
  return Stamp{negative ? -ns : ns};
}

std::string Stamp::toString() const {
  const std::int64_t magnitude = ns < 0 ? -ns : ns;
  char buffer[48];
  std::snprintf(buffer, sizeof(buffer), "%s%lld.%09lld", ns < 0 ? "-" : "",
                static_cast<long long>(magnitude / 1000000000),
                static_cast<long long>(magnitude % 1000000000));
  return buffer;
}

}  // namespace mrslam
