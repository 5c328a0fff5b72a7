#pragma once
// A DDS domain of this test process alone. ctest runs tests in parallel processes; a domain
// picked from the process id would now and then be shared by two of them (and one test would
// see the other's robots). Instead each process takes the first free domain of 100…232 and holds
// an exclusive lock on it until it ends (not inherited by the agents it starts).

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace mrslam::test {

inline int testDomain() {
  static const int domain = [] {
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() / "mrslam-test-domains";
    std::filesystem::create_directories(folder);
    for (int candidate = 100; candidate <= 232; ++candidate) {
      const std::string lock = (folder / (std::to_string(candidate) + ".lock")).string();
      const int fd = ::open(lock.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0666);
      if (fd < 0) {
        continue;
      }
      if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
        return candidate;  // the descriptor stays open: the lock lasts as long as the process
      }
      ::close(fd);
    }
    return 100 + static_cast<int>(::getpid() % 133);  // every domain taken: share one
  }();
  return domain;
}

}  // namespace mrslam::test
