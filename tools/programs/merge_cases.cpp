// mrslam_merge_cases: known-answer merge cases cut from the shared real maps, and the score of
// each merge method on them, side by side in one run.
//
//   mrslam_merge_cases --methods seed,feature --cases 200 --negatives 50 --seed 1 [--json]
//   mrslam_merge_cases --methods chain,chain:seed+psi,chain:seed+virtual,feature
//
// `chain` is the configured chain; `chain:STEP+STEP[+psi]` a chain of those steps with the chain's
// other settings (its accepted transforms refined by Carpin's psi when it ends in `psi`), so that
// chains are compared side by side in one run.
//
// Positive cases: two crops of one map (see merge_cases.hpp), spread evenly over the overlap
// bands 20–40, 40–60 and 60–80 %. Success: accepted within 2 cells and 1° of the truth; a false
// accept is accepted but wrong. Negative cases: crops of two different buildings; every accept is
// a false accept. Time per merge: median and 90th percentile over all cases.
//
// To look into single cases: `--only 40,125` runs only those, `--judge-truth` also judges each
// case's exact truth by the seed acceptance alone (refused there: the acceptance or block 8 loses
// the case, not the search) and counts per band the truths accepted within the tolerance (the
// most this acceptance can reach), `--save DIR` writes each case's crops and crop B with crop A's
// walls at the truth in red. With `--json --details` each case carries the transform accepted
// (`affine`) and the truth (`truth_affine`) as image affines of crop A into crop B, the numbers
// `mrslam merge B A --judge` takes.
//
// `--truth-slide` measures how well each positive case's maps fix the truth at all (whatever the
// merger): the disagreeing cells the best placement slid 3-8 cells from the truth adds
// (truth_slide.hpp). An overlap of one corridor wall and open floor costs almost nothing slid
// along the wall: any merger that accepts it guesses. Each method's success is then also counted
// on the cases whose margin reaches `--fixed-margin` (default 50 cells), and with `--details`
// each accepted transform carries its own margin (`slide_margin`).

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "mrslam/common/heap.hpp"
#include "mrslam/common/logging.hpp"
#include "mrslam/common/map_io.hpp"
#include "mrslam/common/map_loaders.hpp"
#include "mrslam/common/version.hpp"
#include "mrslam/fusion/merge/merge_cases.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"
#include "mrslam/fusion/merge/overlap_score.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"
#include "mrslam/fusion/merge/truth_slide.hpp"
#include "mrslam/fusion/merge/wall_alignment.hpp"

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
  std::string only;             ///< comma-separated case ids to run (empty: all)
  bool judge_truth = false;     ///< judge each positive case's exact truth by the seed acceptance
  bool truth_slide = false;     ///< measure how well each positive case's maps fix its translation
  long long fixed_margin = 50;  ///< with truth_slide: a truth is fixed when slides cost this much
  std::string save_dir;         ///< write each run case's crops and truth picture here (empty: no)
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
  int gross_false_accepts = 0;  ///< of false_accepts, those beyond a near miss
  int refused = 0;
};

/// One more case of `band`: right, wrong (a near miss or gross) or refused.
void countCase(BandTally& band, bool accepted, const mrslam::fusion::CaseError& error) {
  const bool correct = mrslam::fusion::isCorrect(error);
  ++band.cases;
  band.success += accepted && correct;
  band.false_accepts += accepted && !correct;
  band.gross_false_accepts += accepted && !correct && !mrslam::fusion::isNearMiss(error);
  band.refused += !accepted;
}

struct MethodTally {
  std::string name;
  BandTally bands[kBands];
  BandTally fixed_bands[kBands];  ///< `--truth-slide`: the cases whose maps fix the truth
  int negative_cases = 0;
  int negative_accepts = 0;
  std::vector<double> times_ms;
  nlohmann::json details = nlohmann::json::array();
};

/// `--judge-truth` per band: positive cases, and those whose exact truth the acceptance takes
/// and keeps within the tolerance. No search is needed for those, so their share is the most a
/// method with this acceptance can reach (its ceiling); the rest have overlaps that do not fix
/// the transform for the acceptance even at the truth.
struct TruthTally {
  BandTally bands[kBands];
};

// How a crop was cut, as CropSpec holds it: enough to cut the same case again in a test.
nlohmann::json cropJson(const std::string& source, const mrslam::fusion::CropSpec& spec) {
  return {{"map", source},
          {"corner", {spec.corner.x(), spec.corner.y()}},
          {"size", spec.size},
          {"theta_rad", spec.theta_rad},
          {"pad_low", {spec.pad_low.x(), spec.pad_low.y()}},
          {"pad_high", {spec.pad_high.x(), spec.pad_high.y()}}};
}

