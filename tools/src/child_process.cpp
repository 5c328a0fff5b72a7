#include "mrslam/tools/child_process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace mrslam::tools {

namespace {

int exitCodeOf(int status) {
  if (WIFEXITED(status)) {
    return WEXITSTATUS(status);
  }
  if (WIFSIGNALED(status)) {
    return 128 + WTERMSIG(status);
  }
  return -1;
}

// This process's environment with `extra` ("NAME=value") replacing variables of the same name.
std::vector<std::string> mergedEnvironment(const std::vector<std::string>& extra) {
  std::vector<std::string> merged;
  const auto nameOf = [](const std::string& entry) { return entry.substr(0, entry.find('=')); };
  for (char** entry = environ; *entry != nullptr; ++entry) {
    const std::string text(*entry);
    bool replaced = false;
    for (const std::string& added : extra) {
      replaced = replaced || nameOf(added) == nameOf(text);
    }
    if (!replaced) {
      merged.push_back(text);
    }
  }
  merged.insert(merged.end(), extra.begin(), extra.end());
  return merged;
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const std::string& log_path,
                           const std::vector<std::string>& environment)
    : log_path_(log_path) {
  if (argv.empty()) {
    throw std::runtime_error("ChildProcess: no program given");
  }
  name_ = std::filesystem::path(argv.front()).filename().string();
  const std::filesystem::path log_folder = std::filesystem::path(log_path).parent_path();
  if (!log_folder.empty()) {
    std::filesystem::create_directories(log_folder);
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::vector<char*> args;
  for (const std::string& arg : argv) {
    args.push_back(const_cast<char*>(arg.c_str()));
  }
  args.push_back(nullptr);
  std::vector<std::string> variables = mergedEnvironment(environment);
  std::vector<char*> envp;
  for (std::string& variable : variables) {
    envp.push_back(variable.data());
  }
  envp.push_back(nullptr);
  const int error =
      posix_spawn(&pid_, argv.front().c_str(), &actions, nullptr, args.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) {
    throw std::runtime_error("cannot start " + argv.front() + ": " + std::strerror(error));
  }
}

ChildProcess::~ChildProcess() {
  if (!poll()) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
}

std::optional<int> ChildProcess::poll() {
  if (exit_code_) {
    return exit_code_;
  }
  int status = 0;
  const pid_t result = ::waitpid(pid_, &status, WNOHANG);
  if (result == pid_) {
    exit_code_ = exitCodeOf(status);
  } else if (result < 0 && errno == ECHILD) {
    exit_code_ = -1;  // reaped elsewhere: nothing more to know
  }
  return exit_code_;
}

std::optional<int> ChildProcess::waitFor(double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(timeout_s));
  while (!poll()) {
    if (std::chrono::steady_clock::now() >= deadline) {
      return std::nullopt;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return exit_code_;
}

void ChildProcess::signal(int signal_number) {
  if (!poll()) {
    ::kill(pid_, signal_number);
  }
}

int ChildProcess::stop(double grace_s) {
  signal(SIGINT);
  if (const auto code = waitFor(grace_s)) {
    return *code;
  }
  signal(SIGKILL);
  return waitFor(10.0).value_or(-1);
}

std::string tailOfFile(const std::string& path, std::size_t lines) {
  std::ifstream file(path);
  std::deque<std::string> last;
  std::string line;
  while (std::getline(file, line)) {
    last.push_back(line);
    if (last.size() > lines) {
      last.pop_front();
    }
  }
  std::string text;
  for (const std::string& kept : last) {
    text += kept + "\n";
  }
  return text;
}

}  // namespace mrslam::tools
