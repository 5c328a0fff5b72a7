#pragma once
// Starting, watching and stopping agent processes (the demo, the team launcher, the
// integration tests). Each child writes its standard output and error into its own log file.

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace mrslam::tools {

class ChildProcess {
 public:
  /// Starts argv[0] (a path) with its arguments; stdout and stderr go to `log_path`. The child
  /// gets this process's environment with `environment` ("NAME=value") added or replacing.
  /// Throws std::runtime_error when the program cannot be started.
  ChildProcess(const std::vector<std::string>& argv, const std::string& log_path,
               const std::vector<std::string>& environment = {});
  /// Kills the child (SIGKILL) if it still runs, and reaps it.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  const std::string& logPath() const { return log_path_; }
  const std::string& name() const { return name_; }

  /// The exit code once the child has ended (128 + signal when a signal ended it).
  std::optional<int> poll();
  /// Waits up to timeout_s for the end; nothing on time-out.
  std::optional<int> waitFor(double timeout_s);
  /// Sends a signal (SIGINT, SIGTERM, SIGKILL) if the child still runs.
  void signal(int signal_number);
  /// SIGINT, then SIGKILL if it has not ended within grace_s. Returns the exit code.
  int stop(double grace_s);

 private:
  pid_t pid_ = -1;
  std::optional<int> exit_code_;
  std::string log_path_;
  std::string name_;
};

/// The last `lines` lines of a text file (for error reports).
std::string tailOfFile(const std::string& path, std::size_t lines);

}  // namespace mrslam::tools
