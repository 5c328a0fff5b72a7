// mrslam_merge_cases: known-answer merge cases cut from the shared real maps, and the score of
// each merge method on them, side by side in one run.
//
//   mrslam_merge_cases --methods seed,feature --cases 200 --negatives 50 --seed 1 [--json]
//
// Positive cases: two crops of one map (see merge_cases.hpp), spread evenly over the overlap
// bands 20–40, 40–60 and 60–80 %. Success: accepted within 2 cells and 1° of the truth; a false
// accept is accepted but wrong. Negative cases: crops of two different buildings; every accept is
// a false accept. Time per merge: median and 90th percentile over all cases.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "mrslam/common/map_loaders.hpp"
#include "mrslam/common/version.hpp"
#include "mrslam/fusion/merge/merge_cases.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"
#include "mrslam/fusion/merge/overlap_score.hpp"

namespace {

namespace fs = std::filesystem;
using mrslam::fusion::MergeCase;

constexpr int kBands = 3;

struct CasesOptions {
  std::string methods;
  mrslam::fusion::CaseSettings settings;
  std::string maps_dir;
  std::string config;  ///< optional YAML: a section of settings per method name
  bool json = false;
  bool details = false;
};

/// The shared maps and the building each shows.
const std::vector<std::pair<std::string, std::string>>& sourceFiles() {
  static const std::vector<std::pair<std::string, std::string>> files = {
      {"carpin-intel.txt", "intel"},         {"freiburg-intel.pgm", "intel"},
      {"freiburg-aces.pgm", "aces"},         {"carpin-LongRun6.txt", "ucmerced"},
      {"carpin-LongRun7.txt", "ucmerced"},   {"carpin-robot0_cast.txt", "ap_hill"},
      {"carpin-robot1_cast.txt", "ap_hill"}, {"carpin-robot2_cast.txt", "ap_hill"},
      {"carpin-robot3_cast.txt", "ap_hill"}};
  return files;
}

/// shared/data/maps in `start` or one of its parents (empty if none).
std::string mapsFolderAbove(fs::path start) {
  for (fs::path folder = start; !folder.empty(); folder = folder.parent_path()) {
    if (fs::is_directory(folder / "shared" / "data" / "maps")) {
      return (folder / "shared" / "data" / "maps").string();
    }
    if (folder == folder.parent_path()) {
      break;
    }
  }
  return "";
}

/// $MRSLAM_DATA_DIR/maps, else shared/data/maps above the working folder or above this program.
std::string findMapsFolder() {
  if (const char* data = std::getenv("MRSLAM_DATA_DIR")) {
    return (fs::path(data) / "maps").string();
  }
  std::string found = mapsFolderAbove(fs::current_path());
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  if (found.empty() && !error) {
    found = mapsFolderAbove(program.parent_path());
  }
  return found.empty() ? "../shared/data/maps" : found;
}

std::vector<mrslam::fusion::SourceMap> loadSources(const std::string& folder) {
  std::vector<mrslam::fusion::SourceMap> sources;
  for (const auto& [file, building] : sourceFiles()) {
    sources.push_back({file, building, mrslam::loadMapFile((fs::path(folder) / file).string())});
  }
  return sources;
}

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    if (!item.empty()) {
      items.push_back(item);
    }
  }
  return items;
}

int bandOf(double overlap) {
  return std::clamp(static_cast<int>((overlap - 0.2) / 0.2), 0, 2);
}

struct BandTally {
  int cases = 0;
  int success = 0;
  int false_accepts = 0;
  int refused = 0;
};

struct MethodTally {
  std::string name;
  BandTally bands[kBands];
  int negative_cases = 0;
  int negative_accepts = 0;
  std::vector<double> times_ms;
  nlohmann::json details = nlohmann::json::array();
};

void scoreCase(const MergeCase& merge_case, mrslam::fusion::MapMerger& merger, MethodTally& tally) {
  const auto start = std::chrono::steady_clock::now();
  const mrslam::fusion::MergeResult result = merger.merge(merge_case.a, merge_case.b);
  tally.times_ms.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  nlohmann::json detail = {
      {"case", merge_case.id},
      {"accepted", result.accepted},
      {"merger_verification", result.verification},
      {"verification",
       mrslam::fusion::scoreOverlap(merge_case.a, merge_case.b, result.T_to_from).verification()},
      {"reason", result.reason},
      {"time_ms", tally.times_ms.back()}};
  if (!merge_case.positive) {
    ++tally.negative_cases;
    tally.negative_accepts += result.accepted;
    tally.details.push_back(detail);
    return;
  }
  BandTally& band = tally.bands[bandOf(merge_case.overlap)];
  ++band.cases;
  const mrslam::fusion::CaseError error = mrslam::fusion::caseError(merge_case, result.T_to_from);
  const bool correct = mrslam::fusion::isCorrect(error);
  band.success += result.accepted && correct;
  band.false_accepts += result.accepted && !correct;
  band.refused += !result.accepted;
  detail["overlap"] = merge_case.overlap;
  detail["angle_error_deg"] = error.angle_rad * 180.0 / 3.14159265358979323846;
  detail["distance_error_cells"] = error.distance_cells;
  tally.details.push_back(detail);
}

