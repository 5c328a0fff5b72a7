#pragma once
// Sensor time stamps: integer nanoseconds, so log time stamps keep their full precision.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace mrslam {

/// A point in time in nanoseconds (since the Unix epoch for live data, or the log's own clock).
struct Stamp {
  std::int64_t ns = 0;

  static Stamp fromNanoseconds(std::int64_t ns) { return Stamp{ns}; }
  static Stamp fromMicroseconds(std::int64_t us) { return Stamp{us * 1000}; }
  static Stamp fromSeconds(double seconds);
  /// Parses a decimal number of seconds ("1234.5678", "-3", "12.") exactly, to the nanosecond
  /// (digits beyond the ninth decimal are dropped). Returns nothing when the text is not a number.
  static std::optional<Stamp> parseSeconds(std::string_view text);

  double seconds() const { return static_cast<double>(ns) * 1e-9; }
  /// Seconds with nine decimals, e.g. "1234.567800000".
  std::string toString() const;

  friend bool operator<(Stamp a, Stamp b) { return a.ns < b.ns; }
  friend bool operator<=(Stamp a, Stamp b) { return a.ns <= b.ns; }
  friend bool operator>(Stamp a, Stamp b) { return a.ns > b.ns; }
  friend bool operator>=(Stamp a, Stamp b) { return a.ns >= b.ns; }
  friend bool operator==(Stamp a, Stamp b) { return a.ns == b.ns; }
  friend bool operator!=(Stamp a, Stamp b) { return a.ns != b.ns; }
};

/// Seconds from a to b.
inline double secondsBetween(Stamp a, Stamp b) {
  return static_cast<double>(b.ns - a.ns) * 1e-9;
}

}  // namespace mrslam
