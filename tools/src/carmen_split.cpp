#include "mrslam/tools/carmen_split.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "mrslam/drivers/line_reader.hpp"

namespace mrslam::tools {

namespace {

struct LogLines {
  std::vector<std::string> params;              ///< PARAM and comment lines
  std::vector<std::vector<std::string>> scans;  ///< lines from one FLASER up to the next
  std::vector<SE2> scan_poses;                  ///< corrected laser pose of each FLASER
  std::vector<std::string> before_first_scan;   ///< ODOM lines before the first FLASER
};

SE2 flaserPose(const std::string& line, const std::string& where) {
  std::vector<std::string_view> fields;
  drivers::splitFields(line, fields);
  const auto count = fields.size() > 1 ? drivers::parseInteger(fields[1]) : std::nullopt;
  if (!count || *count < 0 || fields.size() < static_cast<std::size_t>(*count) + 5) {
    throw std::runtime_error(where + ": malformed FLASER line");
  }
  const std::size_t at = static_cast<std::size_t>(*count) + 2;
  const auto x = drivers::parseNumber(fields[at]);
  const auto y = drivers::parseNumber(fields[at + 1]);
  const auto theta = drivers::parseNumber(fields[at + 2]);
  if (!x || !y || !theta) {
    throw std::runtime_error(where + ": malformed FLASER pose");
  }
  return SE2(*x, *y, *theta);
}

LogLines readLog(const std::string& log_path) {
  LogLines log;
  drivers::LineReader reader(log_path);
  std::string line;
  while (reader.next(line)) {
    if (line.rfind("PARAM", 0) == 0 || line.rfind("#", 0) == 0) {
      log.params.push_back(line);
    } else if (line.rfind("FLASER", 0) == 0) {
      log.scan_poses.push_back(
          flaserPose(line, log_path + ":" + std::to_string(reader.lineNumber())));
      log.scans.push_back({line});
    } else if (!line.empty()) {
      (log.scans.empty() ? log.before_first_scan : log.scans.back()).push_back(line);
    }
  }
  return log;
}

}  // namespace

std::vector<LogSegment> splitCarmenLog(const std::string& log_path, const std::string& folder,
                                       const SplitSettings& settings) {
  const LogLines log = readLog(log_path);
  const int scans = static_cast<int>(log.scans.size());
  if (settings.segments < 1 || scans < settings.segments) {
    throw std::runtime_error(log_path + ": " + std::to_string(scans) + " scans cannot make " +
                             std::to_string(settings.segments) + " segments");
  }
  std::filesystem::create_directories(folder);
  std::vector<LogSegment> segments;
  for (int k = 0; k < settings.segments; ++k) {
    const int begin =
        std::max(0, k * scans / settings.segments - (k > 0 ? settings.overlap_scans : 0));
    const int end = (k + 1) * scans / settings.segments;
    LogSegment segment;
    segment.path =
        (std::filesystem::path(folder) / ("segment_" + std::to_string(k + 1) + ".log")).string();
    segment.first_scan = begin;
    segment.scan_count = end - begin;
    segment.T_log_origin = log.scan_poses[static_cast<std::size_t>(begin)];
    std::ofstream file(segment.path);
    for (const std::string& param : log.params) {
      file << param << "\n";
    }
    for (int scan = begin; scan < end; ++scan) {
      for (const std::string& line : log.scans[static_cast<std::size_t>(scan)]) {
        file << line << "\n";
      }
    }
    if (!file) {
      throw std::runtime_error(segment.path + ": cannot write");
    }
    segments.push_back(segment);
  }
  return segments;
}

void writeSplitTruth(const std::vector<LogSegment>& segments, const std::vector<std::string>& ids,
                     const std::string& path) {
  if (segments.empty() || ids.size() != segments.size()) {
    throw std::runtime_error(path + ": one robot id per segment is needed");
  }
  const SE2 T_reference_log = segments.front().T_log_origin.inverse();
  nlohmann::json robots = nlohmann::json::array();
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const SE2 T_reference_origin = T_reference_log * segments[k].T_log_origin;
    robots.push_back({{"id", ids[k]},
                      {"placed", true},
                      {"x", T_reference_origin.x()},
                      {"y", T_reference_origin.y()},
                      {"theta", T_reference_origin.theta()},
                      {"first_scan", segments[k].first_scan},
                      {"scans", segments[k].scan_count},
                      {"log", segments[k].path}});
  }
  std::ofstream file(path);
  file << nlohmann::json{{"reference", ids.front()}, {"robots", robots}}.dump(2) << "\n";
  if (!file) {
    throw std::runtime_error(path + ": cannot write");
  }
}

}  // namespace mrslam::tools
