#include "mrslam/drivers/scip_codec.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

namespace mrslam::drivers::scip {
namespace {

TEST(ScipChecksumTest, StatusLinesOfTheSpecification) {
  EXPECT_EQ(checksum("00"), 'P');
  EXPECT_EQ(checksum("99"), 'b');
  EXPECT_TRUE(hasValidChecksum("00P"));
  EXPECT_TRUE(hasValidChecksum("99b"));
  EXPECT_FALSE(hasValidChecksum("00Q"));
  EXPECT_FALSE(hasValidChecksum("0"));  // no room for a sum char
}

TEST(ScipChecksumTest, KeyValueVectorsOfTheSpecificationSumWithoutTheSemicolon) {
  for (const char* line : {"PROT:SCIP 2.0;N", "DMIN:20;4", "AMIN:44;7", "SCAN:600;e"}) {
    EXPECT_TRUE(hasValidKeyValueChecksum(line)) << line;
    EXPECT_FALSE(hasValidChecksum(line)) << line << ": the ';' is not part of the sum";
  }
  EXPECT_EQ(checksum("DMIN:20"), '4');
  EXPECT_EQ(checksum("PROT:SCIP 2.0"), 'N');
}

TEST(ScipChecksumTest, KeyValueLinesSummedWithTheSemicolonAreAcceptedToo) {
  const std::string with_semicolon = std::string("DMIN:20;") + checksum("DMIN:20;");
  ASSERT_NE(with_semicolon.back(), '4');  // the two conventions differ on this line
  EXPECT_TRUE(hasValidKeyValueChecksum(with_semicolon));
  EXPECT_FALSE(hasValidKeyValueChecksum("DMIN:20;5"));
  EXPECT_FALSE(hasValidKeyValueChecksum("DMIN:21;4"));
}

TEST(ScipChecksumTest, WithChecksumAppendsTheSumChar) {
  EXPECT_EQ(withChecksum("00"), "00P");
  EXPECT_EQ(withChecksum("SCAN:600"), "SCAN:600e");
}

TEST(ScipEncodingTest, VectorsOfTheSpecification) {
  EXPECT_EQ(encode(1234, 2), "CB");
  EXPECT_EQ(encode(5432, 3), "1Dh");
  EXPECT_EQ(decode("CB"), 1234u);
  EXPECT_EQ(decode("1Dh"), 5432u);
  EXPECT_EQ(encode(0, 4), "0000");
  EXPECT_EQ(encode((1u << 24) - 1, 4), "oooo");
  EXPECT_EQ(decode("oooo"), (1u << 24) - 1);
}

TEST(ScipEncodingTest, RoundTripsRandomValuesOfEveryWidth) {
  std::mt19937 random(42);
  for (int chars = 1; chars <= 4; ++chars) {
    std::uniform_int_distribution<std::uint32_t> value(0, (1u << (6 * chars)) - 1);
    for (int i = 0; i < 200; ++i) {
      const std::uint32_t v = value(random);
      const std::string text = encode(v, chars);
      ASSERT_EQ(text.size(), static_cast<std::size_t>(chars));
      EXPECT_EQ(decode(text), v);
    }
  }
}

TEST(ScipEncodingTest, RejectsValuesThatDoNotFitAndCharsOutsideTheAlphabet) {
  EXPECT_THROW(encode(4096, 2), std::invalid_argument);
  EXPECT_THROW(encode(1, 5), std::invalid_argument);
  EXPECT_FALSE(decode("").has_value());
  EXPECT_FALSE(decode("00000").has_value());
  EXPECT_FALSE(decode("/0").has_value());  // 0x2F: below '0'
  EXPECT_FALSE(decode("0p").has_value());  // 0x70: above 'o'
  EXPECT_FALSE(decode(std::string("0\n")).has_value());
}

TEST(ScipEncodingTest, DecodeValuesNeedsWholeValuesAndLeavesTheOutputUnchangedOnError) {
  std::vector<std::uint32_t> values{7};
  EXPECT_TRUE(decodeValues("1DhCB0", 3, values));  // "CB0" = 1234 · 64
  EXPECT_EQ(values, (std::vector<std::uint32_t>{7, 5432, 1234u * 64}));
  EXPECT_FALSE(decodeValues("1DhC", 3, values));
  EXPECT_FALSE(decodeValues("1Dh~~~", 3, values));
  EXPECT_EQ(values.size(), 3u);
}

TEST(ScipStatusTest, EveryStatusHasAClearText) {
  EXPECT_EQ(statusText("VV", "00"), "OK");
  EXPECT_EQ(statusText("MD", "99"), "scan data follows");
  EXPECT_EQ(statusText("MD", "01"), "parameter error: start step is not a number");
  EXPECT_EQ(statusText("MS", "04"), "parameter error: end step is out of range");
  EXPECT_EQ(statusText("GD", "05"), "parameter error: end step is below the start step");
  EXPECT_EQ(statusText("MD", "07"), "parameter error: number of scans is not a number");
  EXPECT_EQ(statusText("GD", "10"), "laser is off");
  EXPECT_EQ(statusText("BM", "01"), "laser malfunction");
  EXPECT_EQ(statusText("BM", "02"), "laser already on");
  EXPECT_EQ(statusText("MD", "50"), "hardware fault (status 50)");
  EXPECT_EQ(statusText("GD", "97"), "hardware fault (status 97)");
  EXPECT_EQ(statusText("ZZ", "0E"), "undefined command");
  EXPECT_EQ(statusText("MD", "98"), "unknown status 98");
  EXPECT_EQ(statusText("VV", "01"), "unknown status 01");  // parameter errors are MD/MS/GD/GS
}

TEST(ScipStatusTest, SuccessIsOkScanDataAndLaserAlreadyOn) {
  EXPECT_TRUE(isSuccessStatus("QT", "00"));
  EXPECT_TRUE(isSuccessStatus("MD", "99"));
  EXPECT_TRUE(isSuccessStatus("BM", "02"));
  EXPECT_FALSE(isSuccessStatus("MD", "02"));
  EXPECT_FALSE(isSuccessStatus("BM", "01"));
  EXPECT_FALSE(isSuccessStatus("GD", "10"));
}

}  // namespace
}  // namespace mrslam::drivers::scip
