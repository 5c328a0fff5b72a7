// mrslam_scan end to end: against the emulator as a separate process (mrslam_hokuyo_emulator),
// and against silent, garbage-talking, missing and vanishing devices.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "mrslam/drivers/hokuyo_emulator.hpp"
#include "mrslam/tools/child_process.hpp"
#include "test_data.hpp"

namespace mrslam::test {
namespace {

using tools::ChildProcess;

std::vector<std::string> linesOf(const std::string& path) {
  std::ifstream file(path);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(file, line)) {
    if (!line.empty()) {
      lines.push_back(line);
    }
  }
  return lines;
}

std::vector<nlohmann::json> jsonLinesOf(const std::string& path) {
  std::vector<nlohmann::json> objects;
  for (const std::string& line : linesOf(path)) {
    if (line.front() == '{') {
      objects.push_back(nlohmann::json::parse(line));
    }
  }
  return objects;
}

std::unique_ptr<ChildProcess> startScan(const std::string& device,
                                        std::vector<std::string> arguments,
                                        const std::string& log) {
  const std::string program = binaryPath("tools/mrslam_scan");
  EXPECT_TRUE(std::filesystem::exists(program)) << program << " is not built";
  arguments.insert(arguments.begin(), {program, device});
  return std::make_unique<ChildProcess>(arguments, log);
}

/// Runs mrslam_scan to its end and checks it failed with code `code` and one line of output
/// that names the device and contains `reason`.
void expectOneLineFailure(const std::string& device, const std::string& reason, int code) {
  const std::string log = (scratchFolder("scan") / "scan.log").string();
  auto scan = startScan(device, {"--timeout", "0.2"}, log);
  EXPECT_EQ(scan->waitFor(60.0), code) << tools::tailOfFile(log, 10);
  const auto lines = linesOf(log);
  ASSERT_EQ(lines.size(), 1u) << tools::tailOfFile(log, 10);
  EXPECT_EQ(lines[0].rfind("mrslam_scan: " + device + ": ", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find(reason), std::string::npos) << lines[0];
}

TEST(ScanToolTest, PrintsScansOfAnEmulatorProcessAsJsonLines) {
  const auto folder = scratchFolder("emulated");
  const std::string link = (folder / "ttyACM-emulated").string();
  ChildProcess emulator(
      {binaryPath("tools/mrslam_hokuyo_emulator"), link, "--model", "ubg05ln", "--pattern", "ramp"},
      (folder / "emulator.log").string());
  for (int wait = 0; wait < 200 && !std::filesystem::exists(link); ++wait) {
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  ASSERT_TRUE(std::filesystem::exists(link)) << tools::tailOfFile(emulator.logPath(), 10);

  const std::string log = (folder / "scan.log").string();
  auto scan = startScan(link, {"--json", "--count", "3", "--timeout", "2"}, log);
  ASSERT_EQ(scan->waitFor(60.0), 0) << tools::tailOfFile(log, 10);
  const auto scans = jsonLinesOf(log);
  ASSERT_EQ(scans.size(), 3u) << tools::tailOfFile(log, 10);

  const drivers::HokuyoModel model = drivers::HokuyoModel::ubg05ln();
  const auto raw = drivers::hokuyoRangePattern("ramp", model)(0);
  double previous_ms = 0.0;
  for (const nlohmann::json& object : scans) {
    EXPECT_NEAR(object["angle_min_rad"].get<double>(), -256 * 0.36 * M_PI / 180, 1e-9);
    EXPECT_NEAR(object["angle_increment_rad"].get<double>(), 0.36 * M_PI / 180, 1e-12);
    const auto& ranges = object["ranges_m"];
    ASSERT_EQ(ranges.size(), 513u);
    std::vector<std::size_t> no_return;
    std::size_t error_codes = 0;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] > 4500) {  // beyond DMAX: no echo, written as null and listed
        EXPECT_TRUE(ranges[i].is_null()) << i;
        no_return.push_back(i);
      } else if (raw[i] < 20) {  // below DMIN: an error code, written as null
        EXPECT_TRUE(ranges[i].is_null()) << i;
        ++error_codes;
      } else {
        EXPECT_NEAR(ranges[i].get<double>(), raw[i] / 1000.0, 1e-6) << i;
      }
    }
    EXPECT_GT(no_return.size(), 0u);
    EXPECT_GT(error_codes, 0u);
    EXPECT_EQ(object["no_return"].get<std::vector<std::size_t>>(), no_return);
    const double stamp_ms = object["timestamp_ms"].get<double>();
    EXPECT_GT(stamp_ms, previous_ms);
    previous_ms = stamp_ms;
  }
  const std::string text = tools::tailOfFile(log, 40);
  EXPECT_NE(text.find("PROD: SOKUIKI Sensor UBG-05LN"), std::string::npos) << text;
  EXPECT_NE(text.find("ARES: 1000"), std::string::npos) << text;
  EXPECT_EQ(emulator.stop(10.0), 0) << tools::tailOfFile(emulator.logPath(), 10);
}

TEST(ScanToolTest, ASilentDeviceEndsWithAOneLineReason) {
  drivers::PtyPair pty((scratchFolder("silent") / "ttyACM-silent").string());
  expectOneLineFailure(pty.devicePath(), "the device does not answer", 2);
}

TEST(ScanToolTest, AGarbageTalkingDeviceEndsWithAOneLineReason) {
  drivers::HokuyoEmulatorSettings settings;
  settings.device_baud = 9600;  // not probed: every answer is noise
  drivers::HokuyoEmulator emulator(settings,
                                   (scratchFolder("garbage") / "ttyACM-garbage").string());
  emulator.start();
  expectOneLineFailure(emulator.devicePath(), "garbage", 2);
}

TEST(ScanToolTest, AMissingDeviceEndsWithAOneLineReason) {
  expectOneLineFailure("/dev/nonexistent-mrslam-hokuyo", "cannot open", 2);
}

TEST(ScanToolTest, AVanishingDeviceEndsWithAOneLineReason) {
  const auto folder = scratchFolder("vanishing");
  drivers::HokuyoEmulator emulator({}, (folder / "ttyACM-vanishing").string());
  emulator.start();
  const std::string log = (folder / "scan.log").string();
  auto scan = startScan(emulator.devicePath(), {"--json", "--count", "0", "--timeout", "0.5"}, log);
  for (int wait = 0; wait < 400 && jsonLinesOf(log).empty() && !scan->poll(); ++wait) {
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  ASSERT_FALSE(jsonLinesOf(log).empty()) << tools::tailOfFile(log, 10);
  emulator.unplug();
  EXPECT_EQ(scan->waitFor(60.0), 3) << tools::tailOfFile(log, 10);
  const auto lines = linesOf(log);
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.back().rfind("mrslam_scan: ", 0), 0u) << lines.back();
  EXPECT_NE(lines.back().find("device vanished"), std::string::npos) << lines.back();
  // Identity lines (stderr with --json), then scans only, then the reason.
  const auto first_scan = std::find_if(lines.begin(), lines.end(),
                                       [](const std::string& line) { return line.front() == '{'; });
  for (auto line = first_scan; line + 1 < lines.end(); ++line) {
    EXPECT_EQ(line->front(), '{') << "only scans before the reason: " << *line;
  }
}

}  // namespace
}  // namespace mrslam::test
