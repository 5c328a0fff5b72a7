// Fuzz target: the 3DM-GX1 stream parser and frame decoders on arbitrary bytes. The first byte
// picks the accepted headers and how the rest is cut into reads. A returned frame must have
// its checksum right; anything else aborts.

#include <cstdint>
#include <cstdlib>
#include <vector>

#include "mrslam/drivers/gx1_codec.hpp"

namespace {

using namespace mrslam::drivers::gx1;

std::vector<std::uint8_t> headersFor(std::uint8_t choice) {
  const std::uint8_t all[] = {kEulerCommand, kEulerVectorsCommand, kQuaternionVectorsCommand,
                              kEepromReadCommand, kContinuousCommand};
  std::vector<std::uint8_t> headers;
  for (int i = 0; i < 5; ++i) {
    if ((choice & (1u << i)) != 0 || (choice & 0x1F) == 0) {
      headers.push_back(all[i]);
    }
  }
  return headers;
}

void check(const Frame& frame) {
  // Re-encoding gives the frame's bytes with a correct checksum: it must decode the same.
  const std::vector<std::uint16_t> words(frame.words.begin(),
                                         frame.words.begin() + frame.word_count);
  const std::vector<std::uint8_t> bytes = encodeFrame(frame.header, words);
  const auto again = decodeFrame(bytes.data(), bytes.size());
  if (!again || again->header != frame.header || bytes.size() != frameSize(frame.header)) {
    std::abort();
  }
  const Gains gains;
  decodeReading(frame, gains);
  decodeReading(frame, gains, QuaternionConvention::kEarthToSensor);
  decodeEepromValue(frame);
  decodeContinuousConfirmation(frame);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) {
    return 0;
  }
  const std::uint8_t choice = data[0];
  StreamParser parser(headersFor(choice));
  const std::size_t chunk = 1 + (choice >> 5) * 5;  // 1 .. 36 bytes per read
  std::uint64_t frames = 0;
  for (std::size_t at = 1; at < size; at += chunk) {
    const std::size_t count = at + chunk <= size ? chunk : size - at;
    parser.push(data + at, count);
    while (const auto frame = parser.next()) {
      check(*frame);
      ++frames;
    }
  }
  parser.discardPartial();
  const ParserCounters& counters = parser.counters();
  if (counters.frames != frames || parser.pending() != 0) {
    std::abort();
  }
  // Every input byte is in a frame, skipped, part of a rejected candidate's first byte, or in the
  // dropped partial frame: no more frames than could fit.
  if (frames * 7 > size) {
    std::abort();
  }
  return 0;
}
