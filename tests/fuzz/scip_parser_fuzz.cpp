// Fuzz target: the SCIP 2.0 reply parser on arbitrary bytes. The input is cut into replies by
// the framer (in two chunk sizes), and each reply goes through every parser the driver uses:
// line checks of both kinds, key:value parsing, PP geometry, and scan decoding for the scan
// requests the driver and the emulator make, down to a LaserScan.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "mrslam/drivers/scip_geometry.hpp"
#include "mrslam/drivers/scip_protocol.hpp"

namespace {

using namespace mrslam::drivers::scip;

ScanRequest requestFor(const char* command, int start, int end, int cluster) {
  ScanRequest request;
  request.command = command;
  request.start_step = start;
  request.end_step = end;
  request.cluster = cluster;
  return request;
}

const ScanRequest kRequests[] = {
    requestFor("MD", 44, 725, 1), requestFor("GD", 44, 725, 1),  requestFor("MD", 44, 50, 1),
    requestFor("MS", 0, 1080, 3), requestFor("GD", 244, 756, 1),
};

void parseBlock(const std::string& block) {
  const ScanGeometry urg04lx{20, 5600, 1024, 44, 725, 384, 600};
  if (auto reply = parseReply(block, LineCheck::kKeyValue)) {
    if (auto values = parseKeyValues(reply.value())) {
      if (auto geometry = ScanGeometry::fromParameters(values.value())) {
        geometry.value().stepAngleRad(geometry.value().amax);
      }
    }
  }
  const auto reply = parseReply(block, LineCheck::kData);
  if (!reply) {
    return;
  }
  for (const ScanRequest& request : kRequests) {
    findEcho(block, request.echoPrefix());
    if (auto scan = decodeScanReply(reply.value(), request)) {
      if (scan.value().ranges_mm.size() != request.valueCount()) {
        __builtin_trap();  // a decoded scan always has exactly the values asked for
      }
      toLaserScan(scan.value().ranges_mm, urg04lx, request, ZeroRange::kInvalid);
    }
  }
}

void frameAndParse(const std::uint8_t* data, std::size_t size, std::size_t chunk) {
  ReplyFramer framer(4096);
  for (std::size_t at = 0; at < size; at += chunk) {
    const std::size_t length = std::min(chunk, size - at);
    framer.append(reinterpret_cast<const char*>(data + at), length);
    while (auto block = framer.next()) {
      parseBlock(*block);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  frameAndParse(data, size, 1);
  frameAndParse(data, size, 4096);
  return 0;
}
