// A robot agent on its devices, exactly as on a robot but with the devices emulated behind real
// pseudo-terminals (the emulator programs as separate processes): it reads scans and IMU
// samples, stops cleanly on Ctrl-C, writes its map and records what it read.

#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <sstream>
#include <thread>

#include "agent_processes.hpp"
#include "mrslam/common/map_io.hpp"

namespace mrslam::test {
namespace {

std::size_t linesStartingWith(const std::string& text, const std::string& prefix) {
  std::size_t count = 0;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    count += line.rfind(prefix, 0) == 0;
  }
  return count;
}

// Waits (bounded) until `path` exists.
bool appears(const std::filesystem::path& path) {
  for (int i = 0; i < 200 && !std::filesystem::exists(path); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  return std::filesystem::exists(path);
}

TEST(DevicesAgentTest, TheAgentReadsEmulatedDevicesAndStopsCleanlyOnCtrlC) {
  const auto out = scratchFolder("run");
  const auto laser_link = out / "ttyACM0";
  const auto imu_link = out / "ttyS0";
  auto laser = startAgent("tools/mrslam_hokuyo_emulator",
                          {laser_link.string(), "--pattern", "room"}, (out / "laser.log").string());
  auto imu =
      startAgent("tools/mrslam_gx1_emulator", {imu_link.string()}, (out / "imu.log").string());
  ASSERT_TRUE(appears(laser_link)) << logOf(*laser);
  ASSERT_TRUE(appears(imu_link)) << logOf(*imu);

  const std::string config = (out / "robot.yaml").string();
  std::ofstream(config) << "robot_id: coroware1\nsource:\n  type: devices\n  devices:\n"
                        << "    laser:\n      device: " << laser_link.string()
                        << "\n      fallback: none\n    imu:\n      device: " << imu_link.string()
                        << "\n      fallback: none\npublish:\n  map_period_s: 0.5\n";
  auto agent = startAgent("robot_agent/robot_agent",
                          {"--config", config, "--no-dds", "--out", (out / "map").string(),
                           "--record", (out / "recorded.log").string()},
                          (out / "agent.log").string());
  // Until the agent has recorded some of each kind (bounded), then Ctrl-C.
  for (int i = 0; i < 400; ++i) {
    const std::string recorded = fileText(out / "recorded.log");
    if (linesStartingWith(recorded, "LASER") >= 10 && linesStartingWith(recorded, "IMU") >= 10) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  agent->signal(SIGINT);
  ASSERT_EQ(finish(*agent, 30.0), 0) << logOf(*agent);

  const std::string recorded = fileText(out / "recorded.log");
  EXPECT_GE(linesStartingWith(recorded, "LASER"), 10u);
  EXPECT_GE(linesStartingWith(recorded, "IMU"), 10u);
  const std::string log = fileText(out / "agent.log");
  EXPECT_NE(log.find("laser: reading its device"), std::string::npos) << log;
  EXPECT_NE(log.find("imu: reading its device"), std::string::npos) << log;
  const GridMap map = loadMapYaml((out / "map" / "coroware1.yaml").string());
  std::size_t occupied = 0;
  for (const std::int8_t cell : map.cells) {
    occupied += cell > 50;
  }
  EXPECT_GT(occupied, 100u) << "the emulated room's walls are in the map";
}

}  // namespace
}  // namespace mrslam::test
