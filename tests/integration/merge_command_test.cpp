// mrslam_merge as a separate process: JSON output, the affine in the files' pixel coordinates,
// the merged picture and the exit code for unreadable inputs.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>

#include "agent_processes.hpp"
#include "mrslam/common/map_io.hpp"
#include "mrslam/common/map_loaders.hpp"
#include "mrslam/fusion/merge/chain_merger.hpp"
#include "mrslam/fusion/merge/merge_cases.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"
#include "mrslam/fusion/merge/overlap_score.hpp"

namespace mrslam::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

CommandRun runMerge(const std::vector<std::string>& arguments,
                    const std::filesystem::path& folder) {
  return runToEnd("tools/mrslam_merge", arguments, (folder / "merge.log").string(), 120.0);
}

/// The last line of the output that holds a JSON object.
nlohmann::json lastJsonLine(const std::string& output) {
  std::istringstream lines(output);
  std::string json_line;
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line.front() == '{') {
      json_line = line;
    }
  }
  return nlohmann::json::parse(json_line);
}

fusion::CropSpec specOf(int x, int y, int size, double theta_rad, int pad) {
  fusion::CropSpec spec;
  spec.corner = Eigen::Vector2i(x, y);
  spec.size = size;
  spec.theta_rad = theta_rad;
  spec.pad_low = Eigen::Vector2i(pad, 3 * pad);
  spec.pad_high = Eigen::Vector2i(2 * pad, pad);
  return spec;
}

/// Pixel (column, row from the top) of a crop where source cell `s` lands.
Eigen::Vector2d pixelOf(const fusion::Crop& crop, const Eigen::Vector2d& s) {
  const Eigen::Vector2d cell = crop.T_crop_source.apply(s);
  return Eigen::Vector2d(cell.x(), crop.map.geometry.height - 1.0 - cell.y());
}

TEST(MergeCommandTest, JsonAffineMapsPixelsOfOneFileOntoTheOther) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  const auto folder = scratchFolder("affine");
  const GridMap intel = loadMapFile(sharedDataPath("maps/carpin-intel.txt"));
  const fusion::CropSpec spec_0 = specOf(150, 200, 320, 20.0 * kPi / 180.0, 10);
  const fusion::CropSpec spec_1 = specOf(220, 240, 320, -50.0 * kPi / 180.0, 30);
  const fusion::Crop crop_0 = fusion::cutCrop(intel, spec_0);
  const fusion::Crop crop_1 = fusion::cutCrop(intel, spec_1);
  // Map 0 as a map_server YAML (+ PGM), map 1 as a bare PGM.
  saveMapYaml(crop_0.map, (folder / "zero.yaml").string());
  saveMapYaml(crop_1.map, (folder / "one.yaml").string());
  const CommandRun run = runMerge({(folder / "zero.yaml").string(), (folder / "one.pgm").string(),
                                   "--method", "feature", "--json"},
                                  folder);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json json = lastJsonLine(run.output);
  ASSERT_EQ(json["pairs"].size(), 1u) << json.dump();
  const nlohmann::json& pair = json["pairs"][0];
  EXPECT_EQ(pair["from"], 1);
  EXPECT_EQ(pair["to"], 0);
  ASSERT_TRUE(pair["accepted"].get<bool>()) << pair.dump();
  EXPECT_EQ(pair["method"], "feature");
  EXPECT_GT(pair["verification"].get<double>(), 0.9);
  EXPECT_GE(pair["time_ms"].get<double>(), 0.0);
  const auto affine = pair["affine"].get<std::vector<std::vector<double>>>();
  ASSERT_EQ(affine.size(), 2u);
  // Source cells spread over the shared part land at the same place through the affine.
  for (const Eigen::Vector2d& source :
       {Eigen::Vector2d(300, 330), Eigen::Vector2d(240, 420), Eigen::Vector2d(420, 300)}) {
    const Eigen::Vector2d p1 = pixelOf(crop_1, source);
    const Eigen::Vector2d expected = pixelOf(crop_0, source);
    const Eigen::Vector2d mapped(affine[0][0] * p1.x() + affine[0][1] * p1.y() + affine[0][2],
                                 affine[1][0] * p1.x() + affine[1][1] * p1.y() + affine[1][2]);
    EXPECT_LT((mapped - expected).norm(), 2.0)
        << source.transpose() << " → " << mapped.transpose() << " vs " << expected.transpose();
  }
  // The turn of file 1's pixels onto file 0's: +70° in the grid is −70° in the pictures.
  EXPECT_NEAR(std::atan2(affine[1][0], affine[0][0]), -70.0 * kPi / 180.0, 1.0 * kPi / 180.0);
}

