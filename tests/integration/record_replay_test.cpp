// robot_agent --record writes every sample it reads to an mrslam log; replaying that log with the
// same robot config gives the same trajectory and the same map, bit for bit.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "agent_processes.hpp"

namespace mrslam::test {
namespace {

std::string contentOf(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Runs the robot agent offline with `arguments`; fails the test when it does not end well.
void runOffline(std::vector<std::string> arguments, const std::filesystem::path& log) {
  arguments.push_back("--no-dds");
  auto agent = startAgent("robot_agent/robot_agent", arguments, log.string());
  ASSERT_EQ(finish(*agent, 120.0), 0) << logOf(*agent);
}

void expectRecordingReplaysTheRun(const std::string& config, std::vector<std::string> source,
                                  const std::string& robot_id) {
  const auto out = scratchFolder("run");
  std::vector<std::string> first = source;
  first.insert(first.end(), {"--config", sourcePath(config), "--record",
                             (out / "recorded.log").string(), "--trajectory-out",
                             (out / "first.tum").string(), "--out", (out / "first").string()});
  runOffline(first, out / "first.txt");
  runOffline(
      {"--config", sourcePath(config), "--log", (out / "recorded.log").string(), "--trajectory-out",
       (out / "replayed.tum").string(), "--out", (out / "replayed").string()},
      out / "replayed.txt");
  const std::string trajectory = contentOf(out / "first.tum");
  EXPECT_GT(std::count(trajectory.begin(), trajectory.end(), '\n'), 100);
  EXPECT_EQ(trajectory, contentOf(out / "replayed.tum"));
  const std::string map = contentOf(out / "first" / (robot_id + ".pgm"));
  EXPECT_FALSE(map.empty());
  EXPECT_EQ(map, contentOf(out / "replayed" / (robot_id + ".pgm")));
  EXPECT_EQ(contentOf(out / "recorded.log").rfind("# mrslam log", 0), 0u);
}

TEST(RecordReplayTest, ASimulatedRunWithImuReplaysIdentically) {
  expectRecordingReplaysTheRun("config/sim_robot1.yaml", {}, "robot1");
}

TEST(RecordReplayTest, ARealLogReplaysIdenticallyFromItsRecording) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/breezyslam-exp1.dat");
  expectRecordingReplaysTheRun("config/breezyslam.yaml",
                               {"--log", sharedDataPath("logs/breezyslam-exp1.dat")}, "breezyslam");
}

}  // namespace
}  // namespace mrslam::test
