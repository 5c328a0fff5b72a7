// mrslam_merge: offline merge of map files (map_server YAML, PGM/PNG pictures, Carpin .txt).
//
// Pairs: every pair of maps i < j, merged as merge(from = j, to = i), so each later map is placed
// in an earlier one's frame and map 0 is the frame of the merged picture. With --json one JSON
// object goes to standard output:
//   {"pairs": [{"from": j, "to": i, "accepted", "method", "affine": [[a, b, c], [d, e, f]],
//               "verification", "entropy", "time_ms", "reason"}]}
// where `affine` maps a pixel (column, row) of file `from` to a pixel of file `to`, row 0 being
// the first row of each file; `verification` (V = agr / (agr + dis)) and `entropy` (mean bits
// per merged cell) score that transform with the tools' scorer (overlap_score.hpp) whatever the
// method, accepted or not (a merger's own figures may be counted differently). Without --json a
// picture of the merged maps (one colour per map) is written to --out (default merged.png) and a
// summary printed; with --json the picture is written only when --out is given. Exit code 1 with a
// one-line reason when an input cannot be read.
//
// --judge A B C D E F (two maps only): no search; the affine of map 1 into map 0 (as --json
// prints it) is judged by the acceptance every merger ends with: the seed pipeline's block 9 with
// the config's `seed:` settings (the affine placed by its ±δ translation search first), then the
// wall alignment and its turn check. A chain's rival checks are not run. It says why a pair is
// refused at a place one believes right (from another method, a rendezvous, a survey).

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <queue>

#include "mrslam/common/heap.hpp"
#include "mrslam/common/logging.hpp"
#include "mrslam/common/map_loaders.hpp"
#include "mrslam/common/version.hpp"
#include "mrslam/fusion/merge/merge_cases.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"
#include "mrslam/fusion/merge/overlap_score.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"
#include "mrslam/fusion/merge/wall_alignment.hpp"

