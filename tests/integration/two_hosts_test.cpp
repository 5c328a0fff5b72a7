// Two hosts: a fusion agent and a Discovery Server in one network namespace, a robot agent in
// another, joined only by a veth pair that the test creates (root needed, as in CI). UDP only:
// the participants' profile has no shared memory, so the map crosses the virtual wire.

#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "agent_processes.hpp"

namespace mrslam::test {
namespace {

constexpr const char* kIp = "/usr/sbin/ip";

int run(const std::vector<std::string>& argv, const std::filesystem::path& log) {
  tools::ChildProcess process(argv, log.string());
  const auto code = process.waitFor(20.0);
  return code ? *code : -1;
}

// A config of `source` with UDP only and absolute profile paths (it lives in a scratch folder).
std::string udpConfig(const std::string& source, const std::filesystem::path& folder,
                      const std::string& name) {
  std::string text = fileText(sourcePath(source));
  text = std::regex_replace(
      text, std::regex("\ndds:\n"),
      "\ndds:\n  participant_profile: mrslam_participant_udp\n  profiles_file: " +
          sourcePath("config/dds/profiles.xml") + "\n");
  const std::string path = (folder / name).string();
  std::ofstream(path) << text;
  return path;
}

class TwoHostsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (::geteuid() != 0) {
      GTEST_SKIP() << "network namespaces need root";
    }
    folder_ = scratchFolder("hosts");
    const std::string id = std::to_string(getpid() % 100000);
    host_a_ = "mrslam_a" + id;
    host_b_ = "mrslam_b" + id;
    subnet_ = "10." + std::to_string(100 + getpid() % 100) + "." + std::to_string(getpid() % 250);
    const std::string veth_a = "mra" + id;
    const std::string veth_b = "mrb" + id;
    const std::vector<std::vector<std::string>> steps = {
        {kIp, "netns", "add", host_a_},
        {kIp, "netns", "add", host_b_},
        {kIp, "link", "add", veth_a, "type", "veth", "peer", "name", veth_b},
        {kIp, "link", "set", veth_a, "netns", host_a_},
        {kIp, "link", "set", veth_b, "netns", host_b_},
        {kIp, "-n", host_a_, "addr", "add", subnet_ + ".1/24", "dev", veth_a},
        {kIp, "-n", host_b_, "addr", "add", subnet_ + ".2/24", "dev", veth_b},
        {kIp, "-n", host_a_, "link", "set", veth_a, "up"},
        {kIp, "-n", host_b_, "link", "set", veth_b, "up"},
        {kIp, "-n", host_a_, "link", "set", "lo", "up"},
        {kIp, "-n", host_b_, "link", "set", "lo", "up"},
    };
    for (const auto& step : steps) {
      ASSERT_EQ(run(step, folder_ / "ip.log"), 0) << fileText(folder_ / "ip.log");
    }
    created_ = true;
  }
  void TearDown() override {
    processes_.clear();  // killed before their namespaces go
    if (created_) {
      run({kIp, "netns", "del", host_a_}, folder_ / "ip_del.log");
      run({kIp, "netns", "del", host_b_}, folder_ / "ip_del.log");
    }
  }

  tools::ChildProcess& startIn(const std::string& host, std::vector<std::string> argv,
                               const std::string& log) {
    argv.insert(argv.begin(), {kIp, "netns", "exec", host});
    processes_.push_back(std::make_unique<tools::ChildProcess>(argv, (folder_ / log).string()));
    return *processes_.back();
  }

  std::filesystem::path folder_;
  std::string host_a_, host_b_, subnet_;
  bool created_ = false;
  std::vector<std::unique_ptr<tools::ChildProcess>> processes_;
};

TEST_F(TwoHostsTest, ARobotOnOneHostReachesTheFusionAgentOnAnotherThroughTheServer) {
  const std::string server = subnet_ + ".1:11811";
  startIn(host_a_,
          {"/usr/bin/fast-discovery-server", "-i", "0", "-l", subnet_ + ".1", "-p", "11811"},
          "server.log");
  tools::ChildProcess& fusion =
      startIn(host_a_,
              {binaryPath("fusion_agent/fusion_agent"), "--config",
               udpConfig("config/sim_fusion.yaml", folder_, "fusion.yaml"), "--out",
               (folder_ / "out").string(), "--discovery-server", server, "--max-runtime", "90"},
              "fusion.log");
  tools::ChildProcess& robot = startIn(
      host_b_,
      {binaryPath("robot_agent/robot_agent"), "--config",
       udpConfig("config/sim_robot1.yaml", folder_, "robot1.yaml"), "--discovery-server", server},
      "robot1.log");
  ASSERT_TRUE(waitForLog(folder_ / "fusion.log", "final map 60 of robot1 received", 1, 60.0))
      << logOf(fusion) << "\n"
      << logOf(robot);
  EXPECT_EQ(finish(robot, 60.0), 0) << logOf(robot);  // it saw its final map taken
  fusion.signal(SIGINT);
  ASSERT_EQ(finish(fusion, 60.0), 0) << logOf(fusion);
  std::ifstream robots_file(folder_ / "out" / "robots.json");
  const nlohmann::json robots = nlohmann::json::parse(robots_file);
  ASSERT_EQ(robots["robots"].size(), 1u);
  EXPECT_TRUE(robots["robots"][0]["final"].get<bool>());
  EXPECT_EQ(robots["robots"][0]["scans_inserted"], 600);
}

}  // namespace
}  // namespace mrslam::test
