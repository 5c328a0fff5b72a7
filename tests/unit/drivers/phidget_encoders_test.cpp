// The Phidget encoder adapter against a stand-in libphidget22 built by the tests, loaded through
// the adapter's own dlopen / dlsym code.

#include "mrslam/drivers/phidget_encoders.hpp"

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <thread>

#include "mrslam/common/config.hpp"

namespace mrslam::drivers {
namespace {

// The stand-in's test hooks, found in the same loaded library the adapter uses.
struct StandinHooks {
  int (*move)(int, int, double, int) = nullptr;
  int (*live_handles)() = nullptr;
  int (*attached_channels)() = nullptr;
  unsigned (*data_interval)(int) = nullptr;
};

template <class Function>
void find(void* library, const char* name, Function& function) {
  void* address = ::dlsym(library, name);
  ASSERT_NE(address, nullptr) << name;
  function = reinterpret_cast<Function>(address);
}

class PhidgetEncodersTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ::unsetenv("MRSLAM_PHIDGET_EMULATOR_ATTACH");
    ::unsetenv("MRSLAM_PHIDGET_EMULATOR_SERIAL");
    library_ = ::dlopen(MRSLAM_PHIDGET_EMULATOR, RTLD_NOW | RTLD_LOCAL);
    ASSERT_NE(library_, nullptr) << ::dlerror();
    find(library_, "mrslam_phidget_emulator_move", hooks_.move);
    find(library_, "mrslam_phidget_emulator_live_handles", hooks_.live_handles);
    find(library_, "mrslam_phidget_emulator_attached_channels", hooks_.attached_channels);
    find(library_, "mrslam_phidget_emulator_data_interval", hooks_.data_interval);
    settings_.library_names = {MRSLAM_PHIDGET_EMULATOR};
    settings_.left = {-1, -1, 0, 1};
    settings_.right = {12345, -1, 1, -1};  // mounted mirrored: forward counts down
  }
  void TearDown() override {
    ::unsetenv("MRSLAM_PHIDGET_EMULATOR_ATTACH");
    if (library_ != nullptr) {
      ::dlclose(library_);
    }
  }

  std::unique_ptr<PhidgetEncoders> openOrFail() {
    auto opened = PhidgetEncoders::open(settings_);
    EXPECT_TRUE(opened.ok()) << opened.reason();
    return opened.ok() ? std::move(opened.value()) : nullptr;
  }

  void* library_ = nullptr;
  StandinHooks hooks_;
  PhidgetEncoderSettings settings_;
};

TEST_F(PhidgetEncodersTest, OpensOneAttachedHandlePerWheel) {
  auto encoders = openOrFail();
  ASSERT_TRUE(encoders);
  EXPECT_EQ(hooks_.attached_channels(), 2);
  EXPECT_EQ(hooks_.live_handles(), 2);
  EXPECT_EQ(hooks_.data_interval(0), 8u);  // the data interval setting reached the board
  EXPECT_EQ(encoders->libraryName(), MRSLAM_PHIDGET_EMULATOR);
  EXPECT_FALSE(encoders->poll());  // nothing moved yet
}

TEST_F(PhidgetEncodersTest, PositionChangesAccumulateWithTheWheelsDirection) {
  auto encoders = openOrFail();
  ASSERT_TRUE(encoders);
  ASSERT_EQ(hooks_.move(0, 40, 8.0, 0), 0);
  ASSERT_EQ(hooks_.move(1, -40, 8.0, 0), 0);
  ASSERT_EQ(hooks_.move(0, 25, 8.0, 1), 0);
  const auto ticks = encoders->poll();
  ASSERT_TRUE(ticks);
  EXPECT_EQ(ticks->left, 65);
  EXPECT_EQ(ticks->right, 40);  // direction -1
  EXPECT_GT(ticks->stamp.ns, 0);
  EXPECT_FALSE(encoders->poll());  // unchanged since

  ASSERT_EQ(hooks_.move(1, -10, 8.0, 0), 0);
  const auto more = encoders->poll();
  ASSERT_TRUE(more);
  EXPECT_EQ(more->left, 65);
  EXPECT_EQ(more->right, 50);
  EXPECT_GE(more->stamp, ticks->stamp);
  // The board's own count has no direction sign.
  EXPECT_EQ(encoders->devicePosition(Wheel::kLeft), 65);
  EXPECT_EQ(encoders->devicePosition(Wheel::kRight), -50);
  const PhidgetEncoderCounters counters = encoders->counters();
  EXPECT_EQ(counters.position_changes[0], 2u);
  EXPECT_EQ(counters.position_changes[1], 2u);
  EXPECT_EQ(counters.index_triggers[0], 1u);
}

TEST_F(PhidgetEncodersTest, TimeChangeIsTakenInMilliseconds) {
  auto encoders = openOrFail();
  ASSERT_TRUE(encoders);
  ASSERT_EQ(hooks_.move(0, 40, 8.0, 0), 0);    // 40 counts in 8 ms
  ASSERT_EQ(hooks_.move(1, -30, 12.0, 0), 0);  // 30 counts forward in 12 ms
  EXPECT_DOUBLE_EQ(encoders->speedCountsPerSecond(Wheel::kLeft), 5000.0);
  EXPECT_DOUBLE_EQ(encoders->speedCountsPerSecond(Wheel::kRight), 2500.0);
  EXPECT_DOUBLE_EQ(encoders->counters().device_time_s[0], 0.008);
  EXPECT_DOUBLE_EQ(encoders->counters().device_time_s[1], 0.012);
}