namespace {

using mrslam::GridMap;
using mrslam::fusion::GridTransform;
using mrslam::fusion::MergeResult;

constexpr double kPi = 3.14159265358979323846;

struct MergeOptions {
  std::vector<std::string> maps;
  std::string method = mrslam::fusion::defaultMergerName();
  std::string config;  ///< optional YAML: a section of settings per method name
  bool json = false;
  std::string out;
  double resolution_m = mrslam::kDefaultMapResolution;
  std::vector<double> judge;  ///< (a, b, c, d, e, f): the image affine of map 1 into map 0
};

struct PairResult {
  int from = 0;
  int to = 0;
  MergeResult result;
  double time_ms = 0.0;
  mrslam::fusion::OverlapScore score;  ///< V and H of result.T_to_from by the tools' scorer
  std::optional<GridTransform> given;  ///< --judge: the transform judged, before block 8
};

std::vector<GridMap> loadMaps(const MergeOptions& options) {
  std::vector<GridMap> maps;
  for (const std::string& path : options.maps) {
    maps.push_back(mrslam::loadMapFile(path, options.resolution_m));
    if (maps.back().geometry.resolution_m != maps.front().geometry.resolution_m) {
      throw mrslam::MapIoError(
          path + ": resolution " + std::to_string(maps.back().geometry.resolution_m) +
          " differs from the first map's " + std::to_string(maps.front().geometry.resolution_m));
    }
  }
  return maps;
}

std::vector<PairResult> mergePairs(const std::vector<GridMap>& maps,
                                   mrslam::fusion::MapMerger& merger) {
  std::vector<PairResult> pairs;
  for (int to = 0; to < static_cast<int>(maps.size()); ++to) {
    for (int from = to + 1; from < static_cast<int>(maps.size()); ++from) {
      PairResult pair{from, to, {}, 0.0, {}, std::nullopt};
      const auto start = std::chrono::steady_clock::now();
      pair.result =
          merger.merge(maps[static_cast<std::size_t>(from)], maps[static_cast<std::size_t>(to)]);
      pair.time_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      pair.score =
          mrslam::fusion::scoreOverlap(maps[static_cast<std::size_t>(from)],
                                       maps[static_cast<std::size_t>(to)], pair.result.T_to_from);
      pairs.push_back(pair);
    }
  }
  return pairs;
}

/// --judge: the given affine of map 1 into map 0, judged without a search.
PairResult judgeGiven(const std::vector<GridMap>& maps, const std::vector<double>& values,
                      mrslam::fusion::SeedMerger& judge) {
  mrslam::fusion::ImageAffine affine;
  affine << values[0], values[1], values[2], values[3], values[4], values[5];
  const GridMap& from = maps[1];
  const GridMap& to = maps[0];
  const GridTransform given =
      mrslam::fusion::imageAffineToGridTransform(affine, from.geometry.height, to.geometry.height);
  PairResult pair{1, 0, {}, 0.0, {}, given};
  const auto start = std::chrono::steady_clock::now();
  pair.result = judge.judgeHypotheses(from, to, {given});
  mrslam::fusion::alignAccepted(from, to, judge.settings().wall_alignment,
                                judge.settings().similarity, pair.result);
  pair.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  pair.score = mrslam::fusion::scoreOverlap(from, to, pair.result.T_to_from);
  return pair;
}

nlohmann::ordered_json toJson(const std::vector<PairResult>& pairs,
                              const std::vector<GridMap>& maps) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const PairResult& pair : pairs) {
    const mrslam::fusion::ImageAffine affine = mrslam::fusion::gridTransformToImageAffine(
        pair.result.T_to_from, maps[static_cast<std::size_t>(pair.from)].geometry.height,
        maps[static_cast<std::size_t>(pair.to)].geometry.height);
    list.push_back(
        {{"from", pair.from},
         {"to", pair.to},
         {"accepted", pair.result.accepted},
         {"method", pair.result.method},
         {"affine",
          {{affine(0, 0), affine(0, 1), affine(0, 2)}, {affine(1, 0), affine(1, 1), affine(1, 2)}}},
         {"verification", pair.score.verification()},
         {"entropy", pair.score.entropy_bits},
         {"time_ms", pair.time_ms},
         {"reason", pair.result.reason}});
  }
  return {{"pairs", list}};
}

/// T_0_k for every map reachable from map 0 over accepted pairs (breadth first).
std::vector<std::optional<GridTransform>> placeMaps(const std::vector<PairResult>& pairs,
                                                    std::size_t map_count) {
  std::vector<std::optional<GridTransform>> T_0_k(map_count);
  T_0_k[0] = GridTransform();
  std::queue<int> open;
  open.push(0);
  while (!open.empty()) {
    const int known = open.front();
    open.pop();
    for (const PairResult& pair : pairs) {
      if (!pair.result.accepted || (pair.from != known && pair.to != known)) {
        continue;
      }
      const bool forward = pair.to == known;  // T_known_other = T_to_from
      const int other = forward ? pair.from : pair.to;
      if (T_0_k[static_cast<std::size_t>(other)]) {
        continue;
      }
      const GridTransform T_known_other =
          forward ? pair.result.T_to_from : pair.result.T_to_from.inverse();
      T_0_k[static_cast<std::size_t>(other)] =
          mrslam::fusion::compose(*T_0_k[static_cast<std::size_t>(known)], T_known_other);
      open.push(other);
    }
  }
  return T_0_k;
}

cv::Vec3d colourOf(std::size_t map) {
  static const std::vector<cv::Vec3d> palette = {{200, 90, 20}, {20, 120, 230}, {40, 170, 40},
                                                 {40, 40, 210}, {170, 60, 160}, {160, 160, 0}};
  return palette[map % palette.size()];
}

