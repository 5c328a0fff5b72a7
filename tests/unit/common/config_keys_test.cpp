// ConfigKeyLog: what Config records of the loaders' reads while a log exists.

#include "mrslam/common/config_keys.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "mrslam/common/config.hpp"

namespace mrslam {
namespace {

// "key kind default range [choices]" of each use, for compact expectations.
std::vector<std::string> describe(const std::vector<ConfigKeyUse>& uses) {
  std::vector<std::string> lines;
  for (const ConfigKeyUse& use : uses) {
    std::string line = use.key + " " + configKeyKindName(use.kind) + " " + use.default_text;
    if (!use.range.empty()) {
      line += " " + use.range;
    }
    for (const std::string& choice : use.choices) {
      line += " |" + choice;
    }
    lines.push_back(line);
  }
  return lines;
}

TEST(ConfigKeyLogTest, RecordsKeysKindsDefaultsAndRanges) {
  const Config config = Config::loadString(
      "rate: 2\nlaser:\n  count: 3\nitems:\n  - name: a\n  - name: b\nmaybe: 4\n",
      "/etc/mrslam/toy.yaml");
  ConfigKeyLog log;
  config.getDouble("rate", 0.05, {0.0, 10.0});
  config.requireDouble("rate");
  const Config laser = config.section("laser");
  laser.getInt("count", 2, {1, 99});
  laser.getInt("floor", -1, {-1, 1e9});
  config.getBool("enabled", true);
  config.getString("name", "ekf");
  config.getChoice("mode", "fast", {"fast", "slow"});
  config.getDoubles("pose", {0.0, 0.0, 0.0}, 3);
  config.getPath("out", "out/maps");
  config.getPath("profiles", "/etc/mrslam/dds/profiles.xml");
  config.getPath("elsewhere", "/usr/share/x.xml");
  config.getExpandedString("library", "libphidget22.so");
  for (const Config& item : config.sectionList("items")) {
    item.requireString("name");
  }
  if (config.has("maybe")) {
    config.requireInt("maybe");
  }
  config.requirePath("rate");

  const std::vector<std::string> expected = {
      "rate number 0.05 [0, 10]",
      "rate number required",
      "laser section {}",
      "laser.count integer 2 [1, 99]",
      "laser.floor integer -1 [-1, 1000000000]",
      "enabled bool true",
      "name string \"ekf\"",
      "mode choice \"fast\" |fast |slow",
      "pose numbers [0, 0, 0]",
      "out path \"out/maps\"",
      "profiles path \"dds/profiles.xml\"",
      "elsewhere path \"/usr/share/x.xml\"",
      "library string \"libphidget22.so\"",
      "items section list []",
      "items[].name string required",
      "items[].name string required",
      "maybe integer unset",
      "rate path required",
  };
  EXPECT_EQ(describe(log.uses()), expected);
  for (const ConfigKeyUse& use : log.uses()) {
    EXPECT_EQ(use.file, "/etc/mrslam/toy.yaml") << use.key;
  }
  log.clear();
  EXPECT_TRUE(log.uses().empty());
}

TEST(ConfigKeyLogTest, RecordsNothingWithoutALogAndChangesNoResult) {
  const Config config = Config::loadString("rate: 2\nextra: 1\n", "toy.yaml");
  EXPECT_FALSE(ConfigKeyLog::recording());
  EXPECT_EQ(config.getDouble("rate", 0.05), 2.0);
  EXPECT_TRUE(config.has("extra"));
  std::vector<ConfigKeyUse> uses;
  {
    ConfigKeyLog log;
    EXPECT_TRUE(ConfigKeyLog::recording());
    EXPECT_EQ(config.getDouble("rate", 0.05), 2.0);
    // has() is not a read: the key stays unknown, as without a log.
    EXPECT_TRUE(config.has("extra"));
    EXPECT_THROW(config.checkNoUnknownKeys(), ConfigError);
    uses = log.uses();
  }
  EXPECT_FALSE(ConfigKeyLog::recording());
  EXPECT_EQ(uses.size(), 1u);
  ConfigKeyLog later;
  config.getDouble("rate", 0.05);
  EXPECT_EQ(later.uses().size(), 1u);
}

TEST(ConfigKeyLogTest, OneLogAtATime) {
  ConfigKeyLog log;
  EXPECT_THROW(ConfigKeyLog second, std::logic_error);
  EXPECT_TRUE(ConfigKeyLog::recording());
}

TEST(ConfigKeyLogTest, DefaultsReadAsWrittenInYaml) {
  EXPECT_EQ(yamlNumber(0.05), "0.05");
  EXPECT_EQ(yamlNumber(2.0), "2");
  EXPECT_EQ(yamlNumber(120.0), "120");
  EXPECT_EQ(yamlNumber(-1.0), "-1");
  EXPECT_EQ(yamlNumber(-0.0), "0");
  EXPECT_EQ(yamlNumber(1e-6), "1e-6");
  EXPECT_EQ(yamlNumber(9e15), "9e15");
  EXPECT_EQ(yamlNumber(6.5536e-3), "0.0065536");
  EXPECT_EQ(yamlNumber(16'000'000), "16000000");
  EXPECT_EQ(yamlNumber(static_cast<double>(0.85f)), "0.85");  // a float default
  const double degree = M_PI / 180.0;
  EXPECT_EQ(yamlNumber((0.5 * degree) / degree), "0.5");  // computed from radians
  EXPECT_EQ(yamlNumber(1.5 * M_PI / 180.0 / degree), "1.5");
  EXPECT_EQ(yamlString("ekf"), "\"ekf\"");
  EXPECT_EQ(yamlString(""), "\"\"");
  EXPECT_EQ(yamlString("a\"b"), "\"a\\\"b\"");
  EXPECT_EQ(yamlNumbers({0.0, 0.0, 0.0}), "[0, 0, 0]");
  EXPECT_EQ(yamlNumbers({19200, 38400, 115200}), "[19200, 38400, 115200]");
  EXPECT_EQ(yamlNumbers({}), "[]");
}

}  // namespace
}  // namespace mrslam
