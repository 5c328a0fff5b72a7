#pragma once
// SCIP 2.0 character codec (Hokuyo laser rangers): line checksums, the 6-bit character
// encoding of values, and the meaning of status codes. Pure functions, no I/O.
//
// Facts (Hokuyo SCIP 2.0 specification C-42-03320B):
//  - The sum char of a line is ((Σ bytes before it) & 0x3F) + 0x30.
//  - `KEY:value;S` lines (VV, PP, II) sum `KEY:value` only; some devices include the ';'.
//  - A value is sent as 6-bit groups, most significant first, each + 0x30: 2 chars = 12 bits,
//    3 chars = 18 bits (MD/GD ranges), 4 chars = 24 bits (time stamps).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mrslam::drivers::scip {

/// Largest number of encoded chars a data line carries before its sum char.
constexpr std::size_t kMaxDataLineChars = 64;

/// The sum char of `bytes`: ((Σ bytes) & 0x3F) + 0x30.
char checksum(std::string_view bytes);

/// A line (without its LF) whose last char is the sum of all the bytes before it.
bool hasValidChecksum(std::string_view line);

/// A `KEY:value;S` line: accepts the sum over `KEY:value` (the specification) and over
/// `KEY:value;` (some devices). Other lines must pass hasValidChecksum().
bool hasValidKeyValueChecksum(std::string_view line);

/// `line` followed by its sum char (no LF).
std::string withChecksum(std::string_view line);

/// Encodes `value` in `chars` (1 to 4) chars. Throws std::invalid_argument when it does not fit.
std::string encode(std::uint32_t value, int chars);

/// Decodes 1 to 4 encoded chars; nothing when a char is outside '0' (0x30) … 'o' (0x6F).
std::optional<std::uint32_t> decode(std::string_view chars);

/// Decodes a run of fixed-width values (2 or 3 chars each) and appends them to `values`.
/// False (with `values` unchanged) when the length is not a multiple of `width` or a char is bad.
bool decodeValues(std::string_view chars, int width, std::vector<std::uint32_t>& values);

/// A clear text for the status `status` (two chars) of a reply to `command` (its first two
/// letters, e.g. "MD"): "OK", "scan data follows", parameter errors, hardware faults, …,
/// or "unknown status XX".
std::string statusText(std::string_view command, std::string_view status);

/// True for the statuses that mean success for `command`: "00", "99" (scan data),
/// and BM's "02" (laser already on).
bool isSuccessStatus(std::string_view command, std::string_view status);

}  // namespace mrslam::drivers::scip
