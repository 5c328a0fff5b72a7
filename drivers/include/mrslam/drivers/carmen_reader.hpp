#pragma once
// Replay of CARMEN logs (plain or gzip), one message per line:
//   FLASER n r1 .. rn x y theta odom_x odom_y odom_theta timestamp hostname logger_timestamp
//   ODOM x y theta tv rv accel timestamp hostname logger_timestamp
// FLASER gives a LaserScan (ranges in metres, first beam at -90°, logged_pose = the laser pose
// x y theta) and (CarmenSettings::odometry) an OdometryPose from its odom fields just before the
// scan; ODOM gives an OdometryPose. Samples carry the `timestamp` field, read exactly (exponent
// form too: csail writes "1.13486e+09"), in file order; stamps that go backwards are counted.
// PARAM, NEFF, '#' and empty lines are passed over; other message types (RAWLASER1, ROBOTLASER1,
// SYNC, ...) are skipped and counted in skipped_records().
//
// The corrected logs (Radish intel, aces, csail) follow every FLASER with an ODOM line that
// repeats its pose: odometry re-anchored to the corrected pose, stamped 0 (intel: 69 of them
// with garbage such as 1.65576e-153) or long before the scan. An ODOM line right after a FLASER,
// with its pose and stamped more than kReanchorLagS before it, is such a line: counted in
// reanchor_odom_records() and, by default, not emitted. (A raw log's ODOM line may repeat the
// scan's pose too, when the robot stood still: the raw intel log has 578, up to 0.9 s early,
// as its lines were logged out of order.) In the corrected logs the FLASER odom fields equal
// the laser pose.
//
// The laser's mounting on the robot, T_robot_laser, comes from the log: the first FLASER line's
// laser pose in the frame of its odometry pose (fr079: x = -0.04 m, on every line), else
// `PARAM robot_frontlaser_offset` (an x offset). The constructor reads the log up to its first
// FLASER line, so laserMounting() is known as soon as the reader is open.
//
// Reversing: an ODOM step that runs ahead while its own velocity tv is backwards (below
// -kReversingSpeedMps) is a robot that integrated |v|: the raw fr079 log reports reversing in
// 320 ODOM lines, yet not one of its steps moves back. Such a step is mirrored (its translation
// turned by π in the frame of the pose before it, its turn kept), counted in
// reversed_odometry_steps(), and every later pose, of ODOM and FLASER lines alike, is carried along
// by the accumulated correction.

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mrslam/common/se2.hpp"
#include "mrslam/drivers/line_reader.hpp"
#include "mrslam/drivers/log_format.hpp"
#include "mrslam/drivers/sample_source.hpp"

namespace mrslam::drivers {

/// Where the OdometryPose samples of a CARMEN log come from.
enum class CarmenOdometry {
  kFlaserOdom,  ///< the odom fields of each FLASER line, stamped as the scan, just before it
  kOdomLines,   ///< the ODOM lines (the higher-rate stream between scans)
  kBoth,        ///< both, in file order
};

struct CarmenSettings {
  std::string path;                                           ///< the log, plain text or gzip
  MalformedPolicy malformed_policy = MalformedPolicy::kSkip;  ///< what a malformed line does
  /// kFlaserOdom: one pose per scan, stamped with it; the ODOM lines of the corrected logs jump
  /// back in time (intel: 629 of 13631) and are reset to the corrected pose at every scan.
  CarmenOdometry odometry = CarmenOdometry::kFlaserOdom;
  bool emit_reanchor_odom = false;  ///< emit the ODOM line that repeats a FLASER's pose too
  double max_range_m = 50.0;  ///< readings at or above are kNoReturn (sentinels 50, 81.83, 81.91)
  double range_min_m = 0.01;  ///< readings below are kInvalid (a SICK LMS reports 0 on error)
};

class CarmenReader final : public SampleSource {
 public:
  /// An ODOM line that repeats the FLASER pose before it and is stamped more than this many
  /// seconds before that scan re-anchors the odometry (see above).
  static constexpr double kReanchorLagS = 5.0;
  /// A FLASER line whose pose pair differs from the first line's mounting by more than these
  /// counts in laser_mounting_mismatches().
  static constexpr double kMountingToleranceM = 1e-3;
  static constexpr double kMountingToleranceRad = 1e-3;
  /// A tv this far below zero is reversing (a stopped robot's tv jitters by millimetres a second).
  static constexpr double kReversingSpeedMps = 0.05;
  /// ... and a step this far ahead runs against it (smaller ones are the turn's own rounding).
  static constexpr double kReversingStepM = 1e-3;

