// 3DM-GX1 stream parser throughput: frames per second for 0x31 (23 bytes) and 0x0C (31 bytes)
// frames, clean and with one frame in 20 corrupted, fed in 64-byte reads as a serial port would.
// At 38400 baud a device delivers at most ~167 frames/s of 0x31 and ~124 of 0x0C; the
// "x_realtime" counter is how many such devices one core could parse.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include "mrslam/drivers/gx1_codec.hpp"

namespace mrslam::drivers::gx1 {
namespace {

constexpr int kFrames = 1000;
constexpr std::size_t kReadSize = 64;
constexpr double kBytesPerSecond = 38400.0 / 10.0;  // 8N1: 10 bits per byte

std::vector<std::uint8_t> stream(std::uint8_t command, int corrupt_every) {
  DeviceState device;
  device.roll_rad = 0.1;
  device.pitch_rad = -0.05;
  device.yaw_rad = 1.2;
  device.acceleration_g = {0.01, -0.02, -1.0};
  device.angular_rate_rad_s = {0.001, 0.002, 0.3};
  device.magnetic_gauss = {0.2, 0.0, 0.4};
  std::vector<std::uint8_t> bytes;
  for (int i = 0; i < kFrames; ++i) {
    std::vector<std::uint8_t> frame =
        encodeReading(command, device, Gains{}, static_cast<std::uint16_t>(i));
    if (corrupt_every > 0 && i % corrupt_every == 0) {
      frame[frame.size() / 2] ^= 0x5A;
    }
    bytes.insert(bytes.end(), frame.begin(), frame.end());
  }
  return bytes;
}

void BM_ParseStream(benchmark::State& state, std::uint8_t command, int corrupt_every) {
  const std::vector<std::uint8_t> bytes = stream(command, corrupt_every);
  const Gains gains;
  std::int64_t frames = 0;
  for (auto _ : state) {
    StreamParser parser({command});
    for (std::size_t at = 0; at < bytes.size(); at += kReadSize) {
      parser.push(bytes.data() + at, std::min(kReadSize, bytes.size() - at));
      while (const auto frame = parser.next()) {
        benchmark::DoNotOptimize(decodeReading(*frame, gains));
        ++frames;
      }
    }
  }
  state.SetItemsProcessed(frames);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes.size()));
  const double device_frames_per_second = kBytesPerSecond / static_cast<double>(frameSize(command));
  state.counters["x_realtime"] = benchmark::Counter(
      static_cast<double>(frames) / device_frames_per_second, benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(BM_ParseStream, euler_vectors_0x31, kEulerVectorsCommand, 0);
BENCHMARK_CAPTURE(BM_ParseStream, quaternion_vectors_0x0C, kQuaternionVectorsCommand, 0);
BENCHMARK_CAPTURE(BM_ParseStream, euler_vectors_0x31_5pc_corrupt, kEulerVectorsCommand, 20);
BENCHMARK_CAPTURE(BM_ParseStream, quaternion_vectors_0x0C_5pc_corrupt, kQuaternionVectorsCommand,
                  20);

}  // namespace
}  // namespace mrslam::drivers::gx1

BENCHMARK_MAIN();
