// Standard output carries only a program's result: the robot agent prints nothing there (its
// log and summary go to standard error), the evaluation its table, the merge its JSON.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "test_data.hpp"

namespace mrslam::test {
namespace {

struct Streams {
  int exit_code = -1;
  std::string out;
  std::string err;
};

std::string contentOf(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Runs a program of the build tree with its standard output and error in separate files.
Streams runSplit(const std::string& program, const std::string& arguments) {
  const auto folder = scratchFolder("streams");
  const std::string command = "'" + binaryPath(program) + "' " + arguments + " > '" +
                              (folder / "out").string() + "' 2> '" + (folder / "err").string() +
                              "'";
  Streams streams;
  streams.exit_code = std::system(command.c_str());
  streams.out = contentOf(folder / "out");
  streams.err = contentOf(folder / "err");
  return streams;
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) {
    lines.push_back(line);
  }
  return lines;
}

const std::string kSmallLog = "tests/fuzz/corpus/carmen_reader/small.log";

TEST(StandardOutputTest, TheRobotAgentLogsToStandardErrorOnly) {
  const Streams run =
      runSplit("robot_agent/robot_agent", "--config-dir '" + sourcePath("config") + "' '" +
                                              sourcePath(kSmallLog) + "' --no-dds --speed 0");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, "");
  EXPECT_NE(run.err.find("carmen: SLAM: 3 scans"), std::string::npos) << run.err;
}

TEST(StandardOutputTest, TheEvaluationPrintsOnlyItsTable) {
  const Streams run =
      runSplit("tools/mrslam_evaluate_trajectory", "--config-dir '" + sourcePath("config") + "' '" +
                                                       sourcePath(kSmallLog) + "' --runs odometry");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::vector<std::string> lines = linesOf(run.out);
  ASSERT_EQ(lines.size(), 3u) << run.out;  // header, rule, the odometry run
  for (const std::string& line : lines) {
    EXPECT_EQ(line.rfind("|", 0), 0u) << line;
  }
}

TEST(StandardOutputTest, TheMergeJsonParsesWhole) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  const std::string map = "'" + sharedDataPath("maps/carpin-intel.txt") + "'";
  const Streams run = runSplit("tools/mrslam_merge", map + " " + map + " --method feature --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);  // throws on anything else
  ASSERT_EQ(json["pairs"].size(), 1u);
  EXPECT_TRUE(json["pairs"][0]["accepted"].get<bool>());
}

// ./mrslam checks that nothing needs building before it runs a command: when nothing does, it
// says nothing, and the command's JSON is all of standard output.
TEST(StandardOutputTest, TheEntryPointAddsNothingWhenTheBuildIsUpToDate) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  if (!std::filesystem::exists(binaryPath(".up-to-date-tests"))) {
    GTEST_SKIP() << "needs a build made by ./mrslam test (its stamp "
                 << binaryPath(".up-to-date-tests") << ")";
  }
  const auto folder = scratchFolder("entry");
  const std::string map = "'" + sharedDataPath("maps/carpin-intel.txt") + "'";
  const std::string command = "MRSLAM_BUILD_DIR='" + binaryPath("") + "' '" + sourcePath("mrslam") +
                              "' merge " + map + " " + map + " --method feature --json > '" +
                              (folder / "out").string() + "' 2> '" + (folder / "err").string() +
                              "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << contentOf(folder / "err");
  EXPECT_EQ(contentOf(folder / "err"), "");
  const nlohmann::json json = nlohmann::json::parse(contentOf(folder / "out"));
  EXPECT_EQ(json["pairs"].size(), 1u);
}

}  // namespace
}  // namespace mrslam::test
