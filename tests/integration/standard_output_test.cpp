// Standard output carries only a program's result: the robot agent prints nothing there (its
// log and summary go to standard error), the evaluation its table, the merge its JSON.

#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "agent_processes.hpp"

namespace mrslam::test {
namespace {

struct Streams {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Runs a program of the build tree with its standard output and error in separate files.
Streams runSplit(const std::string& program, const std::string& arguments) {
  const auto folder = scratchFolder("streams");
  const std::string command = "'" + binaryPath(program) + "' " + arguments + " > '" +
                              (folder / "out").string() + "' 2> '" + (folder / "err").string() +
                              "'";
  Streams streams;
  streams.exit_code = std::system(command.c_str());
  streams.out = fileText(folder / "out");
  streams.err = fileText(folder / "err");
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
  // A test must never start a build while the others run: with a source newer than the last
  // ./mrslam build (a build made by hand), there is nothing this test can check.
  const std::string entry =
      "MRSLAM_NO_BUILD=1 MRSLAM_BUILD_DIR='" + binaryPath("") + "' '" + sourcePath("mrslam") + "'";
  if (std::system((entry + " built").c_str()) != 0) {
    GTEST_SKIP() << "a source changed since the last ./mrslam build of " << binaryPath("");
  }
  const auto folder = scratchFolder("entry");
  const std::string map = "'" + sharedDataPath("maps/carpin-intel.txt") + "'";
  const std::string command = entry + " merge " + map + " " + map + " --method feature --json > '" +
                              (folder / "out").string() + "' 2> '" + (folder / "err").string() +
                              "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << fileText(folder / "err");
  EXPECT_EQ(fileText(folder / "err"), "");
  const nlohmann::json json = nlohmann::json::parse(fileText(folder / "out"));
  EXPECT_EQ(json["pairs"].size(), 1u);
}

}  // namespace
}  // namespace mrslam::test
