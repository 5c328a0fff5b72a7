#include "mrslam/drivers/sensor_clock.hpp"

#include <gtest/gtest.h>

#include <random>

namespace mrslam::drivers {
namespace {

constexpr std::int64_t kMs = 1'000'000;
constexpr std::uint32_t kWrap = SensorClock::kCounterModulus;

/// A simulated sensor: its counter runs at (1 + rate_error) of host time, from `start_raw`.
struct SimulatedSensor {
  std::int64_t host_start_ns = 1'700'000'000'000'000'000;
  std::uint32_t start_raw = 0;
  double rate_error = 0.0;

  std::uint32_t rawAt(std::int64_t host_ns) const {
    const double elapsed_ms = (host_ns - host_start_ns) * (1.0 + rate_error) / kMs;
    return static_cast<std::uint32_t>((start_raw + static_cast<std::uint64_t>(elapsed_ms)) % kWrap);
  }
};

TEST(SensorClockTest, UnwrapsThe24BitCounter) {
  SensorClock clock;
  std::uint32_t raw = kWrap - 250;
  const std::int64_t first = (clock.stampScan(raw, Stamp{1000 * kMs}, 0, 0), clock.sensorTimeMs());
  for (int scan = 1; scan <= 10; ++scan) {
    raw = (raw + 100) % kWrap;
    clock.stampScan(raw, Stamp{(1000 + 100 * scan) * kMs}, 0, 0);
    EXPECT_EQ(clock.sensorTimeMs() - first, 100 * scan) << "scan " << scan << " raw " << raw;
  }
  EXPECT_LT(raw, 1000u);  // the counter did wrap
}

TEST(SensorClockTest, StampsAlwaysIncreaseEvenWhenTheCounterStepsBack) {
  SensorClock clock;
  const Stamp a = clock.stampScan(5000, Stamp{10 * kMs}, 0, 0);
  const Stamp b = clock.stampScan(4950, Stamp{11 * kMs}, 0, 0);  // stale: 50 ms back
  EXPECT_EQ(clock.sensorTimeMs(), 4950);                         // taken as a step back…
  EXPECT_GT(b, a);                                               // …yet the stamp increases
  clock.reset();                                                 // a new session keeps the floor
  const Stamp c = clock.stampScan(0, Stamp{1 * kMs}, 0, 0);
  EXPECT_GT(c, b);
}

TEST(SensorClockTest, WithoutTimeSyncTheOffsetIsTheSmallestLatencyBound) {
  const SimulatedSensor sensor{1'700'000'000'000'000'000, 123456, 0.0};
  std::mt19937 random(42);
  std::exponential_distribution<double> jitter_ms(1.0 / 3.0);  // mean 3 ms
  SensorClock clock;
  const std::int64_t fixed_latency = 2 * kMs;
  const std::int64_t last_beam = 70 * kMs;
  Stamp stamp;
  std::int64_t true_start = 0;
  for (int scan = 0; scan < 200; ++scan) {
    true_start = sensor.host_start_ns + scan * 100 * kMs;
    const auto receive =
        true_start + last_beam + fixed_latency + static_cast<std::int64_t>(jitter_ms(random) * kMs);
    stamp = clock.stampScan(sensor.rawAt(true_start), Stamp{receive}, 0, last_beam);
  }
  // Stamps lag by the fixed latency (the smallest bound), within the 1 ms counter resolution.
  EXPECT_NEAR(static_cast<double>(stamp.ns - true_start), fixed_latency, 1.2 * kMs);
}

/// The worst stamp error over one hour at 10 Hz after a TM sync, for a sensor clock running
/// `rate_error` fast, scans arriving after a 180 ms transfer (a slow serial line) plus jitter.
double worstErrorAfterTimeSync(double rate_error, unsigned seed) {
  const SimulatedSensor sensor{1'700'000'000'000'000'000, kWrap - 5000, rate_error};
  std::mt19937 random(seed);
  std::exponential_distribution<double> jitter_ms(1.0 / 2.0);
  SensorClock clock;
  std::int64_t host = sensor.host_start_ns;
  for (int round = 0; round < 5; ++round) {  // TM1 round trips of 2…4 ms
    const std::int64_t rtt = (2 + round % 3) * kMs;
    clock.addRoundTrip(sensor.rawAt(host + rtt / 2), Stamp{host}, Stamp{host + rtt});
    host += 10 * kMs;
  }
  EXPECT_TRUE(clock.synchronisedByRoundTrip());
  const std::int64_t last_beam = 70 * kMs;
  const std::int64_t transfer = 180 * kMs;
  double worst_error_ns = 0.0;
  for (int scan = 0; scan < 36000; ++scan) {
    const std::int64_t true_start = host + scan * 100 * kMs;
    const auto receive =
        true_start + last_beam + transfer + static_cast<std::int64_t>(jitter_ms(random) * kMs);
    const Stamp stamp = clock.stampScan(sensor.rawAt(true_start), Stamp{receive}, 0, last_beam);
    worst_error_ns = std::max(worst_error_ns, std::abs(double(stamp.ns - true_start)));
  }
  return worst_error_ns;
}

TEST(SensorClockTest, TimeSyncRemovesTheScanLatencyAndTracksDriftBothWays) {
  // 50 ppm over an hour is 180 ms of drift, the transfer 180 ms: the stamps stay within a few
  // ms of the true scan start all along.
  EXPECT_LT(worstErrorAfterTimeSync(50e-6, 7), 5.0 * kMs);
  EXPECT_LT(worstErrorAfterTimeSync(-50e-6, 8), 5.0 * kMs);
  EXPECT_LT(worstErrorAfterTimeSync(0.0, 9), 5.0 * kMs);
}

}  // namespace
}  // namespace mrslam::drivers
