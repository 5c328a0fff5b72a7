#pragma once
// The adapter interface every sensor source implements: devices, log readers and the simulator.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mrslam/common/samples.hpp"

namespace mrslam::drivers {

/// Counters every source keeps; they go into the robot status.
struct SourceCounters {
  std::uint64_t samples = 0;              ///< samples handed out
  std::uint64_t malformed_records = 0;    ///< lines / frames dropped as malformed
  std::uint64_t out_of_order_stamps = 0;  ///< samples whose stamp is older than the one before
};

/// How one sensor of a live source is doing (the robot status carries it).
struct SensorStatus {
  std::string name;      ///< laser, imu, encoders
  std::string source;    ///< device, fallback, absent, starting
  bool healthy = false;  ///< reading its device
  std::uint64_t samples = 0;
  std::uint64_t errors = 0;  ///< times its device was lost
};

/// A stream of samples in the order they are to be processed (time order for a log: file order).
class SampleSource {
 public:
  virtual ~SampleSource() = default;
  /// The next sample, or nothing at the end of the stream. Throws only for errors that stop the
  /// run (a malformed record when the policy says stop, an unreadable file).
  virtual std::optional<Sample> next() = 0;
  /// A short description for logs, e.g. "breezyslam log ../shared/data/logs/exp1.dat".
  virtual std::string describe() const = 0;
  virtual SourceCounters counters() const = 0;
  /// Per-sensor health of a live source (devices); empty for logs and the simulator.
  virtual std::vector<SensorStatus> sensors() const { return {}; }
  /// How much of the source has been read (0…1), when it is known (a log, the simulator).
  virtual std::optional<double> progress() const { return std::nullopt; }
};

/// What a log reader does with a malformed line.
enum class MalformedPolicy {
  kSkip,  ///< drop it, count it, log it (rate-limited) and go on
  kStop,  ///< stop the run with `file:line: what is wrong`
};

}  // namespace mrslam::drivers