/// One pixel of the merged picture: the maps' colours, dark where occupied, light where free.
cv::Vec3b mergedPixel(const std::vector<GridMap>& maps,
                      const std::vector<std::optional<GridTransform>>& T_k_0,
                      const Eigen::Vector2d& cell_0) {
  cv::Vec3d free_sum(0, 0, 0);
  cv::Vec3d occupied_sum(0, 0, 0);
  int free_count = 0;
  int occupied_count = 0;
  for (std::size_t k = 0; k < maps.size(); ++k) {
    if (!T_k_0[k]) {
      continue;
    }
    const Eigen::Vector2d p = T_k_0[k]->apply(cell_0);
    const int x = static_cast<int>(std::lround(p.x()));
    const int y = static_cast<int>(std::lround(p.y()));
    if (!maps[k].geometry.contains(x, y)) {
      continue;
    }
    const auto cell = mrslam::fusion::classOf(maps[k].at(x, y));
    if (cell == mrslam::fusion::CellClass::kOccupied) {
      occupied_sum += colourOf(k) * 0.6;
      ++occupied_count;
    } else if (cell == mrslam::fusion::CellClass::kFree) {
      free_sum += colourOf(k) * 0.25 + cv::Vec3d(255, 255, 255) * 0.75;
      ++free_count;
    }
  }
  const cv::Vec3d colour = occupied_count > 0 ? occupied_sum / occupied_count
                           : free_count > 0   ? free_sum / free_count
                                              : cv::Vec3d(128, 128, 128);
  return cv::Vec3b(cv::saturate_cast<uchar>(colour[0]), cv::saturate_cast<uchar>(colour[1]),
                   cv::saturate_cast<uchar>(colour[2]));
}

/// The placed maps drawn in map 0's cell frame, y up; returns false if the file is not written.
bool writeMergedPicture(const std::vector<GridMap>& maps,
                        const std::vector<std::optional<GridTransform>>& T_0_k,
                        const std::string& path) {
  Eigen::Vector2d low = Eigen::Vector2d::Constant(1e18);
  Eigen::Vector2d high = Eigen::Vector2d::Constant(-1e18);
  std::vector<std::optional<GridTransform>> T_k_0(maps.size());
  for (std::size_t k = 0; k < maps.size(); ++k) {
    if (!T_0_k[k]) {
      continue;
    }
    T_k_0[k] = T_0_k[k]->inverse();
    const double w = maps[k].geometry.width - 1.0;
    const double h = maps[k].geometry.height - 1.0;
    for (const Eigen::Vector2d& corner : {Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 0),
                                          Eigen::Vector2d(0, h), Eigen::Vector2d(w, h)}) {
      low = low.cwiseMin(T_0_k[k]->apply(corner));
      high = high.cwiseMax(T_0_k[k]->apply(corner));
    }
  }
  const Eigen::Vector2d origin = low.array().floor();
  const int width = static_cast<int>(std::ceil(high.x()) - origin.x()) + 1;
  const int height = static_cast<int>(std::ceil(high.y()) - origin.y()) + 1;
  cv::Mat picture(height, width, CV_8UC3);
  for (int row = 0; row < height; ++row) {
    for (int column = 0; column < width; ++column) {
      const Eigen::Vector2d cell_0 = origin + Eigen::Vector2d(column, height - 1 - row);
      picture.at<cv::Vec3b>(row, column) = mergedPixel(maps, T_k_0, cell_0);
    }
  }
  try {
    return cv::imwrite(path, picture);
  } catch (const cv::Exception&) {
    return false;
  }
}

void printSummary(const std::vector<PairResult>& pairs, const MergeOptions& options) {
  for (const PairResult& pair : pairs) {
    const MergeResult& r = pair.result;
    std::cout << "map " << pair.from << " (" << options.maps[static_cast<std::size_t>(pair.from)]
              << ") -> map " << pair.to << " (" << options.maps[static_cast<std::size_t>(pair.to)]
              << "): ";
    if (r.accepted) {
      std::cout << "accepted by " << r.method << ", turn " << r.T_to_from.theta_rad * 180.0 / kPi
                << " deg, shift (" << r.T_to_from.t_cells.x() << ", " << r.T_to_from.t_cells.y()
                << ") cells";
    } else {
      std::cout << "refused by " << r.method << " (" << r.reason << ")";
    }
    std::cout << ", V " << pair.score.verification() << ", H " << pair.score.entropy_bits
              << " bit/cell, " << pair.time_ms << " ms";
    if (pair.given) {
      const GridTransform moved = mrslam::fusion::compose(pair.given->inverse(), r.T_to_from);
      std::cout << "; judged " << moved.t_cells.norm() << " cells and "
                << std::abs(moved.theta_rad) * 180.0 / kPi << " deg from the given transform";
    }
    std::cout << '\n';
  }
}