// T_b_a as the image affine of crop A's pixels into crop B's (as `mrslam merge --json` prints it
// and `mrslam merge B A --judge` takes it).
nlohmann::json affineJson(const mrslam::fusion::GridTransform& T_b_a, const MergeCase& merge_case) {
  const mrslam::fusion::ImageAffine affine = mrslam::fusion::gridTransformToImageAffine(
      T_b_a, merge_case.a.geometry.height, merge_case.b.geometry.height);
  return {{affine(0, 0), affine(0, 1), affine(0, 2)}, {affine(1, 0), affine(1, 1), affine(1, 2)}};
}

/// `--truth-slide` for one case: whether it is measured (each accepted transform's margin too) and
/// whether the case's maps fix its truth.
struct CaseSlide {
  bool measured = false;  ///< --truth-slide given
  bool fixed = false;     ///< the truth's slides cost at least fixed_margin (or lose the overlap)
};

/// How many disagreeing cells the best placement slid 3-8 cells from `T_b_a` adds; null when no
/// slide keeps the overlap.
nlohmann::json slideMargin(const MergeCase& merge_case,
                           const mrslam::fusion::GridTransform& T_b_a) {
  const mrslam::fusion::TruthSlide slide =
      mrslam::fusion::truthSlide(merge_case.a, merge_case.b, T_b_a);
  return slide.slid_found ? nlohmann::json(slide.margin()) : nlohmann::json();
}

/// Whether the maps fix a truth of this slide: its slides cost at least `fixed_margin` cells, or
/// none keeps the overlap.
bool isFixed(const mrslam::fusion::TruthSlide& slide, long long fixed_margin) {
  return !slide.slid_found || slide.margin() >= fixed_margin;
}

/// `--truth-slide`: a positive case's entry of truth_slides, for the slide of its truth.
nlohmann::json truthSlideJson(const MergeCase& merge_case, const mrslam::fusion::TruthSlide& slide,
                              long long fixed_margin) {
  nlohmann::json json = {{"case", merge_case.id},
                         {"overlap", merge_case.overlap},
                         {"agreement", slide.at_truth.agreement},
                         {"disagreement", slide.at_truth.disagreement},
                         {"slid_found", slide.slid_found},
                         {"fixed", isFixed(slide, fixed_margin)}};
  if (slide.slid_found) {
    json["margin"] = slide.margin();
    json["slide"] = {slide.slide.x(), slide.slide.y()};
    json["slid_agreement"] = slide.slid.agreement;
  }
  return json;
}

