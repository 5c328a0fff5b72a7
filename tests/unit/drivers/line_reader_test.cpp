#include "mrslam/drivers/line_reader.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <fstream>

#include "test_data.hpp"

namespace mrslam::drivers {
namespace {

// Reads every line, checking that the share read only grows and ends at the whole file.
void expectProgressToTheEnd(const std::string& path, std::size_t lines) {
  LineReader reader(path);
  EXPECT_DOUBLE_EQ(reader.fractionRead(), 0.0);
  std::string line;
  double before = 0.0;
  std::size_t read = 0;
  while (reader.next(line)) {
    ++read;
    EXPECT_GE(reader.fractionRead(), before);
    before = reader.fractionRead();
  }
  EXPECT_EQ(read, lines);
  EXPECT_DOUBLE_EQ(reader.fractionRead(), 1.0);
}

TEST(LineReaderTest, TheShareReadGrowsToTheWholeFile) {
  const auto folder = test::scratchFolder("lines");
  const std::string plain = (folder / "plain.log").string();
  {
    std::ofstream file(plain);
    for (int i = 0; i < 200000; ++i) {  // more than one read buffer
      file << "ODOM " << i << " 0 0 0 0 0 " << i << "\n";
    }
  }
  expectProgressToTheEnd(plain, 200000);
  const std::string packed = (folder / "packed.log.gz").string();
  gzFile gz = gzopen(packed.c_str(), "wb");
  for (int i = 0; i < 200000; ++i) {
    gzprintf(gz, "ODOM %d 0 0 0 0 0 %d\n", i, i);
  }
  gzclose(gz);
  expectProgressToTheEnd(packed, 200000);
}

TEST(LineReaderTest, HalfwayThroughALogIsNeitherTheStartNorTheEnd) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/carmen-intel-corrected.log.gz");
  LineReader reader(test::sharedDataPath("logs/carmen-intel-corrected.log.gz"));
  std::string line;
  for (int i = 0; i < 5000 && reader.next(line); ++i) {
  }
  EXPECT_GT(reader.fractionRead(), 0.05);
  EXPECT_LT(reader.fractionRead(), 0.95);
}

}  // namespace
}  // namespace mrslam::drivers
