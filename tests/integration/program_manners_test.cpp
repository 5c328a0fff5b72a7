// Every program a user runs answers --version and --help, and refuses an unknown flag with a
// message that names it.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "agent_processes.hpp"

namespace mrslam::test {
namespace {

struct Program {
  const char* path;                     ///< in the build tree
  const char* name;                     ///< in its --version line
  std::vector<std::string> required{};  ///< its required options, so a flag is the only mistake
};

const Program kPrograms[] = {
    {"robot_agent/robot_agent", "robot_agent"},
    {"fusion_agent/fusion_agent", "fusion_agent", {"--config", "x.yaml"}},
    {"tools/mrslam_demo", "demo", {"--config-dir", "x", "--bin-dir", "y"}},
    {"tools/mrslam_team", "team", {"--bin-dir", "y"}},
    {"tools/mrslam_merge", "merge"},
    {"tools/mrslam_merge_cases", "merge_cases"},
    {"tools/mrslam_split_log", "split_log", {"--out", "y"}},
    {"tools/mrslam_evaluate_trajectory", "evaluate_trajectory"},
    {"tools/mrslam_scan", "scan"},
    {"tools/mrslam_imu", "imu"},
    {"tools/mrslam_hokuyo_emulator", "hokuyo_emulator"},
    {"tools/mrslam_gx1_emulator", "gx1_emulator"},
};

// Runs a program with `arguments`; returns its exit code and, in `output`, what it printed.
int run(const std::string& program, const std::vector<std::string>& arguments,
        const std::filesystem::path& folder, std::string& output) {
  const std::string log = (folder / "output.log").string();
  auto child = startAgent(program, arguments, log);
  const int code = finish(*child, 30.0);
  std::ifstream file(log);
  std::stringstream text;
  text << file.rdbuf();
  output = text.str();
  return code;
}

TEST(ProgramMannersTest, EveryProgramAnswersVersionAndHelp) {
  const auto folder = scratchFolder("run");
  for (const Program& program : kPrograms) {
    std::string output;
    EXPECT_EQ(run(program.path, {"--version"}, folder, output), 0) << program.path;
    EXPECT_EQ(output, "mrslam " + std::string(program.name) + " 0.1.0\n") << program.path;
    EXPECT_EQ(run(program.path, {"--help"}, folder, output), 0) << program.path;
    EXPECT_NE(output.find("Usage:"), std::string::npos) << program.path << ":\n" << output;
  }
}

TEST(ProgramMannersTest, AnUnknownFlagIsRefusedByName) {
  const auto folder = scratchFolder("run");
  for (const Program& program : kPrograms) {
    std::string output;
    // Positional arguments and required options first, so that the flag is the only mistake.
    std::vector<std::string> arguments = program.required;
    arguments.insert(arguments.end(), {"a", "b", "--no-such-flag"});
    EXPECT_NE(run(program.path, arguments, folder, output), 0) << program.path;
    EXPECT_NE(output.find("--no-such-flag"), std::string::npos) << program.path << ":\n" << output;
  }
}

}  // namespace
}  // namespace mrslam::test