double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(fraction * values.size()));
  return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

nlohmann::json toJson(const MethodTally& tally, bool details) {
  nlohmann::json bands = nlohmann::json::array();
  int false_accepts = 0;
  for (int b = 0; b < kBands; ++b) {
    const BandTally& band = tally.bands[b];
    false_accepts += band.false_accepts;
    bands.push_back({{"overlap", {(2 + 2 * b) / 10.0, (4 + 2 * b) / 10.0}},
                     {"cases", band.cases},
                     {"success", band.success},
                     {"rate", band.cases == 0 ? 0.0 : double(band.success) / band.cases},
                     {"false_accepts", band.false_accepts},
                     {"refused", band.refused}});
  }
  nlohmann::json json = {
      {"bands", bands},
      {"false_accepts_positive", false_accepts},
      {"negative_cases", tally.negative_cases},
      {"false_accepts_negative", tally.negative_accepts},
      {"time_ms",
       {{"median", percentile(tally.times_ms, 0.5)}, {"p90", percentile(tally.times_ms, 0.9)}}}};
  if (details) {
    json["cases"] = tally.details;
  }
  return json;
}

void printTable(const std::vector<MethodTally>& tallies) {
  std::cout << std::left << std::setw(10) << "method" << std::setw(12) << "20-40 %" << std::setw(12)
            << "40-60 %" << std::setw(12) << "60-80 %" << std::setw(18) << "false acc (pos)"
            << std::setw(18) << "false acc (neg)" << std::setw(12) << "median ms"
            << "p90 ms\n";
  for (const MethodTally& tally : tallies) {
    std::cout << std::setw(10) << tally.name;
    int false_accepts = 0;
    for (const BandTally& band : tally.bands) {
      std::ostringstream cell;
      cell << band.success << "/" << band.cases;
      std::cout << std::setw(12) << cell.str();
      false_accepts += band.false_accepts;
    }
    std::ostringstream negatives;
    negatives << tally.negative_accepts << "/" << tally.negative_cases;
    std::cout << std::setw(18) << false_accepts << std::setw(18) << negatives.str() << std::fixed
              << std::setprecision(1) << std::setw(12) << percentile(tally.times_ms, 0.5)
              << percentile(tally.times_ms, 0.9) << std::defaultfloat << '\n';
  }
}

int run(const CasesOptions& options) {
  std::vector<MethodTally> tallies;
  std::vector<std::unique_ptr<mrslam::fusion::MapMerger>> mergers;
  std::vector<MergeCase> cases;
  try {
    const mrslam::Config config = options.config.empty()
                                      ? mrslam::Config::loadString("", "<defaults>")
                                      : mrslam::Config::loadFile(options.config);
    mrslam::fusion::checkMergerConfig(config);
    for (const std::string& name : splitList(options.methods)) {
      mergers.push_back(mrslam::fusion::makeMergerFrom(name, config));
      tallies.push_back({});
      tallies.back().name = name;
    }
    const std::string folder = options.maps_dir.empty() ? findMapsFolder() : options.maps_dir;
    cases = mrslam::fusion::generateCases(loadSources(folder), options.settings);
  } catch (const std::exception& error) {
    std::cerr << "mrslam_merge_cases: " << error.what() << '\n';
    return 1;
  }
  for (const MergeCase& merge_case : cases) {
    for (std::size_t m = 0; m < mergers.size(); ++m) {
      scoreCase(merge_case, *mergers[m], tallies[m]);
    }
    if ((merge_case.id + 1) % 25 == 0) {
      std::cerr << "mrslam_merge_cases: " << merge_case.id + 1 << "/" << cases.size() << " cases\n";
    }
  }
  if (options.json) {
    nlohmann::json methods = nlohmann::json::object();
    for (const MethodTally& tally : tallies) {
      methods[tally.name] = toJson(tally, options.details);
    }
    std::cout << nlohmann::json{{"cases", options.settings.positive_cases},
                                {"negatives", options.settings.negative_cases},
                                {"seed", options.settings.seed},
                                {"methods", methods}}
                     .dump()
              << '\n';
  } else {
    printTable(tallies);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CasesOptions options;
  std::string all;
  for (const std::string& name : mrslam::fusion::mergerNames()) {
    all += (all.empty() ? "" : ",") + name;
  }
  options.methods = all;
  CLI::App app{"Scores merge methods on known-answer cases cut from the shared maps"};
  app.add_option("--methods", options.methods, "comma-separated merge methods")
      ->capture_default_str();
  app.add_option("--cases", options.settings.positive_cases, "positive cases")
      ->capture_default_str()
      ->check(CLI::Range(3, 100000));
  app.add_option("--negatives", options.settings.negative_cases, "cases from two buildings")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  app.add_option("--seed", options.settings.seed, "seed of the case generator")
      ->capture_default_str();
  app.add_option("--maps", options.maps_dir, "folder of the shared maps (default: found)");
  app.add_option("--config", options.config, "YAML of merger settings, one section per method");
  app.add_flag("--json", options.json, "print one JSON object");
  app.add_flag("--details", options.details, "with --json: every case's result too");
  app.set_version_flag("--version", mrslam::versionLine("merge_cases"));
  CLI11_PARSE(app, argc, argv);
  return run(options);
}