/// The six numbers of --judge: the image affine of crop 1's pixels onto crop 0's for T_0_1.
std::vector<std::string> judgeArguments(const fusion::GridTransform& T_0_1, const GridMap& map_1,
                                        const GridMap& map_0) {
  const fusion::ImageAffine affine =
      fusion::gridTransformToImageAffine(T_0_1, map_1.geometry.height, map_0.geometry.height);
  std::vector<std::string> arguments{"--judge"};
  for (int row = 0; row < 2; ++row) {
    for (int column = 0; column < 3; ++column) {
      std::ostringstream number;
      number.precision(17);
      number << affine(row, column);
      arguments.push_back(number.str());
    }
  }
  return arguments;
}

TEST(MergeCommandTest, JudgeGivesTheAcceptancesVerdictOnAGivenAffine) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  const auto folder = scratchFolder("judge");
  const GridMap intel = loadMapFile(sharedDataPath("maps/carpin-intel.txt"));
  const fusion::Crop crop_0 = fusion::cutCrop(intel, specOf(150, 200, 320, 0.35, 10));
  const fusion::Crop crop_1 = fusion::cutCrop(intel, specOf(220, 240, 320, -0.87, 30));
  saveMapYaml(crop_0.map, (folder / "zero.yaml").string());
  saveMapYaml(crop_1.map, (folder / "one.yaml").string());
  const std::vector<std::string> maps{(folder / "zero.yaml").string(),
                                      (folder / "one.yaml").string()};
  const fusion::GridTransform T_0_1 =
      fusion::compose(crop_0.T_crop_source, crop_1.T_crop_source.inverse());
  const auto judged = [&](const fusion::GridTransform& T_given) {
    std::vector<std::string> arguments = maps;
    for (const std::string& argument : judgeArguments(T_given, crop_1.map, crop_0.map)) {
      arguments.push_back(argument);
    }
    arguments.push_back("--json");
    const CommandRun run = runMerge(arguments, folder);
    EXPECT_EQ(run.exit_code, 0) << run.output;
    const nlohmann::json pairs = lastJsonLine(run.output)["pairs"];
    EXPECT_EQ(pairs.size(), 1u) << pairs.dump();
    return pairs.at(0);
  };
  // The truth, 3 cells and 0.5° off: accepted, and placed back within the tolerance.
  fusion::GridTransform near_truth = T_0_1;
  near_truth.theta_rad += 0.5 * kPi / 180.0;
  near_truth.t_cells += Eigen::Vector2d(3.0, 0.0);
  const nlohmann::json right = judged(near_truth);
  ASSERT_TRUE(right["accepted"].get<bool>()) << right.dump();
  EXPECT_EQ(right["method"], "seed/given");
  const auto affine = right["affine"].get<std::vector<std::vector<double>>>();
  fusion::ImageAffine found;
  found << affine[0][0], affine[0][1], affine[0][2], affine[1][0], affine[1][1], affine[1][2];
  const fusion::GridTransform error = fusion::compose(
      T_0_1.inverse(), fusion::imageAffineToGridTransform(found, crop_1.map.geometry.height,
                                                          crop_0.map.geometry.height));
  EXPECT_LT(error.t_cells.norm(), fusion::kSuccessDistanceCells) << right.dump();
  EXPECT_LT(std::abs(error.theta_rad), 1.0 * kPi / 180.0) << right.dump();
  // The same maps a quarter turn off: refused, and the reason says why.
  fusion::GridTransform turned = T_0_1;
  turned.theta_rad += kPi / 2.0;
  const nlohmann::json wrong = judged(turned);
  EXPECT_FALSE(wrong["accepted"].get<bool>()) << wrong.dump();
  EXPECT_FALSE(wrong["reason"].get<std::string>().empty()) << wrong.dump();
  // Without --json: the verdict and how far the judged transform lies from the given one.
  std::vector<std::string> arguments = maps;
  for (const std::string& argument : judgeArguments(near_truth, crop_1.map, crop_0.map)) {
    arguments.push_back(argument);
  }
  arguments.insert(arguments.end(), {"--out", (folder / "judged.png").string()});
  const CommandRun summary = runMerge(arguments, folder);
  ASSERT_EQ(summary.exit_code, 0) << summary.output;
  EXPECT_THAT(summary.output, ::testing::HasSubstr("accepted by seed/given"));
  EXPECT_THAT(summary.output, ::testing::HasSubstr("from the given transform"));
}

