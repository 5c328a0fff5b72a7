// The 3DM-GX1 stream parser: frames out of a byte stream, resynchronisation, error counts.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "mrslam/drivers/gx1_codec.hpp"

namespace mrslam::drivers::gx1 {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes eulerFrame(std::uint16_t roll, std::uint16_t ticks) {
  return encodeFrame(kEulerCommand, {roll, 0x0000, 0x0100, ticks});
}

void append(Bytes& stream, const Bytes& more) {
  stream.insert(stream.end(), more.begin(), more.end());
}

std::vector<Frame> parseAll(StreamParser& parser, const Bytes& stream) {
  parser.push(stream.data(), stream.size());
  std::vector<Frame> frames;
  while (std::optional<Frame> frame = parser.next()) {
    frames.push_back(*frame);
  }
  return frames;
}

TEST(Gx1StreamParserTest, FindsBackToBackFramesOfEveryKind) {
  Bytes stream = eulerFrame(1, 10);
  append(stream, encodeFrame(kEepromReadCommand, {10000, 11}));
  append(stream, encodeFrame(kEulerVectorsCommand, std::vector<std::uint16_t>(10, 0x0102)));
  append(stream, encodeFrame(kQuaternionVectorsCommand, std::vector<std::uint16_t>(14, 0x2000)));
  append(stream, encodeFrame(kContinuousCommand, {0x31, 12}));
  StreamParser parser;
  const auto frames = parseAll(parser, stream);
  ASSERT_EQ(frames.size(), 5u);
  EXPECT_EQ(frames[0].header, kEulerCommand);
  EXPECT_EQ(frames[0].ticks(), 10);
  EXPECT_EQ(frames[1].header, kEepromReadCommand);
  EXPECT_EQ(frames[2].header, kEulerVectorsCommand);
  EXPECT_EQ(frames[3].header, kQuaternionVectorsCommand);
  EXPECT_EQ(frames[4].header, kContinuousCommand);
  EXPECT_EQ(parser.counters().frames, 5u);
  EXPECT_EQ(parser.counters().garbage_bytes + parser.counters().bad_checksums, 0u);
}

TEST(Gx1StreamParserTest, WaitsForTheRestOfAFrameSplitAcrossReads) {
  const Bytes frame = eulerFrame(0x0203, 77);
  StreamParser parser;
  for (std::size_t i = 0; i + 1 < frame.size(); ++i) {
    parser.push(&frame[i], 1);
    EXPECT_FALSE(parser.next()) << "after byte " << i;
  }
  parser.push(&frame.back(), 1);
  const auto decoded = parser.next();
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->words[0], 0x0203);
  EXPECT_EQ(parser.pending(), 0u);
}

TEST(Gx1StreamParserTest, SkipsGarbageBytesAndCountsThem) {
  Bytes stream = {0x00, 0x55, 0xAA, 0xFF};
  append(stream, eulerFrame(5, 1));
  StreamParser parser;
  const auto frames = parseAll(parser, stream);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].words[0], 5);
  EXPECT_EQ(parser.counters().garbage_bytes, 4u);
  EXPECT_EQ(parser.counters().bad_checksums, 0u);
}

TEST(Gx1StreamParserTest, DropsABadChecksumAndResynchronisesOnTheNextFrame) {
  Bytes bad = eulerFrame(7, 1);
  bad.back() ^= 0x40;
  Bytes stream = bad;
  append(stream, eulerFrame(8, 2));
  StreamParser parser;
  const auto frames = parseAll(parser, stream);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].words[0], 8);
  EXPECT_EQ(parser.counters().bad_checksums, 1u);
  EXPECT_EQ(parser.counters().garbage_bytes, bad.size() - 1);
}

TEST(Gx1StreamParserTest, FindsAFrameStartingInsideARejectedCandidate) {
  // A truncated 0x31 frame: its 23-byte candidate swallows the start of the next good frame,
  // which must still be found by sliding one byte at a time.
  Bytes stream = encodeFrame(kEulerVectorsCommand, std::vector<std::uint16_t>(10, 0x0101));
  stream.resize(9);
  append(stream, eulerFrame(9, 3));
  append(stream, eulerFrame(10, 4));
  StreamParser parser;
  const auto frames = parseAll(parser, stream);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].words[0], 9);
  EXPECT_EQ(frames[1].words[0], 10);
  EXPECT_GE(parser.counters().bad_checksums, 1u);
}

TEST(Gx1StreamParserTest, OnlyAcceptedHeadersStartFrames) {
  Bytes stream = encodeFrame(kEepromReadCommand, {1, 2});
  append(stream, eulerFrame(11, 5));
  StreamParser parser({kEulerCommand});
  const auto frames = parseAll(parser, stream);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].header, kEulerCommand);
  EXPECT_EQ(parser.counters().garbage_bytes, 7u);
}

TEST(Gx1StreamParserTest, DiscardPartialCountsATruncatedFrame) {
  const Bytes frame = eulerFrame(12, 6);
  StreamParser parser;
  parser.push(frame.data(), 6);
  EXPECT_FALSE(parser.next());
  parser.discardPartial();
  EXPECT_EQ(parser.counters().truncated_frames, 1u);
  EXPECT_EQ(parser.pending(), 0u);
  parser.discardPartial();  // nothing pending: nothing counted
  EXPECT_EQ(parser.counters().truncated_frames, 1u);
  const auto frames = parseAll(parser, frame);
  EXPECT_EQ(frames.size(), 1u);
}

TEST(Gx1StreamParserTest, NeverReturnsAFrameWithABadChecksumFromRandomBytes) {
  std::mt19937 random(42);
  StreamParser parser;
  Bytes whole;
  std::vector<Frame> frames;
  for (int round = 0; round < 200; ++round) {
    Bytes stream(1 + random() % 64);
    for (auto& byte : stream) {
      byte = static_cast<std::uint8_t>(random());
    }
    append(stream, eulerFrame(static_cast<std::uint16_t>(round), 0));
    append(whole, stream);
    for (const Frame& frame : parseAll(parser, stream)) {
      frames.push_back(frame);
    }
  }
  std::size_t ours = 0;
  for (const Frame& frame : frames) {
    // A frame is handed out only as it stood in the stream, checksum included.
    const Bytes bytes = encodeFrame(
        frame.header,
        std::vector<std::uint16_t>(frame.words.begin(), frame.words.begin() + frame.word_count));
    EXPECT_NE(std::search(whole.begin(), whole.end(), bytes.begin(), bytes.end()), whole.end());
    ours += frame.header == kEulerCommand && frame.words[1] == 0 && frame.words[2] == 0x0100;
  }
  // No byte of a good frame is ever skipped, so every inserted frame is found.
  EXPECT_EQ(ours, 200u);
  EXPECT_GT(parser.counters().garbage_bytes, 1000u);
}

}  // namespace
}  // namespace mrslam::drivers::gx1
