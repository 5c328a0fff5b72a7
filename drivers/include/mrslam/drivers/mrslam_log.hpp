#pragma once
// The project's own log format: every raw sample with its time stamp, written exactly, so a
// replay reproduces poses and maps bit for bit. Text, one sample per line (gzip when the file
// name ends in .gz); see docs/log_format.md.
//
//   # mrslam log 1
//   # robot robot1
//   TICKS <stamp_ns> <left> <right>
//   ODOM <stamp_ns> <x> <y> <theta>
//   IMU <stamp_ns> <roll> <pitch> <yaw> <has_orientation 0|1> <wx> <wy> <wz> <ax> <ay> <az>
//   LASER <stamp_ns> <angle_min> <angle_increment> <range_min> <range_max> <n> <r1> … <rn>
//         [POSE <x> <y> <theta>]
//
// Doubles are written with 17 significant digits and ranges (floats) with 9, which both read
// back to the same bits; a beam with no return is `inf`, an invalid one `nan`.

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "mrslam/drivers/line_reader.hpp"
#include "mrslam/drivers/log_format.hpp"
#include "mrslam/drivers/sample_source.hpp"

namespace mrslam::drivers {

/// The first line of every file in the format.
inline constexpr const char* kMrslamLogMagic = "# mrslam log 1";

class MrslamLogWriter {
 public:
  /// Creates (truncates) the file and writes the header. Throws std::runtime_error on failure.
  MrslamLogWriter(const std::string& path, const std::string& robot_id);
  ~MrslamLogWriter();
  MrslamLogWriter(const MrslamLogWriter&) = delete;
  MrslamLogWriter& operator=(const MrslamLogWriter&) = delete;

  void write(const Sample& sample);
  /// Flushes and closes; throws std::runtime_error when the data could not be written.
  void close();

 private:
  void writeLine(const std::string& line);

  std::string path_;
  struct File;
  std::unique_ptr<File> file_;
};

/// Text of one sample in the format (no line end).
std::string formatSampleLine(const Sample& sample);

struct MrslamLogSettings {
  std::string path;                                           ///< the log, plain or gzip
  MalformedPolicy malformed_policy = MalformedPolicy::kSkip;  ///< what a malformed line does
};

class MrslamLogReader final : public SampleSource {
 public:
  /// Opens the log and checks its first line. Throws std::runtime_error when it is not one.
  explicit MrslamLogReader(MrslamLogSettings settings);

  std::optional<Sample> next() override;
  std::string describe() const override;
  SourceCounters counters() const override { return counters_; }
  std::optional<double> progress() const override { return lines_.fractionRead(); }
  /// The robot id the header names (empty when absent).
  const std::string& robotId() const { return robot_id_; }

 private:
  std::optional<Sample> parseLine(const std::string& line, LineProblem& problem) const;

  MrslamLogSettings settings_;
  LineReader lines_;
  MalformedLineHandler malformed_;
  std::string robot_id_;
  std::string pending_header_;  ///< a non-comment first line to parse after the header
  SourceCounters counters_;
  std::optional<Stamp> last_stamp_;
};

}  // namespace mrslam::drivers

namespace mrslam::drivers {

/// Passes the samples of another source through and records each one (robot_agent --record).
class RecordingSource final : public SampleSource {
 public:
  RecordingSource(std::unique_ptr<SampleSource> source, const std::string& path,
                  const std::string& robot_id)
      : source_(std::move(source)), writer_(path, robot_id) {}

  std::optional<Sample> next() override {
    std::optional<Sample> sample = source_->next();
    if (sample) {
      writer_.write(*sample);
    } else {
      writer_.close();
    }
    return sample;
  }
  std::string describe() const override { return source_->describe() + " (recorded)"; }
  SourceCounters counters() const override { return source_->counters(); }
  std::vector<SensorStatus> sensors() const override { return source_->sensors(); }
  std::optional<double> progress() const override { return source_->progress(); }

 private:
  std::unique_ptr<SampleSource> source_;
  MrslamLogWriter writer_;
};

}  // namespace mrslam::drivers
