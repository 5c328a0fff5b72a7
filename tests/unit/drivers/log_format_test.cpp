#include "mrslam/drivers/log_format.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "mrslam/drivers/breezyslam_reader.hpp"
#include "mrslam/drivers/carmen_reader.hpp"
#include "mrslam/drivers/line_reader.hpp"
#include "test_data.hpp"

namespace mrslam::drivers {
namespace {

using ::testing::HasSubstr;

std::string writeFile(const std::filesystem::path& path, const std::string& content) {
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

/// The whole text of a (possibly gzip) file, lines ended by '\n'.
std::string readText(const std::string& path) {
  LineReader lines(path);
  std::string text;
  std::string line;
  while (lines.next(line)) {
    text += line;
    text += '\n';
  }
  return text;
}

std::size_t countScans(SampleSource& source) {
  std::size_t scans = 0;
  while (std::optional<Sample> sample = source.next()) {
    scans += std::holds_alternative<LaserScan>(*sample) ? 1 : 0;
  }
  return scans;
}

// ---------------------------------------------------------------------------------------------
// Format detection

struct RealFile {
  const char* file;
  LogFormat format;
  std::size_t scans;
};

void PrintTo(const RealFile& file, std::ostream* out) {
  *out << file.file;
}

class LogFormatRealFileTest : public ::testing::TestWithParam<RealFile> {};

TEST_P(LogFormatRealFileTest, DetectsTheFormatAndOpensTheRightReader) {
  const std::string relative = std::string("logs/") + GetParam().file;
  MRSLAM_REQUIRE_SHARED_DATA(relative);
  const std::string path = test::sharedDataPath(relative);
  EXPECT_EQ(detectLogFormat(path), GetParam().format);

  const std::unique_ptr<SampleSource> source = openLogReader(path, MalformedPolicy::kStop);
  if (GetParam().format == LogFormat::kBreezySlam) {
    const auto* reader = dynamic_cast<const BreezySlamReader*>(source.get());
    ASSERT_NE(reader, nullptr);
    EXPECT_EQ(reader->settings().malformed_policy, MalformedPolicy::kStop);
    EXPECT_EQ(source->describe(), "breezyslam log " + path);
  } else {
    const auto* reader = dynamic_cast<const CarmenReader*>(source.get());
    ASSERT_NE(reader, nullptr);
    EXPECT_EQ(reader->settings().malformed_policy, MalformedPolicy::kStop);
    EXPECT_EQ(source->describe(), "carmen log " + path);
  }
  EXPECT_EQ(countScans(*source), GetParam().scans);
}

TEST_P(LogFormatRealFileTest, DetectsGzipAndPlainCopiesByContent) {
  const std::string relative = std::string("logs/") + GetParam().file;
  MRSLAM_REQUIRE_SHARED_DATA(relative);
  const std::string text = readText(test::sharedDataPath(relative));
  const auto folder = test::scratchFolder("copies");
  // Names that say nothing (or the wrong thing) about the content.
  const std::string plain = writeFile(folder / "copy.gz", text);
  const std::string gzip = (folder / "copy.txt").string();
  writeGzipFile(gzip, text);

  EXPECT_EQ(detectLogFormat(plain), GetParam().format);
  EXPECT_EQ(detectLogFormat(gzip), GetParam().format);
  const std::unique_ptr<SampleSource> from_plain = openLogReader(plain, MalformedPolicy::kStop);
  const std::unique_ptr<SampleSource> from_gzip = openLogReader(gzip, MalformedPolicy::kStop);
  EXPECT_EQ(countScans(*from_plain), GetParam().scans);
  EXPECT_EQ(countScans(*from_gzip), GetParam().scans);
}

INSTANTIATE_TEST_SUITE_P(
    Logs, LogFormatRealFileTest,
    ::testing::Values(RealFile{"breezyslam-exp1.dat", LogFormat::kBreezySlam, 756},
                      RealFile{"breezyslam-exp2.dat", LogFormat::kBreezySlam, 641},
                      RealFile{"carmen-intel-corrected.log.gz", LogFormat::kCarmen, 910},
                      RealFile{"carmen-aces-corrected.log.gz", LogFormat::kCarmen, 440},
                      RealFile{"carmen-csail-corrected.log.gz", LogFormat::kCarmen, 406}),
    [](const ::testing::TestParamInfo<RealFile>& param_info) {
      std::string name = param_info.param.file;
      name = name.substr(0, name.find('.'));
      for (char& c : name) {
        c = c == '-' ? '_' : c;
      }
      return name;
    });

TEST(LogFormatTest, SmallFilesOfEachFormat) {
  const auto folder = test::scratchFolder("small");
  std::string breezy = "1000 0 1 2";
  for (int i = 4; i < 26; ++i) {
    breezy += " 0";
  }
  EXPECT_EQ(detectLogFormat(writeFile(folder / "a", breezy + "\n")), LogFormat::kBreezySlam);
  EXPECT_EQ(detectLogFormat(writeFile(folder / "b", "# comment\n\nFLASER 1 2 0 0 0 0 0 0 1 h 1\n")),
            LogFormat::kCarmen);
  EXPECT_EQ(detectLogFormat(writeFile(folder / "c", "PARAM robot_use_laser on nohost 0\n")),
            LogFormat::kCarmen);
  EXPECT_EQ(detectLogFormat(writeFile(folder / "d", "ROBOTLASER1 0 0 0\n")), LogFormat::kCarmen);
}

TEST(LogFormatTest, GarbageIsUnknown) {
  const auto folder = test::scratchFolder("garbage");
  std::mt19937 random(42);
  std::string bytes(8192, '\0');
  for (char& c : bytes) {
    c = static_cast<char>(random() & 0xff);
  }
  std::string numbers_no_newline;
  while (numbers_no_newline.size() < 200000) {
    numbers_no_newline += "1 ";
  }
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"random", bytes},
      {"empty", ""},
      {"blank", "\n\n  \n"},
      {"comments", "# message formats defined: PARAM SYNC ODOM FLASER\n# more\n"},
      {"text", "hello world\nFLASER 1 2 3\n"},
      {"lowercase", "flaser 1 2 0 0 0 0 0 0 1 h 1\n"},
      {"few_numbers", "1000 0 1 2 3\n"},
      {"float_stamp",
       "1000.5" + std::string(60, ' ') + "1 2 3 4 5 6 7 8 9 1 2 3 4 5 6 7 8 9 1 2 3 4 5 6 7 8\n"},
      {"csv", "1000,0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20,21,22,23,24,25\n"},
      {"endless_line", numbers_no_newline},
  };
  for (const auto& [name, content] : cases) {
    const std::string path = writeFile(folder / name, content);
    EXPECT_EQ(detectLogFormat(path), LogFormat::kUnknown) << name;
    try {
      openLogReader(path, MalformedPolicy::kSkip);
      ADD_FAILURE() << name << ": opened a reader";
    } catch (const std::runtime_error& error) {
      EXPECT_THAT(error.what(), HasSubstr(path + ": unknown log format")) << name;
    }
  }
  const std::string gzip = (folder / "random.gz").string();
  writeGzipFile(gzip, bytes);
  EXPECT_EQ(detectLogFormat(gzip), LogFormat::kUnknown);
}

TEST(LogFormatTest, MissingFileCannotBeOpened) {
  const auto folder = test::scratchFolder("missing");
  const std::string path = (folder / "nothing.log").string();
  EXPECT_THAT([&] { detectLogFormat(path); },
              ::testing::ThrowsMessage<std::runtime_error>(HasSubstr(path + ": cannot open")));
  EXPECT_THAT([&] { openLogReader(path, MalformedPolicy::kSkip); },
              ::testing::ThrowsMessage<std::runtime_error>(HasSubstr(path + ": cannot open")));
  EXPECT_THAT([&] { detectLogFormat(folder.string()); },
              ::testing::ThrowsMessage<std::runtime_error>(HasSubstr(": cannot open")));
}

TEST(LogFormatTest, FormatNames) {
  EXPECT_STREQ(logFormatName(LogFormat::kBreezySlam), "breezyslam");
  EXPECT_STREQ(logFormatName(LogFormat::kCarmen), "carmen");
  EXPECT_STREQ(logFormatName(LogFormat::kUnknown), "unknown");
}

// ---------------------------------------------------------------------------------------------
// Malformed-line handling shared by the readers

TEST(LogFormatTest, LogFormatErrorNamesFileAndLine) {
  const LogFormatError error("logs/exp1.dat", 17, "expected 707 fields, found 12");
  EXPECT_STREQ(error.what(), "logs/exp1.dat:17: expected 707 fields, found 12");
  EXPECT_EQ(error.path(), "logs/exp1.dat");
  EXPECT_EQ(error.line(), 17u);
  EXPECT_EQ(error.problem(), "expected 707 fields, found 12");
  const std::runtime_error& base = error;
  EXPECT_STREQ(base.what(), error.what());
}

TEST(LogFormatTest, MalformedLineHandlerStopsOrCounts) {
  MalformedLineHandler stop("test", MalformedPolicy::kStop);
  EXPECT_THROW(stop.handle("a.log", 3, {"field count", "too short"}), LogFormatError);

  MalformedLineHandler skip("test", MalformedPolicy::kSkip);
  for (std::size_t line = 1; line <= 5; ++line) {
    skip.handle("a.log", line, {"field count", "too short"});
  }
  skip.handle("a.log", 9, {"not a number", "field 2: 'x' is not a number"});
  EXPECT_EQ(skip.count(), 6u);
  EXPECT_EQ(skip.countsByKind(),
            (std::map<std::string, std::uint64_t>{{"field count", 5}, {"not a number", 1}}));
}

// ---------------------------------------------------------------------------------------------
// LineReader and the field helpers

TEST(LineReaderTest, ReadsPlainAndGzipAlike) {
  const auto folder = test::scratchFolder("lines");
  const std::string long_line(3 * 1000 * 1000 + 7, 'x');  // spans many read chunks
  const std::string content = "first\n\nthird field\r\n" + long_line + "\nlast without end";
  const std::string plain = writeFile(folder / "plain.txt", content);
  const std::string gzip = (folder / "zipped.txt.gz").string();
  writeGzipFile(gzip, content);
  {
    std::ifstream raw(gzip, std::ios::binary);
    EXPECT_EQ(raw.get(), 0x1f);  // gzip magic: the file really is compressed
    EXPECT_EQ(raw.get(), 0x8b);
  }
  for (const std::string& path : {plain, gzip}) {
    LineReader lines(path);
    EXPECT_EQ(lines.path(), path);
    EXPECT_EQ(lines.lineNumber(), 0u);
    std::string line;
    const std::vector<std::string> expected = {"first", "", "third field", long_line,
                                               "last without end"};
    for (std::size_t i = 0; i < expected.size(); ++i) {
      ASSERT_TRUE(lines.next(line)) << path << " line " << i + 1;
      EXPECT_EQ(line, expected[i]) << path << " line " << i + 1;
      EXPECT_EQ(lines.lineNumber(), i + 1);
      EXPECT_FALSE(lines.lastLineCut());
    }
    EXPECT_FALSE(lines.next(line));
    EXPECT_FALSE(lines.next(line));
    EXPECT_EQ(lines.lineNumber(), expected.size());
  }
}

TEST(LineReaderTest, CutsLinesLongerThanTheLimit) {
  const auto folder = test::scratchFolder("lines");
  const std::string path = writeFile(folder / "a.txt", "abcdefghij\nshort\n");
  LineReader lines(path, 4);
  std::string line;
  ASSERT_TRUE(lines.next(line));
  EXPECT_EQ(line, "abcd");
  EXPECT_TRUE(lines.lastLineCut());
  ASSERT_TRUE(lines.next(line));
  EXPECT_EQ(line, "shor");
  EXPECT_TRUE(lines.lastLineCut());
  EXPECT_EQ(lines.lineNumber(), 2u);
  EXPECT_FALSE(lines.next(line));
}

TEST(LineReaderTest, EmptyFileHasNoLines) {
  const auto folder = test::scratchFolder("lines");
  LineReader lines(writeFile(folder / "empty.txt", ""));
  std::string line = "stale";
  EXPECT_FALSE(lines.next(line));
  EXPECT_EQ(lines.lineNumber(), 0u);
}

TEST(LineReaderTest, TruncatedGzipIsAReadError) {
  const auto folder = test::scratchFolder("lines");
  std::string content;
  std::mt19937 random(42);
  for (int i = 0; i < 20000; ++i) {
    content += std::to_string(random()) + "\n";  // hardly compressible
  }
  const std::string whole = (folder / "whole.gz").string();
  writeGzipFile(whole, content);
  std::ifstream in(whole, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = writeFile(folder / "cut.gz", bytes.substr(0, bytes.size() / 2));

  LineReader lines(cut);
  std::string line;
  std::size_t read = 0;
  try {
    while (lines.next(line)) {
      ++read;
    }
    FAIL() << "read " << read << " lines of a truncated gzip file without an error";
  } catch (const std::runtime_error& error) {
    EXPECT_THAT(error.what(), HasSubstr(cut + ": read error after line"));
  }
  EXPECT_GT(read, 1000u);
  EXPECT_LT(read, 20000u);
}

TEST(LineReaderTest, SplitsFieldsAtRunsOfBlanks) {
  std::vector<std::string_view> fields = {"stale"};
  splitFields("  FLASER\t3  1.5 \r", fields);
  EXPECT_EQ(fields, (std::vector<std::string_view>{"FLASER", "3", "1.5"}));
  splitFields("   ", fields);
  EXPECT_TRUE(fields.empty());
}

TEST(LineReaderTest, ParsesWholeFieldsOnly) {
  EXPECT_EQ(parseInteger("-12"), -12);
  EXPECT_EQ(parseInteger("+7"), 7);
  EXPECT_EQ(parseInteger("212387282"), 212387282);
  EXPECT_FALSE(parseInteger(""));
  EXPECT_FALSE(parseInteger("1.0"));
  EXPECT_FALSE(parseInteger("12a"));
  EXPECT_FALSE(parseInteger("+-1"));
  EXPECT_FALSE(parseInteger("99999999999999999999"));

  EXPECT_DOUBLE_EQ(*parseNumber("0.600266"), 0.600266);
  EXPECT_DOUBLE_EQ(*parseNumber("-2e-3"), -0.002);
  EXPECT_DOUBLE_EQ(*parseNumber("+1.5"), 1.5);
  EXPECT_TRUE(std::isnan(*parseNumber("nan")));
  EXPECT_TRUE(std::isinf(*parseNumber("-inf")));
  EXPECT_TRUE(std::isinf(*parseNumber("1e999")));
  EXPECT_FALSE(parseNumber(""));
  EXPECT_FALSE(parseNumber("1.5x"));
  EXPECT_FALSE(parseNumber("0x10"));
  EXPECT_FALSE(parseNumber("1,5"));
}

TEST(LineReaderTest, ParsesStampsExactly) {
  EXPECT_EQ(parseStampSeconds("32.9068")->ns, 32906800000);
  EXPECT_EQ(parseStampSeconds("1134863807.658747")->ns, 1134863807658747000);
  EXPECT_EQ(parseStampSeconds("1.13486e+09")->ns, 1134860000000000000);
  EXPECT_EQ(parseStampSeconds("1.13487E9")->ns, 1134870000000000000);
  EXPECT_EQ(parseStampSeconds("-2.5e-3")->ns, -2500000);
  EXPECT_EQ(parseStampSeconds("125e-2")->ns, 1250000000);
  EXPECT_EQ(parseStampSeconds(".5e1")->ns, 5000000000);
  EXPECT_EQ(parseStampSeconds("1.65576e-153")->ns, 0);
  EXPECT_EQ(parseStampSeconds("1.5e-9")->ns, 1);
  EXPECT_FALSE(parseStampSeconds("1e99"));
  EXPECT_FALSE(parseStampSeconds("e5"));
  EXPECT_FALSE(parseStampSeconds("1.2e"));
  EXPECT_FALSE(parseStampSeconds("1.2e+x"));
  EXPECT_FALSE(parseStampSeconds("1.2.3e4"));
  EXPECT_FALSE(parseStampSeconds("nan"));
  EXPECT_FALSE(parseStampSeconds("inf"));
  EXPECT_FALSE(parseStampSeconds(""));
}

}  // namespace
}  // namespace mrslam::drivers
