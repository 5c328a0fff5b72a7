#pragma once
// Helpers of the integration tests: real robot and fusion agents as separate processes.

#include <unistd.h>

#include <memory>
#include <string>
#include <vector>

#include "mrslam/tools/child_process.hpp"
#include "test_data.hpp"

namespace mrslam::test {

/// A DDS domain of this test process alone (tests run in parallel processes).
inline int privateDomain() {
  return 100 + static_cast<int>(getpid() % 120);
}

inline std::unique_ptr<tools::ChildProcess> startAgent(const std::string& program,
                                                       std::vector<std::string> arguments,
                                                       const std::string& log_path) {
  arguments.insert(arguments.begin(), binaryPath(program));
  return std::make_unique<tools::ChildProcess>(arguments, log_path);
}

/// Waits for an agent and returns its exit code (-1 on time-out, after killing it).
inline int finish(tools::ChildProcess& agent, double timeout_s) {
  const auto code = agent.waitFor(timeout_s);
  if (!code) {
    agent.stop(5.0);
    return -1;
  }
  return *code;
}

/// The end of an agent's log, for failure messages.
inline std::string logOf(const tools::ChildProcess& agent) {
  return agent.logPath() + ":\n" + tools::tailOfFile(agent.logPath(), 30);
}

}  // namespace mrslam::test