  /// Checks the settings (std::invalid_argument), opens the log (std::runtime_error) and reads
  /// it up to its first FLASER line (a malformed line there under kStop: LogFormatError).
  explicit CarmenReader(CarmenSettings settings);

  std::optional<Sample> next() override;
  std::string describe() const override;
  SourceCounters counters() const override;
  std::optional<double> progress() const override { return lines_.fractionRead(); }

  const CarmenSettings& settings() const { return settings_; }
  /// Records of message types this reader does not read (RAWLASER1, ROBOTLASER1, ...).
  std::uint64_t skipped_records() const { return skipped_records_; }
  /// ODOM lines that repeat the pose of the FLASER before them (emitted or not).
  std::uint64_t reanchor_odom_records() const { return reanchor_odom_records_; }
  /// ODOM steps that ran ahead while reversing, mirrored (see above).
  std::uint64_t reversed_odometry_steps() const { return reversed_odometry_steps_; }
  /// Malformed lines by kind ("field count", "beam count", "not a number", "not finite",
  /// "negative", "bad stamp", "not a message").
  std::map<std::string, std::uint64_t> malformedByKind() const { return malformed_.countsByKind(); }

  /// T_robot_laser as the log records it: the first FLASER line's laser pose in the frame of its
  /// odometry pose, else `PARAM robot_frontlaser_offset` as (offset, 0, 0); nothing when the
  /// log has neither. Known from construction on.
  std::optional<SE2> laserMounting() const;
  /// FLASER lines read so far whose laser pose, seen from their odometry pose, is not the first
  /// line's mounting (kMountingTolerance*): a log whose pose pair is no fixed mounting.
  std::uint64_t laser_mounting_mismatches() const { return mounting_mismatches_; }

  /// Angle between beams of an n-beam FLASER over 180°: an odd count includes both ends
  /// (181, 361: pi/(n-1)); an even count lacks the last beam (180, 360: pi/n), as CARMEN has it.
  /// The 180-beam intel and aces logs fit best so (consecutive scans at their corrected poses).
  static double beamIncrementRad(std::size_t beam_count);

 private:
  /// Reads and parses one line into pending_; false at the end of the log.
  bool readLine();
  std::optional<LineProblem> parseLine();
  std::optional<LineProblem> parseFlaser();
  std::optional<LineProblem> parseOdom();
  std::optional<LineProblem> parseParam();
  void noteMounting(const SE2& T_world_laser, const SE2& T_world_robot);
  /// Mirrors a step that ran against its velocity; returns the ODOM pose to emit.
  SE2 correctReversing(const SE2& T_world_robot_raw, double tv_mps);
  std::optional<LineProblem> numbers(std::size_t first, std::size_t count, double* out) const;

  const CarmenSettings settings_;
  LineReader lines_;
  MalformedLineHandler malformed_;
  std::string line_;
  std::vector<std::string_view> fields_;
  std::vector<double> values_;
  std::deque<Sample> pending_;
  std::optional<std::array<double, 3>> flaser_pose_;  ///< x y theta while the last record is FLASER
  Stamp flaser_stamp_;                                ///< the stamp of that FLASER
  bool flaser_seen_ = false;
  std::optional<SE2> flaser_mounting_;          ///< T_robot_laser from the first FLASER's pose pair
  std::optional<double> param_laser_offset_m_;  ///< PARAM robot_frontlaser_offset
  std::uint64_t mounting_mismatches_ = 0;
  std::optional<Stamp> last_stamp_;
  SourceCounters counters_;
  std::uint64_t skipped_records_ = 0;
  std::uint64_t reanchor_odom_records_ = 0;
  std::optional<SE2> last_raw_odom_;  ///< the previous ODOM pose as logged
  SE2 T_corrected_raw_;               ///< what the mirrored steps so far moved the odometry by
  std::uint64_t reversed_odometry_steps_ = 0;
};

}  // namespace mrslam::drivers