TEST_F(PhidgetEncodersTest, ChangesFromManyLibraryThreadsAreAllCounted) {
  auto encoders = openOrFail();
  ASSERT_TRUE(encoders);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([this] {
      for (int i = 0; i < 250; ++i) {
        hooks_.move(i % 2, 1, 1.0, 0);
      }
    });
  }
  for (auto& thread : threads) {
    thread.join();
  }
  const auto ticks = encoders->poll();
  ASSERT_TRUE(ticks);
  EXPECT_EQ(ticks->left, 500);
  EXPECT_EQ(ticks->right, -500);
}

TEST_F(PhidgetEncodersTest, DestructionClosesAndDeletesTheHandles) {
  {
    auto encoders = openOrFail();
    ASSERT_TRUE(encoders);
    ASSERT_EQ(hooks_.live_handles(), 2);
  }
  EXPECT_EQ(hooks_.live_handles(), 0);
  EXPECT_EQ(hooks_.attached_channels(), 0);
  EXPECT_EQ(hooks_.move(0, 1, 1.0, 0), -1);  // nobody listens any more
}

TEST_F(PhidgetEncodersTest, NoDeviceAttachingIsAClearFailure) {
  ::setenv("MRSLAM_PHIDGET_EMULATOR_ATTACH", "fail", 1);
  auto opened = PhidgetEncoders::open(settings_);
  ASSERT_FALSE(opened.ok());
  EXPECT_NE(opened.reason().find("left encoder (serial any, hub port any, channel 0)"),
            std::string::npos)
      << opened.reason();
  EXPECT_NE(opened.reason().find("no device attached within 2000 ms: Timed Out"), std::string::npos)
      << opened.reason();
  EXPECT_EQ(hooks_.live_handles(), 0);  // what was created is deleted again
}

TEST_F(PhidgetEncodersTest, AnotherBoardsSerialNumberIsAClearFailure) {
  settings_.right.serial_number = 999;
  auto opened = PhidgetEncoders::open(settings_);
  ASSERT_FALSE(opened.ok());
  EXPECT_NE(opened.reason().find("right encoder (serial 999"), std::string::npos)
      << opened.reason();
  EXPECT_EQ(hooks_.live_handles(), 0);
}

TEST_F(PhidgetEncodersTest, AMissingLibraryIsAClearFailure) {
  settings_.library_names = {"/nonexistent/libphidget22.so.0", "libphidget22-nonexistent.so"};
  auto opened = PhidgetEncoders::open(settings_);
  ASSERT_FALSE(opened.ok());
  EXPECT_EQ(opened.reason().rfind("cannot load libphidget22", 0), 0u) << opened.reason();
  EXPECT_NE(opened.reason().find("/nonexistent/libphidget22.so.0"), std::string::npos);
  EXPECT_NE(opened.reason().find("libphidget22-nonexistent.so"), std::string::npos);
}

TEST_F(PhidgetEncodersTest, ALibraryWithoutAFunctionIsAClearFailure) {
  settings_.library_names = {MRSLAM_PHIDGET_EMULATOR_INCOMPLETE};
  auto opened = PhidgetEncoders::open(settings_);
  ASSERT_FALSE(opened.ok());
  EXPECT_NE(opened.reason().find("lacks PhidgetEncoder_getPosition"), std::string::npos)
      << opened.reason();
}

TEST_F(PhidgetEncodersTest, TheNextLibraryNameIsTriedWhenOneFails) {
  settings_.library_names = {"/nonexistent/libphidget22.so.0", MRSLAM_PHIDGET_EMULATOR};
  auto encoders = openOrFail();
  ASSERT_TRUE(encoders);
  EXPECT_EQ(encoders->libraryName(), MRSLAM_PHIDGET_EMULATOR);
}

TEST(PhidgetEncoderSettingsTest, BadSettingsAreRefusedBeforeLoading) {
  PhidgetEncoderSettings settings;
  EXPECT_TRUE(settings.check().empty());
  settings.right = settings.left;
  EXPECT_NE(settings.check().find("same encoder input"), std::string::npos);
  settings.right.channel = 1;
  settings.right.direction = 0;
  auto opened = PhidgetEncoders::open(settings);
  ASSERT_FALSE(opened.ok());
  EXPECT_NE(opened.reason().find("direction"), std::string::npos);
}

TEST(PhidgetEncoderSettingsTest, ReadsAConfigSection) {
  const Config config = Config::loadString(
      "library: /opt/phidgets/libphidget22.so\nattach_timeout_s: 0.5\ndata_interval_ms: 16\n"
      "left: {serial_number: 4711, channel: 2}\nright: {serial_number: 4711, channel: 3, "
      "direction: -1}\n",
      "robot.yaml");
  const PhidgetEncoderSettings settings = PhidgetEncoderSettings::fromConfig(config);
  config.checkNoUnknownKeys();
  EXPECT_EQ(settings.library_names, std::vector<std::string>{"/opt/phidgets/libphidget22.so"});
  EXPECT_EQ(settings.attach_timeout, std::chrono::milliseconds(500));
  EXPECT_EQ(settings.data_interval_ms, 16);
  EXPECT_EQ(settings.left.serial_number, 4711);
  EXPECT_EQ(settings.left.channel, 2);
  EXPECT_EQ(settings.left.direction, 1);
  EXPECT_EQ(settings.right.channel, 3);
  EXPECT_EQ(settings.right.direction, -1);
  EXPECT_EQ(settings.right.hub_port, -1);
}

TEST(PhidgetEncoderSettingsTest, AZeroDirectionInAConfigIsAnError) {
  const Config config = Config::loadString("left:\n  direction: 0\n", "robot.yaml");
  EXPECT_THROW(PhidgetEncoderSettings::fromConfig(config), ConfigError);
}

}  // namespace
}  // namespace mrslam::drivers
