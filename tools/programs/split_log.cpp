// mrslam_split_log: cuts a CARMEN log into K segments (one robot each) and writes the truth.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

#include "mrslam/common/logging.hpp"
#include "mrslam/common/version.hpp"
#include "mrslam/tools/carmen_split.hpp"

int main(int argc, char** argv) {
  mrslam::logToStandardError("mrslam_split_log");
  CLI::App app{"Cut a CARMEN log into K segments, each replayed by its own robot agent"};
  std::string log;
  std::string out;
  mrslam::tools::SplitSettings settings;
  std::string prefix = "robot";
  app.add_option("LOG", log, "CARMEN log (plain or .gz)")->required();
  app.add_option("--out", out, "output folder")->required();
  app.add_option("--segments", settings.segments, "number of segments K")
      ->check(CLI::Range(1, 100));
  app.add_option("--overlap-scans", settings.overlap_scans,
                 "scans each segment repeats from the one before")
      ->check(CLI::Range(0, 100000));
  app.add_option("--prefix", prefix, "robot ids are <prefix>1 … <prefix>K");
  app.set_version_flag("--version", mrslam::versionLine("split_log"));
  CLI11_PARSE(app, argc, argv);
  try {
    const auto segments = mrslam::tools::splitCarmenLog(log, out, settings);
    std::vector<std::string> ids;
    for (std::size_t k = 0; k < segments.size(); ++k) {
      ids.push_back(prefix + std::to_string(k + 1));
      std::printf("%s: %s (%d scans from scan %d)\n", ids.back().c_str(), segments[k].path.c_str(),
                  segments[k].scan_count, segments[k].first_scan);
    }
    const std::string truth = (std::filesystem::path(out) / "truth.json").string();
    mrslam::tools::writeSplitTruth(segments, ids, truth);
    std::printf("true placements: %s\n", truth.c_str());
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "mrslam_split_log: %s\n", error.what());
    return 1;
  }
}