int run(const MergeOptions& options) {
  std::vector<GridMap> maps;
  std::unique_ptr<mrslam::fusion::MapMerger> merger;
  std::unique_ptr<mrslam::fusion::SeedMerger> judge;
  try {
    maps = loadMaps(options);
    if (!options.judge.empty() && maps.size() != 2) {
      throw std::invalid_argument(
          "--judge takes exactly two maps (the affine of map 1 into map 0)");
    }
    const mrslam::Config config = options.config.empty()
                                      ? mrslam::Config::loadString("", "<defaults>")
                                      : mrslam::Config::loadFile(options.config);
    mrslam::fusion::checkMergerConfig(config);
    merger = mrslam::fusion::makeMergerFrom(options.method, config);
    if (!options.judge.empty()) {
      judge = std::make_unique<mrslam::fusion::SeedMerger>(
          mrslam::fusion::loadSeedMergerSettings(config.section("seed")));
    }
  } catch (const std::exception& error) {  // MapIoError, ConfigError, unknown method
    std::cerr << "mrslam_merge: " << error.what() << '\n';
    return 1;
  }
  const std::vector<PairResult> pairs =
      judge ? std::vector<PairResult>{judgeGiven(maps, options.judge, *judge)}
            : mergePairs(maps, *merger);
  const std::string out = options.out.empty() && !options.json ? "merged.png" : options.out;
  const std::vector<std::optional<GridTransform>> T_0_k = placeMaps(pairs, maps.size());
  if (!out.empty() && !writeMergedPicture(maps, T_0_k, out)) {
    std::cerr << "mrslam_merge: " << out << ": cannot write the merged picture\n";
    return 1;
  }
  if (options.json) {
    std::cout << toJson(pairs, maps).dump() << '\n';
  } else {
    printSummary(pairs, options);
    std::cout << "merged picture: " << out << ", maps placed in map 0's frame:";
    for (std::size_t k = 0; k < T_0_k.size(); ++k) {
      std::cout << (T_0_k[k] ? " " + std::to_string(k) : "");
    }
    std::cout << '\n';
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  mrslam::logToStandardError("mrslam_merge");
  MergeOptions options;
  CLI::App app{"Merges occupancy grid maps (YAML, PGM, PNG, Carpin .txt) pairwise"};
  app.add_option("maps", options.maps, "two or more map files")->required()->expected(2, -1);
  app.add_option(
         "--method", options.method,
         "merger: " +
             [] {
               std::string names;
               for (const std::string& name : mrslam::fusion::mergerNames()) {
                 names += (names.empty() ? "" : ", ") + name;
               }
               return names +
                      ", or chain:STEP+STEP[+psi] (a chain of those steps, refined by psi "
                      "when it ends in psi)";
             }())
      ->capture_default_str();
  app.add_option("--config", options.config,
                 "YAML of merger settings, one section per method (feature: {detector: orb})");
  app.add_flag("--json", options.json, "print one JSON object of the pair results");
  app.add_option("--out", options.out, "merged picture (default merged.png without --json)");
  app.add_option("--resolution", options.resolution_m, "metres per cell of pictures and .txt")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--judge", options.judge,
                 "judge this affine of map 1 into map 0 (A B C D E F, as --json prints it) "
                 "without a search: the acceptance's verdict and reason")
      ->expected(6);
  app.set_version_flag("--version", mrslam::versionLine("merge"));
  CLI11_PARSE(app, argc, argv);
  mrslam::retainHeapForReuse();  // each merge reuses the last one's memory
  return run(options);
}
