#pragma once
// Cuts a CARMEN log into K segments, each to be replayed by its own robot agent from its own
// origin: a team with unknown relative start poses and a known true answer.

#include <string>
#include <vector>

#include "mrslam/common/se2.hpp"

namespace mrslam::tools {

struct SplitSettings {
  int segments = 3;       ///< K
  int overlap_scans = 0;  ///< scans each segment repeats from the end of the one before
};

struct LogSegment {
  std::string path;    ///< the segment's CARMEN log
  int first_scan = 0;  ///< index of its first FLASER in the whole log
  int scan_count = 0;
  SE2 T_log_origin;  ///< corrected pose of its first scan in the log's frame
};

/// Splits `log_path` (plain or gzip) into `folder`/segment_<k>.log (k from 1), with equal numbers
/// of scans; every PARAM line goes to every segment. Throws std::runtime_error on bad input.
std::vector<LogSegment> splitCarmenLog(const std::string& log_path, const std::string& folder,
                                       const SplitSettings& settings);

/// Writes the true placements, transforms.json style: {"reference": ids[0], "robots": [{"id",
/// "placed": true, "x", "y", "theta"}]}, each the pose of a segment's origin in the first one's.
void writeSplitTruth(const std::vector<LogSegment>& segments, const std::vector<std::string>& ids,
                     const std::string& path);

}  // namespace mrslam::tools
