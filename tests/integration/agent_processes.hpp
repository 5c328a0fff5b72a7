#pragma once
// Helpers of the integration tests: real robot and fusion agents as separate processes.

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "mrslam/tools/child_process.hpp"
#include "test_data.hpp"
#include "test_domain.hpp"

namespace mrslam::test {

/// The whole text of a file ("" when it cannot be read).
inline std::string fileText(const std::filesystem::path& path) {
  std::ifstream file(path);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

/// A DDS domain of this test process alone (tests run in parallel processes).
inline int privateDomain() {
  return testDomain();
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

/// A program run to its end: its exit code and all it printed.
struct CommandRun {
  int exit_code = -1;  ///< -1: it did not end in time
  std::string output;  ///< standard output and error together
};

/// Runs a program of the build tree to its end (killed after `timeout_s`), its output in
/// `log_path`.
inline CommandRun runToEnd(const std::string& program, const std::vector<std::string>& arguments,
                           const std::string& log_path, double timeout_s) {
  auto process = startAgent(program, arguments, log_path);
  CommandRun run;
  run.exit_code = finish(*process, timeout_s);
  run.output = fileText(log_path);
  return run;
}

/// The end of an agent's log, for failure messages.
inline std::string logOf(const tools::ChildProcess& agent) {
  return agent.logPath() + ":\n" + tools::tailOfFile(agent.logPath(), 30);
}

/// How often the file holds `text`.
inline int occurrencesIn(const std::filesystem::path& path, const std::string& text) {
  const std::string log = fileText(path);
  int found = 0;
  for (std::size_t at = log.find(text); at != std::string::npos; at = log.find(text, at + 1)) {
    ++found;
  }
  return found;
}

/// Waits (bounded: `timeout_s`) until the file holds `text` `times` times.
inline bool waitForLog(const std::filesystem::path& path, const std::string& text, int times = 1,
                       double timeout_s = 60.0) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(timeout_s));
  while (true) {
    if (occurrencesIn(path, text) >= times) {
      return true;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

}  // namespace mrslam::test