void scoreCase(const MergeCase& merge_case, mrslam::fusion::MapMerger& merger,
               const CaseSlide& case_slide, MethodTally& tally) {
  const auto start = std::chrono::steady_clock::now();
  const mrslam::fusion::MergeResult result = merger.merge(merge_case.a, merge_case.b);
  tally.times_ms.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  nlohmann::json detail = {
      {"case", merge_case.id},
      {"accepted", result.accepted},
      {"method", result.method},
      {"merger_verification", result.verification},
      {"verification",
       mrslam::fusion::scoreOverlap(merge_case.a, merge_case.b, result.T_to_from).verification()},
      {"reason", result.reason},
      {"time_ms", tally.times_ms.back()},
      {"crop_a", cropJson(merge_case.source_a, merge_case.spec_a)},
      {"crop_b", cropJson(merge_case.source_b, merge_case.spec_b)}};
  if (result.accepted) {
    detail["affine"] = affineJson(result.T_to_from, merge_case);
    if (case_slide.measured) {
      detail["slide_margin"] = slideMargin(merge_case, result.T_to_from);
    }
  }
  if (!merge_case.positive) {
    ++tally.negative_cases;
    tally.negative_accepts += result.accepted;
    tally.details.push_back(detail);
    return;
  }
  BandTally& band = tally.bands[bandOf(merge_case.overlap)];
  const mrslam::fusion::CaseError error = mrslam::fusion::caseError(merge_case, result.T_to_from);
  countCase(band, result.accepted, error);
  if (case_slide.fixed) {
    countCase(tally.fixed_bands[bandOf(merge_case.overlap)], result.accepted, error);
  }
  detail["overlap"] = merge_case.overlap;
  detail["truth_affine"] = affineJson(merge_case.T_b_a, merge_case);
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

/// Band `b`'s counts, its right and wrong accepts under the given names (and of the wrong ones
/// those beyond a near miss as "gross_" and that name).
nlohmann::json bandJson(int b, const BandTally& band, const char* right_name,
                        const char* wrong_name) {
  return {{"overlap", {(2 + 2 * b) / 10.0, (4 + 2 * b) / 10.0}},
          {"cases", band.cases},
          {right_name, band.success},
          {"rate", band.cases == 0 ? 0.0 : double(band.success) / band.cases},
          {wrong_name, band.false_accepts},
          {std::string("gross_") + wrong_name, band.gross_false_accepts},
          {"refused", band.refused}};
}

/// The false accepts over the bands, and of them the gross ones.
std::pair<int, int> falseAccepts(const BandTally (&bands)[kBands]) {
  int all = 0;
  int gross = 0;
  for (const BandTally& band : bands) {
    all += band.false_accepts;
    gross += band.gross_false_accepts;
  }
  return {all, gross};
}

nlohmann::json toJson(const MethodTally& tally, bool details, bool with_fixed) {
  nlohmann::json bands = nlohmann::json::array();
  nlohmann::json fixed_bands = nlohmann::json::array();
  for (int b = 0; b < kBands; ++b) {
    bands.push_back(bandJson(b, tally.bands[b], "success", "false_accepts"));
    fixed_bands.push_back(bandJson(b, tally.fixed_bands[b], "success", "false_accepts"));
  }
  const auto [false_accepts, gross] = falseAccepts(tally.bands);
  nlohmann::json json = {
      {"bands", bands},
      {"false_accepts_positive", false_accepts},
      {"gross_false_accepts_positive", gross},
      {"negative_cases", tally.negative_cases},
      {"false_accepts_negative", tally.negative_accepts},
      {"time_ms",
       {{"median", percentile(tally.times_ms, 0.5)}, {"p90", percentile(tally.times_ms, 0.9)}}}};
  if (with_fixed) {
    json["bands_fixed"] = fixed_bands;
  }
  if (details) {
    json["cases"] = tally.details;
  }
  return json;
}

/// Each band's "success/cases", a column of 12 characters each.
void printBandCells(const BandTally (&bands)[kBands]) {
  for (const BandTally& band : bands) {
    std::ostringstream cell;
    cell << band.success << "/" << band.cases;
    std::cout << std::setw(12) << cell.str();
  }
}

/// "N (G gross)": false accepts and, of them, the gross ones; "N" when none is gross.
std::string falseAcceptsText(std::pair<int, int> false_accepts) {
  const auto [all, gross] = false_accepts;
  return std::to_string(all) + (gross > 0 ? " (" + std::to_string(gross) + " gross)" : "");
}

/// The width of the table's first column: 10, or two more than the longest method name (a chain
/// variant such as "chain:exhaustive+seed+psi").
int nameColumn(const std::vector<MethodTally>& tallies) {
  std::size_t longest = 8;
  for (const MethodTally& tally : tallies) {
    longest = std::max(longest, tally.name.size());
  }
  return static_cast<int>(longest) + 2;
}

/// `--truth-slide`: each method's success per band on the cases whose maps fix the truth.
void printFixedRows(const std::vector<MethodTally>& tallies, long long fixed_margin) {
  std::cout << "on the cases whose truth slid 3-8 cells costs " << fixed_margin
            << " disagreeing cells or more:\n";
  const int name_column = nameColumn(tallies);
  for (const MethodTally& tally : tallies) {
    std::cout << std::setw(name_column) << tally.name;
    printBandCells(tally.fixed_bands);
    std::cout << falseAcceptsText(falseAccepts(tally.fixed_bands)) << '\n';
  }
}

void printTable(const std::vector<MethodTally>& tallies) {
  const int name_column = nameColumn(tallies);
  std::cout << std::left << std::setw(name_column) << "method" << std::setw(12) << "20-40 %"
            << std::setw(12) << "40-60 %" << std::setw(12) << "60-80 %" << std::setw(18)
            << "false acc (pos)" << std::setw(18) << "false acc (neg)" << std::setw(12)
            << "median ms"
            << "p90 ms\n";
  for (const MethodTally& tally : tallies) {
    std::cout << std::setw(name_column) << tally.name;
    printBandCells(tally.bands);
    std::ostringstream negatives;
    negatives << tally.negative_accepts << "/" << tally.negative_cases;
    std::cout << std::setw(18) << falseAcceptsText(falseAccepts(tally.bands)) << std::setw(18)
              << negatives.str() << std::fixed << std::setprecision(1) << std::setw(12)
              << percentile(tally.times_ms, 0.5) << percentile(tally.times_ms, 0.9)
              << std::defaultfloat << '\n';
  }
}

/// The case ids of `--only` (empty: every case).
std::vector<int> parseCaseIds(const std::string& text) {
  std::vector<int> ids;
  for (const std::string& item : splitList(text)) {
    const bool digits =
        std::all_of(item.begin(), item.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
    if (!digits || item.size() > 9) {
      throw std::invalid_argument("--only: not a case id: '" + item + "'");
    }
    ids.push_back(std::stoi(item));
  }
  return ids;
}

bool isSelected(const std::vector<int>& ids, int id) {
  return ids.empty() || std::find(ids.begin(), ids.end(), id) != ids.end();
}

/// `--judge-truth`: the seed acceptance given the exact truth as its only hypothesis, then the
/// alignment and turn check every merger ends with. A refusal there means the acceptance (or
/// block 8 sliding away from it) loses the case, not the search.
nlohmann::json judgeTruth(const MergeCase& merge_case, mrslam::fusion::SeedMerger& judge,
                          TruthTally& tally) {
  mrslam::fusion::MergeResult result =
      judge.judgeHypotheses(merge_case.a, merge_case.b, {merge_case.T_b_a});
  mrslam::fusion::alignAccepted(merge_case.a, merge_case.b, judge.settings().wall_alignment,
                                judge.settings().similarity, result);
  const mrslam::fusion::CaseError error = mrslam::fusion::caseError(merge_case, result.T_to_from);
  countCase(tally.bands[bandOf(merge_case.overlap)], result.accepted, error);
  return {{"case", merge_case.id},
          {"overlap", merge_case.overlap},
          {"accepted", result.accepted},
          {"verification", result.verification},
          {"distance_error_cells", error.distance_cells},
          {"angle_error_deg", error.angle_rad * 180.0 / 3.14159265358979323846},
          {"reason", result.reason}};
}

void printTruthJudgement(const nlohmann::json& judged) {
  const std::string reason = judged["reason"].get<std::string>();
  std::cout << "case " << judged["case"].get<int>() << " overlap " << std::fixed
            << std::setprecision(2) << judged["overlap"].get<double>() << ": the truth is "
            << (judged["accepted"].get<bool>() ? "accepted" : "refused") << ", V "
            << std::setprecision(3) << judged["verification"].get<double>() << ", ends "
            << std::setprecision(2) << judged["distance_error_cells"].get<double>() << " cells and "
            << judged["angle_error_deg"].get<double>() << " deg from it" << std::defaultfloat
            << (reason.empty() ? "" : " (" + reason + ")") << '\n';
}

nlohmann::json toJson(const TruthTally& tally) {
  nlohmann::json bands = nlohmann::json::array();
  for (int b = 0; b < kBands; ++b) {
    bands.push_back(
        bandJson(b, tally.bands[b], "accepted_within_tolerance", "accepted_outside_tolerance"));
  }
  return {{"bands", bands}};
}

void printTruthCeiling(const TruthTally& tally, int name_column) {
  std::cout << std::left << std::setw(name_column) << "truth";
  printBandCells(tally.bands);
  std::cout << "(the exact truth judged alone: accepted within 2 cells and 1 deg)\n";
}

/// `--save`: case_<id>_a.png, case_<id>_b.png and case_<id>_truth.png (crop B with crop A's
/// walls placed by the truth in red; a negative case has no truth picture).
void saveCasePictures(const MergeCase& merge_case, const fs::path& folder) {
  const std::string stem = (folder / ("case_" + std::to_string(merge_case.id))).string();
  mrslam::saveMapPng(merge_case.a, stem + "_a.png");
  mrslam::saveMapPng(merge_case.b, stem + "_b.png");
  if (!merge_case.positive) {
    return;
  }
  mrslam::MapOverlay walls_of_a;
  const mrslam::GridGeometry& geometry = merge_case.a.geometry;
  for (int cy = 0; cy < geometry.height; ++cy) {
    for (int cx = 0; cx < geometry.width; ++cx) {
      if (merge_case.a.at(cx, cy) > 50) {
        const Eigen::Vector2d in_b = merge_case.T_b_a.apply(Eigen::Vector2d(cx, cy));
        walls_of_a.cells.emplace_back(static_cast<int>(std::lround(in_b.x())),
                                      static_cast<int>(std::lround(in_b.y())));
      }
    }
  }
  mrslam::saveMapPng(merge_case.b, stem + "_truth.png", {walls_of_a});
}

int run(const CasesOptions& options) {
  std::vector<MethodTally> tallies;
  std::vector<std::unique_ptr<mrslam::fusion::MapMerger>> mergers;
  std::vector<MergeCase> cases;
  std::vector<int> only;
  std::unique_ptr<mrslam::fusion::SeedMerger> truth_judge;
  nlohmann::json truth_judgements = nlohmann::json::array();
  TruthTally truth_tally;
  nlohmann::json truth_slides = nlohmann::json::array();
  try {
    only = parseCaseIds(options.only);
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
    if (options.judge_truth) {
      truth_judge = std::make_unique<mrslam::fusion::SeedMerger>(
          mrslam::fusion::loadSeedMergerSettings(config.section("seed")));
    }
  } catch (const std::exception& error) {
    std::cerr << "mrslam_merge_cases: " << error.what() << '\n';
    return 1;
  }
  for (const MergeCase& merge_case : cases) {
    if (!isSelected(only, merge_case.id)) {
      continue;
    }
    if (!options.save_dir.empty()) {
      fs::create_directories(options.save_dir);
      saveCasePictures(merge_case, options.save_dir);
    }
    if (truth_judge && merge_case.positive) {
      truth_judgements.push_back(judgeTruth(merge_case, *truth_judge, truth_tally));
    }
    CaseSlide case_slide;
    case_slide.measured = options.truth_slide;
    if (options.truth_slide && merge_case.positive) {
      const mrslam::fusion::TruthSlide slide =
          mrslam::fusion::truthSlide(merge_case.a, merge_case.b, merge_case.T_b_a);
      truth_slides.push_back(truthSlideJson(merge_case, slide, options.fixed_margin));
      case_slide.fixed = isFixed(slide, options.fixed_margin);
    }
    for (std::size_t m = 0; m < mergers.size(); ++m) {
      scoreCase(merge_case, *mergers[m], case_slide, tallies[m]);
    }
    if ((merge_case.id + 1) % 25 == 0) {
      std::cerr << "mrslam_merge_cases: " << merge_case.id + 1 << "/" << cases.size() << " cases\n";
    }
  }
  if (options.json) {
    nlohmann::json methods = nlohmann::json::object();
    for (const MethodTally& tally : tallies) {
      methods[tally.name] = toJson(tally, options.details, options.truth_slide);
    }
    nlohmann::json json = {{"cases", options.settings.positive_cases},
                           {"negatives", options.settings.negative_cases},
                           {"seed", options.settings.seed},
                           {"methods", methods}};
    if (options.judge_truth) {
      json["truth_judgements"] = truth_judgements;
      json["truth_ceiling"] = toJson(truth_tally);
    }
    if (options.truth_slide) {
      json["fixed_margin"] = options.fixed_margin;
      json["truth_slides"] = truth_slides;
    }
    std::cout << json.dump() << '\n';
  } else {
    for (const nlohmann::json& judged : truth_judgements) {
      printTruthJudgement(judged);
    }
    printTable(tallies);
    if (options.truth_slide) {
      printFixedRows(tallies, options.fixed_margin);
    }
    if (options.judge_truth) {
      printTruthCeiling(truth_tally, nameColumn(tallies));
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  mrslam::logToStandardError("mrslam_merge_cases");
  CasesOptions options;
  std::string all;
  for (const std::string& name : mrslam::fusion::mergerNames()) {
    all += (all.empty() ? "" : ",") + name;
  }
  options.methods = all;
  CLI::App app{"Scores merge methods on known-answer cases cut from the shared maps"};
  app.add_option("--methods", options.methods,
                 "comma-separated merge methods; chain:STEP+STEP[+psi] scores a chain of those "
                 "steps (refined by psi when it ends in psi) beside the others")
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
  app.add_option("--only", options.only, "comma-separated case ids: run only these");
  app.add_flag("--judge-truth", options.judge_truth,
               "judge each positive case's exact truth by the seed acceptance alone and count "
               "per band those accepted within the tolerance (with --json: truth_judgements, "
               "truth_ceiling)");
  app.add_flag("--truth-slide", options.truth_slide,
               "measure per positive case the disagreeing cells the best placement slid 3-8 "
               "cells from the truth adds (near 0: the maps do not fix the truth), and each "
               "method's success on the cases they fix (with --json: truth_slides, bands_fixed, "
               "and each accepted case's slide_margin with --details)");
  app.add_option("--fixed-margin", options.fixed_margin,
                 "with --truth-slide: the least margin of a truth the maps fix, cells")
      ->capture_default_str()
      ->check(CLI::Range(0LL, 100000000LL));
  app.add_option("--save", options.save_dir,
                 "folder: write each run case's crops and crop B with A's walls at the truth");
  app.set_version_flag("--version", mrslam::versionLine("merge_cases"));
  CLI11_PARSE(app, argc, argv);
  mrslam::retainHeapForReuse();  // each merge reuses the last one's memory
  return run(options);
}
