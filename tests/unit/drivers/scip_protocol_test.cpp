#include "mrslam/drivers/scip_protocol.hpp"

#include <gtest/gtest.h>

#include "mrslam/drivers/scip_codec.hpp"

namespace mrslam::drivers::scip {
namespace {

ScanRequest mdRequest(int start, int end, int cluster = 1) {
  ScanRequest request;
  request.start_step = start;
  request.end_step = end;
  request.cluster = cluster;
  return request;
}

std::vector<std::uint32_t> sampleValues(std::size_t count) {
  std::vector<std::uint32_t> values;
  for (std::size_t i = 0; i < count; ++i) {
    values.push_back(static_cast<std::uint32_t>(100 + 10 * i));
  }
  return values;
}

/// An MD scan reply built line by line: 22 values = 66 chars, so value 21 is split between the
/// 64-char first line and the second line.
std::string splitValueScanReply(std::uint32_t stamp) {
  std::string chars;
  for (const std::uint32_t value : sampleValues(22)) {
    chars += encode(value, 3);
  }
  return "MD0044006501000\n99b\n" + withChecksum(encode(stamp, 4)) + "\n" +
         withChecksum(chars.substr(0, 64)) + "\n" + withChecksum(chars.substr(64)) + "\n\n";
}

Reply parsed(const std::string& block, LineCheck check = LineCheck::kData) {
  auto reply = parseReply(block, check);
  EXPECT_TRUE(reply.ok()) << reply.reason();
  return reply.ok() ? reply.value() : Reply{};
}

TEST(ScanRequestTest, TextEchoPrefixAndValueCount) {
  ScanRequest request = mdRequest(44, 725);
  EXPECT_EQ(request.text(), "MD0044072501000");
  EXPECT_EQ(request.echoPrefix(), "MD00440725010");
  EXPECT_EQ(request.valueCount(), 682u);
  EXPECT_EQ(request.valueChars(), 3);
  request.command = "GS";
  request.cluster = 3;
  EXPECT_EQ(request.text(), "GS0044072503");
  EXPECT_EQ(request.echoPrefix(), "GS0044072503");
  EXPECT_EQ(request.valueCount(), 228u);  // ceil(682 / 3)
  EXPECT_EQ(request.valueChars(), 2);
}

TEST(ParseReplyTest, SplitsEchoStatusAndDataLinesWithoutSumChars) {
  const Reply reply = parsed(splitValueScanReply(1000));
  EXPECT_EQ(reply.echo, "MD0044006501000");
  EXPECT_EQ(reply.status, "99");
  ASSERT_EQ(reply.data.size(), 3u);
  EXPECT_EQ(reply.data[0], encode(1000, 4));
  EXPECT_EQ(reply.data[1].size(), 64u);
  EXPECT_EQ(reply.data[2].size(), 2u);
}

TEST(ParseReplyTest, DetectsEveryKindOfDamage) {
  const std::string good = splitValueScanReply(1000);
  std::string bad_sum = good;
  bad_sum[good.find('\n', 26) - 1] ^= 0x01;  // the sum char of the first data line
  EXPECT_EQ(parseReply(bad_sum, LineCheck::kData).error(), ErrorKind::kChecksum);
  EXPECT_EQ(parseReply("VV\n00Q\n\n", LineCheck::kData).error(), ErrorKind::kChecksum);
  EXPECT_EQ(parseReply(good.substr(0, good.size() - 1), LineCheck::kData).error(),
            ErrorKind::kTruncated);
  EXPECT_EQ(parseReply("VV\n\n", LineCheck::kData).error(), ErrorKind::kTruncated);
  const auto scip11 = parseReply("QT\nE\n\n", LineCheck::kData);
  EXPECT_EQ(scip11.error(), ErrorKind::kGarbage);
  EXPECT_NE(scip11.reason().find("not a SCIP 2.0 status"), std::string::npos);
  const std::string long_line = withChecksum(std::string(65, '0'));
  EXPECT_EQ(parseReply("MD\n99b\n" + long_line + "\n\n", LineCheck::kData).error(),
            ErrorKind::kGarbage);
}

TEST(ParseReplyTest, KeyValueLinesOfTheSpecification) {
  const Reply reply = parsed("PP\n00P\nDMIN:20;4\nAMIN:44;7\nSCAN:600;e\n\n", LineCheck::kKeyValue);
  const auto values = parseKeyValues(reply);
  ASSERT_TRUE(values.ok()) << values.reason();
  EXPECT_EQ(values.value().at("DMIN"), "20");
  EXPECT_EQ(values.value().at("AMIN"), "44");
  EXPECT_EQ(values.value().at("SCAN"), "600");
  // The same lines fail the strict data-line check (the ';' is not summed).
  EXPECT_EQ(parseReply("PP\n00P\nDMIN:20;4\n\n", LineCheck::kData).error(), ErrorKind::kChecksum);
  const Reply no_colon = parsed("PP\n00P\n" + withChecksum("DMIN20") + "\n\n");
  EXPECT_EQ(parseKeyValues(no_colon).error(), ErrorKind::kGarbage);
}

TEST(DecodeScanReplyTest, DecodesValuesSplitAcrossLines) {
  const auto scan = decodeScanReply(parsed(splitValueScanReply(123456)), mdRequest(44, 65));
  ASSERT_TRUE(scan.ok()) << scan.reason();
  EXPECT_EQ(scan.value().timestamp_ms, 123456u);
  EXPECT_EQ(scan.value().ranges_mm, sampleValues(22));
  EXPECT_EQ(scan.value().remaining_scans, 0);
}

TEST(DecodeScanReplyTest, RoundTripsScanDataLinesOfFullSizeScans) {
  for (const auto& [start, end] : {std::pair{44, 725}, std::pair{0, 1080}}) {
    ScanRequest request = mdRequest(start, end);
    const auto values = sampleValues(request.valueCount());
    const std::string block = formatReply(request.text(), "99", scanDataLines(77, values, 3));
    const auto scan = decodeScanReply(parsed(block), request);
    ASSERT_TRUE(scan.ok()) << scan.reason();
    EXPECT_EQ(scan.value().ranges_mm, values);
  }
}

TEST(DecodeScanReplyTest, RejectsWrongEchoStatusAndValueCount) {
  const Reply reply = parsed(splitValueScanReply(5));
  EXPECT_EQ(decodeScanReply(reply, mdRequest(44, 66)).error(), ErrorKind::kGarbage);  // echo
  Reply error_status = reply;
  error_status.status = "50";
  const auto fault = decodeScanReply(error_status, mdRequest(44, 65));
  EXPECT_EQ(fault.error(), ErrorKind::kStatus);
  EXPECT_NE(fault.reason().find("hardware fault"), std::string::npos);
  Reply missing_line = reply;
  missing_line.data.pop_back();
  EXPECT_EQ(decodeScanReply(missing_line, mdRequest(44, 65)).error(), ErrorKind::kTruncated);
  Reply short_middle_line = reply;
  short_middle_line.data[1].pop_back();
  EXPECT_EQ(decodeScanReply(short_middle_line, mdRequest(44, 65)).error(), ErrorKind::kTruncated);
  Reply extra_values = reply;
  extra_values.data.back() += "000";
  EXPECT_EQ(decodeScanReply(extra_values, mdRequest(44, 65)).error(), ErrorKind::kGarbage);
  Reply no_stamp = reply;
  no_stamp.data.clear();
  EXPECT_EQ(decodeScanReply(no_stamp, mdRequest(44, 65)).error(), ErrorKind::kTruncated);
}

TEST(DecodeScanReplyTest, SingleScanRepliesCarryStatusOkAndTheExactEcho) {
  ScanRequest request = mdRequest(44, 65);
  request.command = "GD";
  const auto values = sampleValues(22);
  const Reply reply = parsed(formatReply("GD0044006501", "00", scanDataLines(9, values, 3)));
  const auto scan = decodeScanReply(reply, request);
  ASSERT_TRUE(scan.ok()) << scan.reason();
  EXPECT_EQ(scan.value().ranges_mm, values);
  EXPECT_FALSE(scan.value().remaining_scans.has_value());
  Reply laser_off = reply;
  laser_off.status = "10";
  EXPECT_NE(decodeScanReply(laser_off, request).reason().find("laser is off"), std::string::npos);
}

TEST(FindEchoTest, FindsTheEchoAfterNoise) {
  EXPECT_EQ(findEcho("MD0044\n99b\n", "MD0044"), 0u);
  EXPECT_EQ(findEcho("\x01\xffgarbage\nMD0044\n", "MD0044"), 10u);
  EXPECT_EQ(findEcho("garbage only\n\n", "MD0044"), std::string::npos);
}

TEST(ReplyFramerTest, CutsByteByByteInputIntoReplies) {
  const std::string stream = "\n\nVV\n00P\n\n" + splitValueScanReply(3);
  ReplyFramer framer;
  std::vector<std::string> blocks;
  for (const char c : stream) {
    framer.append(&c, 1);
    while (auto block = framer.next()) {
      blocks.push_back(*block);
    }
  }
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0], "VV\n00P\n\n");  // the leading empty lines are skipped
  EXPECT_EQ(blocks[1], splitValueScanReply(3));
  EXPECT_EQ(framer.pendingBytes(), 0u);
}

TEST(ReplyFramerTest, DropsARunOfNoiseWithoutAReplyEnd) {
  ReplyFramer framer(100);
  const std::string noise(150, 'x');
  framer.append(noise.data(), noise.size());
  EXPECT_FALSE(framer.next().has_value());
  EXPECT_EQ(framer.droppedBytes(), 150u);
  const std::string reply = "QT\n00P\n\n";
  framer.append(reply.data(), reply.size());
  EXPECT_EQ(framer.next(), reply);
}

TEST(FormatReplyTest, WritesTheLayoutOfTheSpecification) {
  EXPECT_EQ(formatReply("QT", "00", {}), "QT\n00P\n\n");
  EXPECT_EQ(keyValueLine("DMIN", "20"), "DMIN:20;4");
  EXPECT_EQ(keyValueLine("PROT", "SCIP 2.0"), "PROT:SCIP 2.0;N");
  const auto lines = scanDataLines(5432, sampleValues(22), 3);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], withChecksum("01Dh"));  // the stamp in 4 chars
  EXPECT_EQ(lines[1].size(), 65u);
  EXPECT_EQ(lines[2].size(), 3u);
}

}  // namespace
}  // namespace mrslam::drivers::scip
