#pragma once
// Where tests find the real data of ../shared/data and the programs of the build tree.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace mrslam::test {

/// Absolute path of a file under the shared data folder (it may not exist).
inline std::string sharedDataPath(const std::string& relative) {
  return (std::filesystem::path(MRSLAM_DATA_DIR) / relative).string();
}

/// Path of a file in the source tree (configs, ...).
inline std::string sourcePath(const std::string& relative) {
  return (std::filesystem::path(MRSLAM_SOURCE_DIR) / relative).string();
}

/// Path of a file in the build tree (programs, ...).
inline std::string binaryPath(const std::string& relative) {
  return (std::filesystem::path(MRSLAM_BINARY_DIR) / relative).string();
}

/// A fresh, empty scratch folder for one test.
inline std::filesystem::path scratchFolder(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path folder =
      std::filesystem::temp_directory_path() / "mrslam-tests" /
      (std::string(info->test_suite_name()) + "." + info->name() + "." + name);
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

}  // namespace mrslam::test

/// Skips the test (reported as skipped, never as passed) when a shared data file is absent.
#define MRSLAM_REQUIRE_SHARED_DATA(relative)                                  \
  do {                                                                        \
    if (!std::filesystem::exists(::mrslam::test::sharedDataPath(relative))) { \
      GTEST_SKIP() << "needs " << ::mrslam::test::sharedDataPath(relative)    \
                   << " (../shared/data beside the project); absent here";    \
    }                                                                         \
  } while (0)
