#include "mrslam/common/config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <functional>

namespace mrslam {
namespace {

using ::testing::HasSubstr;

std::string errorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "no error";
}

TEST(ConfigTest, ReadsTypedValuesWithDefaults) {
  const Config config = Config::loadString(
      "rate: 2.5\ncount: 7\nname: robot1\nenabled: true\nlist: [1, 2, 3]\n"
      "nested:\n  value: 4\n",
      "test.yaml");
  EXPECT_DOUBLE_EQ(config.getDouble("rate", 0.0), 2.5);
  EXPECT_EQ(config.getInt("count", 0), 7);
  EXPECT_EQ(config.getString("name", ""), "robot1");
  EXPECT_TRUE(config.getBool("enabled", false));
  EXPECT_EQ(config.getDoubles("list", {}, 3), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(config.section("nested").getInt("value", 0), 4);
  EXPECT_DOUBLE_EQ(config.getDouble("missing", 9.5), 9.5);
  EXPECT_EQ(config.section("absent").getInt("value", 3), 3);
  EXPECT_NO_THROW(config.checkNoUnknownKeys());
}

TEST(ConfigTest, UnknownKeyNamesFileLineAndKey) {
  const Config config = Config::loadString("rate: 1\nnested:\n  value: 4\n  typo: 5\n", "r.yaml");
  config.getDouble("rate", 0.0);
  config.section("nested").getInt("value", 0);
  EXPECT_EQ(errorOf([&] { config.checkNoUnknownKeys(); }), "r.yaml:4: nested.typo: unknown key");
}

TEST(ConfigTest, WrongTypeNamesFileLineAndKey) {
  const Config config = Config::loadString("a: 1\nrate: fast\n", "r.yaml");
  EXPECT_EQ(errorOf([&] { config.getDouble("rate", 0.0); }),
            "r.yaml:2: rate: must be a number, not 'fast'");
  const Config ints = Config::loadString("count: 2.5\n", "c.yaml");
  EXPECT_EQ(errorOf([&] { ints.getInt("count", 0); }),
            "c.yaml:1: count: must be an integer, not '2.5'");
  const Config bools = Config::loadString("on_off: maybe\n", "b.yaml");
  EXPECT_EQ(errorOf([&] { bools.getBool("on_off", false); }),
            "b.yaml:1: on_off: must be true or false");
  const Config nested = Config::loadString("laser: 3\n", "n.yaml");
  EXPECT_EQ(errorOf([&] { nested.section("laser"); }), "n.yaml:1: laser: must be a map of keys");
}

TEST(ConfigTest, OutOfRangeNamesFileLineAndKey) {
  const Config config = Config::loadString("mapping:\n  resolution_m: -0.05\n", "m.yaml");
  EXPECT_EQ(errorOf([&] {
              config.section("mapping").getDouble("resolution_m", 0.05, {0.001, 1.0});
            }),
            "m.yaml:2: mapping.resolution_m: -0.05 is out of range: must be in [0.001, 1]");
}

TEST(ConfigTest, ChoiceAndRequiredAndListSize) {
  const Config config = Config::loadString("mode: sideways\nxs: [1, 2]\n", "x.yaml");
  EXPECT_EQ(errorOf([&] {
              config.getChoice("mode", "a", {"a", "b"});
            }),
            "x.yaml:1: mode: 'sideways' is not one of: a, b");
  EXPECT_EQ(errorOf([&] { config.requireString("robot_id"); }), "x.yaml:1: robot_id: is required");
  EXPECT_EQ(errorOf([&] { config.getDoubles("xs", {}, 3); }),
            "x.yaml:2: xs: must have exactly 3 numbers");
}

TEST(ConfigTest, ListsOfSectionsTrackTheirKeys) {
  const Config config =
      Config::loadString("robots:\n  - id: a\n  - id: b\n    extra: 1\n", "l.yaml");
  const std::vector<Config> robots = config.sectionList("robots");
  ASSERT_EQ(robots.size(), 2u);
  EXPECT_EQ(robots[0].getString("id", ""), "a");
  EXPECT_EQ(robots[1].getString("id", ""), "b");
  EXPECT_EQ(errorOf([&] { config.checkNoUnknownKeys(); }),
            "l.yaml:4: robots[1].extra: unknown key");
}

TEST(ConfigTest, SyntaxErrorAndMissingFile) {
  EXPECT_THAT(errorOf([] { Config::loadString("a: [1, 2\n", "s.yaml"); }), HasSubstr("s.yaml:"));
  EXPECT_THAT(errorOf([] { Config::loadFile("/nonexistent/robot.yaml"); }),
              HasSubstr("/nonexistent/robot.yaml: cannot open"));
  EXPECT_THAT(errorOf([] { Config::loadString("- 1\n- 2\n", "top.yaml"); }),
              HasSubstr("top.yaml:1: the top level must be a map"));
}

TEST(ConfigTest, RelativePathsAreTakenFromTheConfigFolder) {
  const Config config =
      Config::loadString("log: ../data/a.log\nabs: /tmp/x\n", "/etc/mrslam/r.yaml");
  EXPECT_EQ(config.getPath("log", ""), "/etc/data/a.log");
  EXPECT_EQ(config.getPath("abs", ""), "/tmp/x");
  EXPECT_EQ(config.getPath("absent", "relative/default.xml"), "relative/default.xml");
}

TEST(ConfigTest, EnvironmentVariablesExpandInPaths) {
  ::setenv("MRSLAM_TEST_DEVICE_DIR", "/run/robot7", 1);
  ::unsetenv("MRSLAM_TEST_UNSET");
  const Config config = Config::loadString(
      "laser: ${MRSLAM_TEST_DEVICE_DIR}/laser\nrel: ${MRSLAM_TEST_DEVICE_DIR}x/../imu\n"
      "lib: lib${MRSLAM_TEST_DEVICE_DIR}.so\nmissing: ${MRSLAM_TEST_UNSET}/a\nopen: ${ab\n"
      "empty: ''\n",
      "/etc/mrslam/r.yaml");
  EXPECT_EQ(config.requirePath("laser"), "/run/robot7/laser");
  EXPECT_EQ(config.getPath("rel", ""), "/run/robot7x/../imu");
  EXPECT_EQ(config.getExpandedString("lib", ""), "lib/run/robot7.so");
  EXPECT_EQ(config.getExpandedString("absent", "libphidget22.so"), "libphidget22.so");
  EXPECT_EQ(errorOf([&] { config.requirePath("missing"); }),
            "/etc/mrslam/r.yaml:4: missing: names the environment variable \"MRSLAM_TEST_UNSET\", "
            "which is "
            "not set");
  EXPECT_THAT(errorOf([&] { config.getPath("open", ""); }), HasSubstr("unterminated"));
  EXPECT_THAT(errorOf([&] { config.requirePath("empty"); }), HasSubstr("must not be empty"));
  EXPECT_THAT(errorOf([&] { config.requirePath("nothing"); }), HasSubstr("is required"));
}

}  // namespace
}  // namespace mrslam
