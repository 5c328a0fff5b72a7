#pragma once
// Replay of BreezySLAM's logs (examples/exp1.dat, exp2.dat: a rover at Mines ParisTech with a
// Hokuyo URG-04LX and wheel encoders). One line per scan, whitespace separated:
//   field 1            time stamp in microseconds
//   fields 3, 4        left and right cumulative wheel encoder counts
//   fields 2, 5 .. 25  other rover data (unused; field 25 closes the header: the logs put two
//                      spaces after it, and fields 14-16, 17-19, 23-25 are all "255 0 0")
//   fields 26 .. 707   the 682 ranges in millimetres, the most clockwise beam first
// BreezySLAM's own loaders take fields 25 .. 706 as the ranges (one field earlier, dropping the
// last range): a one-beam (0.35°) turn of every scan. This reader follows the data instead.
// Each line gives a WheelTicks sample, then a LaserScan, both stamped with the line's time.
// Beam order, checked on the data: taking field 3 as the left wheel, the scans of two lines during
// a turn agree after the turn the encoders measured when the first range is the most clockwise
// beam (37 of 37 turning pairs in exp1, 45 of 49 in exp2); the other order mirrors the scans.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mrslam/drivers/line_reader.hpp"
#include "mrslam/drivers/log_format.hpp"
#include "mrslam/drivers/sample_source.hpp"

namespace mrslam::drivers {

/// Which end of a line's ranges is the most clockwise beam (angle_min of the LaserScan).
enum class BeamOrder {
  kFirstIsMostClockwise,  ///< the first range is at -fov/2 (what the BreezySLAM logs hold)
  kLastIsMostClockwise,   ///< the last range is at -fov/2
};

struct BreezySlamSettings {
  std::string path;                                           ///< the log, plain text or gzip
  MalformedPolicy malformed_policy = MalformedPolicy::kSkip;  ///< what a malformed line does
  double field_of_view_deg = 240.0;     ///< angle from the first to the last beam (URG-04LX)
  std::size_t beam_count = 682;         ///< ranges per line
  std::size_t header_field_count = 25;  ///< fields before the first range (see above)
  BeamOrder beam_order = BeamOrder::kFirstIsMostClockwise;  ///< which end is the clockwise beam
  double range_min_m = 0.02;  ///< readings below are URG error codes (1..19 mm): kInvalid
  double range_max_m = 5.6;   ///< readings of 0, or above this, are kNoReturn (URG-04LX: 5.6 m)
};

class BreezySlamReader final : public SampleSource {
 public:
  /// Checks the settings (std::invalid_argument) and opens the log (std::runtime_error).
  explicit BreezySlamReader(BreezySlamSettings settings);

  std::optional<Sample> next() override;
  std::string describe() const override;
  SourceCounters counters() const override;
  std::optional<double> progress() const override { return lines_.fractionRead(); }

  const BreezySlamSettings& settings() const { return settings_; }
  /// Malformed lines by kind ("field count", "not a number", "not finite", "negative").
  std::map<std::string, std::uint64_t> malformedByKind() const { return malformed_.countsByKind(); }

 private:
  std::optional<LineProblem> parseLine();

  const BreezySlamSettings settings_;
  LineReader lines_;
  MalformedLineHandler malformed_;
  std::string line_;
  std::vector<std::string_view> fields_;
  std::deque<Sample> pending_;
  std::optional<Stamp> last_stamp_;
  SourceCounters counters_;
};

}  // namespace mrslam::drivers
