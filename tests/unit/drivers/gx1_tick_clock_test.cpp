// TickClock: unwrapping the 3DM-GX1's 16-bit timer and aligning it with the host clock.

#include <gtest/gtest.h>

#include <random>

#include "mrslam/drivers/gx1_driver.hpp"

namespace mrslam::drivers {
namespace {

constexpr double kPeriod = 6.5536e-3;
constexpr std::int64_t kStart = 1'700'000'000'000'000'000;  // host ns of the first frame

Stamp hostAt(double seconds) {
  return Stamp{kStart + static_cast<std::int64_t>(seconds * 1e9)};
}

TEST(TickClockTest, UnwrapsThe16BitCounter) {
  TickClock clock({kPeriod, 1e-3, 0.05});
  clock.stamp(65530, hostAt(0.0));
  EXPECT_EQ(clock.unwrappedTicks(), 65530u);
  clock.stamp(65535, hostAt(5 * kPeriod));
  clock.stamp(3, hostAt(9 * kPeriod));  // wrapped
  EXPECT_EQ(clock.unwrappedTicks(), 65536u + 3u);
  clock.stamp(10, hostAt(16 * kPeriod));
  EXPECT_EQ(clock.unwrappedTicks(), 65536u + 10u);
}

TEST(TickClockTest, CountsWholeWrapsBetweenFramesFarApart) {
  TickClock clock({kPeriod, 1e-3, 0.05});
  clock.stamp(100, hostAt(0.0));
  // Two wraps and 50 ticks later (about 14 minutes).
  const double later = (2.0 * 65536.0 + 50.0) * kPeriod;
  clock.stamp(150, hostAt(later));
  EXPECT_EQ(clock.unwrappedTicks(), 100u + 2u * 65536u + 50u);
}

TEST(TickClockTest, StampsFollowTheLeastDelayedFrames) {
  // Frames every 3 ticks, read after a delay of 2 to 12 ms; the least delay is 2 ms.
  std::mt19937 random(42);
  std::uniform_real_distribution<double> delay_s(0.002, 0.012);
  TickClock clock({kPeriod, 1e-3, 0.05});
  const double device_start_s = 0.0;
  Stamp previous;
  for (int frame = 0; frame < 400; ++frame) {
    const double sampled_s = device_start_s + frame * 3 * kPeriod;
    const double delay = frame == 0 ? 0.010 : (frame % 10 == 5 ? 0.002 : delay_s(random));
    const Stamp host = hostAt(sampled_s + delay);
    const Stamp stamp = clock.stamp(static_cast<std::uint16_t>(frame * 3), host);
    EXPECT_LE(stamp.ns, host.ns);
    EXPECT_GT(stamp.ns, previous.ns);
    previous = stamp;
    if (frame > 10) {
      // Aligned to the sampling instant plus the least delay, whatever this frame's delay.
      EXPECT_NEAR(secondsBetween(hostAt(sampled_s + 0.002), stamp), 0.0, 3e-4) << frame;
    }
  }
  EXPECT_EQ(clock.resyncs(), 0u);
}

TEST(TickClockTest, FramesReadTogetherGetStampsSpacedByTheirTicks) {
  // Frame k is sampled at k periods; frame 0 is read 2 ms later, frames 1..10 in one late read.
  TickClock clock({kPeriod, 1e-3, 0.05});
  clock.stamp(0, hostAt(0.002));
  const Stamp host = hostAt(10 * kPeriod + 0.002);
  Stamp previous;
  for (int frame = 1; frame <= 10; ++frame) {
    const Stamp stamp = clock.stamp(static_cast<std::uint16_t>(frame), host);
    EXPECT_NEAR(secondsBetween(hostAt(frame * kPeriod + 0.002), stamp), 0.0, 1e-4) << frame;
    if (frame > 1) {
      EXPECT_NEAR(secondsBetween(previous, stamp), kPeriod, 1e-4);  // not all at `host`
    }
    EXPECT_LE(stamp.ns, host.ns);
    previous = stamp;
  }
  EXPECT_EQ(clock.resyncs(), 0u);  // a late burst is no reason to resynchronise
}

TEST(TickClockTest, AWrongTickPeriodIsResynchronisedAndStaysNearTheHost) {
  // The device ticks every 10 ms but the setting says 6.5536 ms: device time runs slow.
  TickClock clock({kPeriod, 1e-3, 0.05});
  for (int frame = 0; frame < 300; ++frame) {
    const Stamp host = hostAt(frame * 0.010);
    const Stamp stamp = clock.stamp(static_cast<std::uint16_t>(frame), host);
    // At most max_error_s plus the 8 lagging frames before a resync (3.4 ms each here).
    EXPECT_LE(secondsBetween(stamp, host), 0.05 + 8 * 0.0035 + 0.005);
  }
  EXPECT_GT(clock.resyncs(), 0u);
}

TEST(TickClockTest, ResetStartsAgainButKeepsStampsIncreasing) {
  TickClock clock({kPeriod, 1e-3, 0.05});
  clock.stamp(1000, hostAt(0.0));
  const Stamp before = clock.stamp(1010, hostAt(10 * kPeriod));
  clock.reset();
  // A new connection: the counter restarted; the host clock is what counts.
  const Stamp after = clock.stamp(5, hostAt(10 * kPeriod));
  EXPECT_EQ(clock.unwrappedTicks(), 5u);
  EXPECT_GT(after.ns, before.ns);
}

}  // namespace
}  // namespace mrslam::drivers
