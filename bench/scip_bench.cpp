// Decode throughput of Hokuyo MD scans: reply framing, line checks, value decoding and the
// conversion to a LaserScan, for 682-step (URG-04LX) and 1081-step (UTM-30LX class) scans.
// Reported as scans per second (items_per_second) and bytes per second.

#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>
#include <vector>

#include "mrslam/drivers/scip_geometry.hpp"
#include "mrslam/drivers/scip_protocol.hpp"

namespace {

using namespace mrslam::drivers::scip;

struct ScanFixture {
  ScanGeometry geometry;
  ScanRequest request;
  std::string reply;
};

/// An MD scan reply of `steps` steps from `amin` with varied ranges.
ScanFixture makeScan(const ScanGeometry& geometry) {
  ScanFixture fixture{geometry, {}, {}};
  fixture.request.start_step = geometry.amin;
  fixture.request.end_step = geometry.amax;
  std::vector<std::uint32_t> values;
  for (std::size_t i = 0; i < fixture.request.valueCount(); ++i) {
    values.push_back(static_cast<std::uint32_t>(geometry.dmin_mm + (i * 37) % 5000));
  }
  fixture.reply = formatReply(fixture.request.text(), "99", scanDataLines(123456, values, 3));
  return fixture;
}

const ScanGeometry kUrg04lx{20, 5600, 1024, 44, 725, 384, 600};    // 682 steps
const ScanGeometry kUtm30lx{23, 60000, 1440, 0, 1080, 540, 2400};  // 1081 steps

void decodeScans(benchmark::State& state, const ScanGeometry& geometry) {
  const ScanFixture fixture = makeScan(geometry);
  ReplyFramer framer;
  for (auto _ : state) {
    framer.append(fixture.reply.data(), fixture.reply.size());
    const auto block = framer.next();
    const auto reply = parseReply(*block, LineCheck::kData);
    const auto data = decodeScanReply(reply.value(), fixture.request);
    const auto scan =
        toLaserScan(data.value().ranges_mm, fixture.geometry, fixture.request, ZeroRange::kInvalid);
    benchmark::DoNotOptimize(scan.ranges_m.data());
  }
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(fixture.reply.size()));
  state.counters["steps"] = static_cast<double>(fixture.request.valueCount());
}

void BM_DecodeMdScan682Steps(benchmark::State& state) {
  decodeScans(state, kUrg04lx);
}
void BM_DecodeMdScan1081Steps(benchmark::State& state) {
  decodeScans(state, kUtm30lx);
}

BENCHMARK(BM_DecodeMdScan682Steps);
BENCHMARK(BM_DecodeMdScan1081Steps);

}  // namespace

BENCHMARK_MAIN();