TEST(MergeCommandTest, JudgeTakesExactlyTwoMaps) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  const auto folder = scratchFolder("judge_three");
  const std::string map = sharedDataPath("maps/carpin-robot0_cast.txt");
  const CommandRun run =
      runMerge({map, map, map, "--judge", "1", "0", "0", "0", "1", "0", "--json"}, folder);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.output, ::testing::HasSubstr("--judge takes exactly two maps"));
}

TEST(MergeCommandTest, WritesTheMergedPictureAndASummaryWithoutJson) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot1_cast.txt");
  const auto folder = scratchFolder("picture");
  const std::string out = (folder / "merged.png").string();
  const CommandRun run =
      runMerge({sharedDataPath("maps/carpin-robot0_cast.txt"),
                sharedDataPath("maps/carpin-robot1_cast.txt"), "--method", "feature", "--out", out},
               folder);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, ::testing::HasSubstr("map 1"));
  const cv::Mat picture = cv::imread(out, cv::IMREAD_COLOR);
  ASSERT_FALSE(picture.empty());
  EXPECT_GE(picture.cols, 450);  // at least map 0 (450 × 300 cells)
  EXPECT_GE(picture.rows, 300);
}

TEST(MergeCommandTest, ThreeMapsGiveEveryPairOnce) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  const auto folder = scratchFolder("three");
  const std::string map = sharedDataPath("maps/carpin-robot0_cast.txt");
  const CommandRun run = runMerge({map, map, map, "--method", "feature", "--json"}, folder);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json pairs = lastJsonLine(run.output)["pairs"];
  ASSERT_EQ(pairs.size(), 3u);
  std::set<std::pair<int, int>> seen;
  for (const auto& pair : pairs) {
    EXPECT_LT(pair["to"].get<int>(), pair["from"].get<int>());
    seen.insert({pair["from"].get<int>(), pair["to"].get<int>()});
    // A map against itself: the identity.
    ASSERT_TRUE(pair["accepted"].get<bool>()) << pair.dump();
    const auto affine = pair["affine"].get<std::vector<std::vector<double>>>();
    EXPECT_NEAR(affine[0][2], 0.0, 1.0);
    EXPECT_NEAR(affine[1][2], 0.0, 1.0);
    EXPECT_NEAR(affine[0][0], 1.0, 1e-3);
  }
  EXPECT_EQ(seen.size(), 3u);
}

TEST(MergeCommandTest, TheDefaultMethodIsTheRegistrysBest) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot1_cast.txt");
  const auto folder = scratchFolder("default");
  const CommandRun run = runMerge({sharedDataPath("maps/carpin-robot0_cast.txt"),
                                   sharedDataPath("maps/carpin-robot1_cast.txt"), "--json"},
                                  folder);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json pairs = lastJsonLine(run.output)["pairs"];
  ASSERT_EQ(pairs.size(), 1u);
  // The best merger is the chain: its result names the step that produced it (and after a slash
  // the stage of that step).
  ASSERT_EQ(fusion::defaultMergerName(), "chain");
  const std::string method = pairs[0]["method"].get<std::string>();
  const std::vector<std::string> steps = fusion::parseChainSteps(fusion::kDefaultChainSteps);
  EXPECT_TRUE(std::any_of(steps.begin(), steps.end(), [&](const std::string& step) {
    return method.rfind(step, 0) == 0;
  })) << method;
}

TEST(MergeCommandTest, AMissingFileStopsWithItsPathOnOneLine) {
  const auto folder = scratchFolder("missing");
  const std::string missing = (folder / "nowhere.pgm").string();
  const std::string junk = (folder / "junk.txt").string();
  std::ofstream(junk) << "0 255\n255\n";
  for (const auto& arguments :
       {std::vector<std::string>{missing, junk}, std::vector<std::string>{junk, junk, "--json"}}) {
    const CommandRun run = runMerge(arguments, folder);
    EXPECT_NE(run.exit_code, 0) << run.output;
    EXPECT_THAT(run.output, ::testing::StartsWith("mrslam_merge: " + arguments.front() + ": "));
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
  }
}

TEST(MergeCommandTest, AnUnknownMethodIsRefused) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  const auto folder = scratchFolder("method");
  const std::string map = sharedDataPath("maps/carpin-robot0_cast.txt");
  const CommandRun run = runMerge({map, map, "--method", "magic"}, folder);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.output, ::testing::HasSubstr("magic"));
}

}  // namespace
}  // namespace mrslam::test
