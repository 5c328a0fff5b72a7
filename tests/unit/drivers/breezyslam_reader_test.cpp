#include "mrslam/drivers/breezyslam_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "test_data.hpp"

namespace mrslam::drivers {
namespace {

using ::testing::HasSubstr;

constexpr std::size_t kBeams = 682;
constexpr double kDeg = M_PI / 180.0;

/// The fields of a well-formed line: 25 header fields, then 682 ranges of 100 + beam mm.
std::vector<std::string> goodFields(std::int64_t stamp_us, std::int64_t left, std::int64_t right) {
  std::vector<std::string> fields = {std::to_string(stamp_us),
                                     "14710",
                                     std::to_string(left),
                                     std::to_string(right),
                                     "0.785192",
                                     "0",
                                     "0",
                                     "170.1"};
  while (fields.size() < 25) {
    fields.push_back(fields.size() % 3 == 1 ? "255" : "0");
  }
  for (std::size_t beam = 0; beam < kBeams; ++beam) {
    fields.push_back(std::to_string(100 + beam));
  }
  return fields;
}

/// A line as the real logs write it: two spaces after the header, a space before the end.
std::string joined(const std::vector<std::string>& fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    line += fields[i];
    line += i == 24 ? "  " : " ";
  }
  return line + "\n";
}

std::string writeFile(const std::filesystem::path& path, const std::string& content) {
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

std::vector<Sample> readAll(SampleSource& source) {
  std::vector<Sample> samples;
  while (std::optional<Sample> sample = source.next()) {
    samples.push_back(std::move(*sample));
  }
  return samples;
}

BreezySlamSettings settingsFor(const std::string& path,
                               MalformedPolicy policy = MalformedPolicy::kSkip) {
  BreezySlamSettings settings;
  settings.path = path;
  settings.malformed_policy = policy;
  return settings;
}

struct LogContents {
  std::vector<WheelTicks> ticks;
  std::vector<LaserScan> scans;
};

/// Reads a whole log, checking that every line gave ticks then a scan with the same stamp.
LogContents readPairs(BreezySlamReader& reader) {
  LogContents contents;
  const std::vector<Sample> samples = readAll(reader);
  EXPECT_EQ(samples.size() % 2, 0u);
  for (std::size_t i = 0; i + 1 < samples.size(); i += 2) {
    EXPECT_TRUE(std::holds_alternative<WheelTicks>(samples[i])) << "sample " << i;
    EXPECT_TRUE(std::holds_alternative<LaserScan>(samples[i + 1])) << "sample " << i + 1;
    if (std::holds_alternative<WheelTicks>(samples[i]) &&
        std::holds_alternative<LaserScan>(samples[i + 1])) {
      contents.ticks.push_back(std::get<WheelTicks>(samples[i]));
      contents.scans.push_back(std::get<LaserScan>(samples[i + 1]));
      EXPECT_EQ(contents.ticks.back().stamp, contents.scans.back().stamp);
    }
  }
  return contents;
}

struct BeamClasses {
  std::size_t hits = 0;
  std::size_t no_return = 0;
  std::size_t invalid = 0;
};

BeamClasses classify(const LaserScan& scan) {
  BeamClasses classes;
  for (const float range : scan.ranges_m) {
    if (std::isnan(range)) {
      ++classes.invalid;
    } else if (std::isinf(range)) {
      ++classes.no_return;
    } else {
      ++classes.hits;
    }
  }
  return classes;
}

// ---------------------------------------------------------------------------------------------
// The real logs

struct RealLog {
  const char* file;
  std::size_t lines;
  std::int64_t first_stamp_us, first_left, first_right;
  std::int64_t last_stamp_us, last_left, last_right;
  BeamClasses first_scan;                                 // counted with awk on the first line
  std::vector<std::pair<std::size_t, float>> first_hits;  // beam (field - 26), metres
};

void PrintTo(const RealLog& log, std::ostream* out) {
  *out << log.file;
}

class BreezySlamReaderRealLogTest : public ::testing::TestWithParam<RealLog> {};

TEST_P(BreezySlamReaderRealLogTest, ReadsEveryLineWithTheValuesOfTheFile) {
  const RealLog& log = GetParam();
  MRSLAM_REQUIRE_SHARED_DATA(std::string("logs/") + log.file);
  BreezySlamReader reader(settingsFor(test::sharedDataPath(std::string("logs/") + log.file)));
  const LogContents contents = readPairs(reader);

  ASSERT_EQ(contents.scans.size(), log.lines);
  const SourceCounters counters = reader.counters();
  EXPECT_EQ(counters.samples, 2 * log.lines);
  EXPECT_EQ(counters.malformed_records, 0u);
  EXPECT_EQ(counters.out_of_order_stamps, 0u);

  EXPECT_EQ(contents.ticks.front().stamp.ns, log.first_stamp_us * 1000);
  EXPECT_EQ(contents.ticks.front().left, log.first_left);
  EXPECT_EQ(contents.ticks.front().right, log.first_right);
  EXPECT_EQ(contents.ticks.back().stamp.ns, log.last_stamp_us * 1000);
  EXPECT_EQ(contents.ticks.back().left, log.last_left);
  EXPECT_EQ(contents.ticks.back().right, log.last_right);

  const LaserScan& first = contents.scans.front();
  const BeamClasses classes = classify(first);
  EXPECT_EQ(classes.hits, log.first_scan.hits);
  EXPECT_EQ(classes.no_return, log.first_scan.no_return);
  EXPECT_EQ(classes.invalid, log.first_scan.invalid);
  for (const auto& [beam, metres] : log.first_hits) {
    EXPECT_FLOAT_EQ(first.ranges_m.at(beam), metres) << "beam " << beam;
  }
}

TEST_P(BreezySlamReaderRealLogTest, ScansHave682BeamsOver240DegreesInMetres) {
  const RealLog& log = GetParam();
  MRSLAM_REQUIRE_SHARED_DATA(std::string("logs/") + log.file);
  BreezySlamReader reader(settingsFor(test::sharedDataPath(std::string("logs/") + log.file)));
  const LogContents contents = readPairs(reader);
  ASSERT_FALSE(contents.scans.empty());

  float longest = 0.0f;
  for (std::size_t i = 0; i < contents.scans.size(); ++i) {
    const LaserScan& scan = contents.scans[i];
    ASSERT_EQ(scan.ranges_m.size(), kBeams);
    EXPECT_NEAR(scan.beamAngle(0), -120.0 * kDeg, 1e-12);
    EXPECT_NEAR(scan.beamAngle(kBeams - 1), 120.0 * kDeg, 1e-12);
    EXPECT_FALSE(scan.logged_pose.has_value());
    for (const float range : scan.ranges_m) {
      if (std::isfinite(range)) {
        EXPECT_GE(range, 0.02f);
        EXPECT_LE(range, 5.6f);
        longest = std::max(longest, range);
      }
    }
    if (i > 0) {
      EXPECT_GT(scan.stamp, contents.scans[i - 1].stamp);
      EXPECT_LT(secondsBetween(contents.scans[i - 1].stamp, scan.stamp), 0.5);
    }
  }
  // The rover sees walls a few metres away: metres, not millimetres or centimetres.
  EXPECT_GT(longest, 5.0f);
  EXPECT_GT(secondsBetween(contents.scans.front().stamp, contents.scans.back().stamp), 60.0);
}

INSTANTIATE_TEST_SUITE_P(
    Logs, BreezySlamReaderRealLogTest,
    ::testing::Values(RealLog{"breezyslam-exp1.dat",
                              756,
                              212387282,
                              29221,
                              25178,
                              287007421,
                              211786,
                              210289,
                              {214, 450, 18},
                              {{173, 2.229f}, {198, 5.240f}, {200, 2.150f}, {500, 0.856f}}},
                      RealLog{"breezyslam-exp2.dat",
                              641,
                              361431443,
                              234835,
                              231727,
                              424593575,
                              412369,
                              411147,
                              {238, 421, 23},
                              {{62, 0.559f}, {83, 4.530f}, {100, 1.551f}}}),
    [](const ::testing::TestParamInfo<RealLog>& param_info) {
      return std::string(param_info.param.file).substr(11, 4);  // "exp1", "exp2"
    });

/// End points of a scan in the robot frame (the laser sits 145 mm ahead of the centre); with
/// `mirrored` the ranges are taken in the other order.
std::vector<Eigen::Vector2d> endPoints(const LaserScan& scan, bool mirrored) {
  std::vector<Eigen::Vector2d> points;
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double range = scan.ranges_m[i];
    if (!std::isfinite(range) || range > 4.0) {
      continue;
    }
    const double angle = mirrored ? -scan.beamAngle(i) : scan.beamAngle(i);
    points.emplace_back(0.145 + range * std::cos(angle), range * std::sin(angle));
  }
  return points;
}

/// Median distance from the points of `later` (moved by T_earlier_later) to those of `earlier`.
double medianGap(const std::vector<Eigen::Vector2d>& earlier,
                 const std::vector<Eigen::Vector2d>& later, const SE2& T_earlier_later) {
  std::vector<double> gaps;
  for (std::size_t i = 0; i < later.size(); i += 2) {
    const Eigen::Vector2d p = T_earlier_later * later[i];
    double best = INFINITY;
    for (const Eigen::Vector2d& q : earlier) {
      best = std::min(best, (p - q).squaredNorm());
    }
    gaps.push_back(std::sqrt(best));
  }
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<long>(gaps.size() / 2), gaps.end());
  return gaps.empty() ? INFINITY : gaps[gaps.size() / 2];
}

// The default beam order is the one under which two scans taken during a turn agree after the
// turn the encoders measured (left = field 3, right = field 4; wheel radius 77 mm, half axle
// 165 mm, counts * 180 / 2000 wheel degrees). The other order mirrors the scans, so the turn
// that would reconcile them has the opposite sign.
TEST_P(BreezySlamReaderRealLogTest, DefaultBeamOrderMakesScansAgreeDuringTurns) {
  const RealLog& log = GetParam();
  MRSLAM_REQUIRE_SHARED_DATA(std::string("logs/") + log.file);
  BreezySlamReader reader(settingsFor(test::sharedDataPath(std::string("logs/") + log.file)));
  const LogContents contents = readPairs(reader);
  const auto wheel_m = [](std::int64_t counts) {
    return static_cast<double>(counts) * 180.0 / 2000.0 * kDeg * 0.077;
  };
  int pairs = 0;
  int default_better = 0;
  for (std::size_t i = 0; i + 1 < contents.scans.size(); ++i) {
    const double left = wheel_m(contents.ticks[i + 1].left - contents.ticks[i].left);
    const double right = wheel_m(contents.ticks[i + 1].right - contents.ticks[i].right);
    const double turn = (right - left) / (2.0 * 0.165);
    const double ahead = 0.5 * (right + left);
    if (std::abs(turn) < 3.0 * kDeg) {
      continue;
    }
    const SE2 T_earlier_later(ahead * std::cos(0.5 * turn), ahead * std::sin(0.5 * turn), turn);
    const double as_read = medianGap(endPoints(contents.scans[i], false),
                                     endPoints(contents.scans[i + 1], false), T_earlier_later);
    const double mirrored = medianGap(endPoints(contents.scans[i], true),
                                      endPoints(contents.scans[i + 1], true), T_earlier_later);
    ++pairs;
    default_better += as_read < mirrored ? 1 : 0;
  }
  ASSERT_GE(pairs, 20);
  EXPECT_GE(default_better, pairs * 9 / 10) << default_better << " of " << pairs << " pairs";
}

// ---------------------------------------------------------------------------------------------
// Settings and conversions, on small files

TEST(BreezySlamReaderTest, ConvertsMillimetresAndErrorCodes) {
  const auto folder = test::scratchFolder("log");
  std::vector<std::string> fields = goodFields(1500000, -20, 35);
  const std::size_t first = 25;
  fields[first + 0] = "0";  // no return
  fields[first + 1] = "1";  // URG error codes are below 20 mm
  fields[first + 2] = "19";
  fields[first + 3] = "20";    // range_min
  fields[first + 4] = "5600";  // range_max
  fields[first + 5] = "5601";  // beyond range_max
  fields[first + 681] = "4321";
  BreezySlamReader reader(settingsFor(writeFile(folder / "a.dat", joined(fields))));
  const LogContents contents = readPairs(reader);
  ASSERT_EQ(contents.scans.size(), 1u);
  const WheelTicks& ticks = contents.ticks[0];
  EXPECT_EQ(ticks.stamp.ns, 1500000000);
  EXPECT_EQ(ticks.left, -20);  // cumulative counts go down when a wheel turns back
  EXPECT_EQ(ticks.right, 35);
  const LaserScan& scan = contents.scans[0];
  EXPECT_EQ(scan.ranges_m[0], LaserScan::kNoReturn);
  EXPECT_TRUE(std::isnan(scan.ranges_m[1]));
  EXPECT_TRUE(std::isnan(scan.ranges_m[2]));
  EXPECT_FLOAT_EQ(scan.ranges_m[3], 0.020f);
  EXPECT_FLOAT_EQ(scan.ranges_m[4], 5.600f);
  EXPECT_EQ(scan.ranges_m[5], LaserScan::kNoReturn);
  EXPECT_FLOAT_EQ(scan.ranges_m[6], 0.106f);
  EXPECT_FLOAT_EQ(scan.ranges_m[681], 4.321f);
  EXPECT_DOUBLE_EQ(scan.range_min_m, 0.02);
  EXPECT_DOUBLE_EQ(scan.range_max_m, 5.6);
  EXPECT_NEAR(scan.angle_increment_rad, 240.0 * kDeg / 681.0, 1e-15);
}

TEST(BreezySlamReaderTest, BeamOrderSettingReversesTheRanges) {
  const auto folder = test::scratchFolder("log");
  const std::string path = writeFile(folder / "a.dat", joined(goodFields(1000, 0, 0)));
  BreezySlamSettings reversed = settingsFor(path);
  reversed.beam_order = BeamOrder::kLastIsMostClockwise;
  BreezySlamReader first_clockwise(settingsFor(path));
  BreezySlamReader last_clockwise(reversed);
  const LaserScan a = readPairs(first_clockwise).scans.at(0);
  const LaserScan b = readPairs(last_clockwise).scans.at(0);
  EXPECT_FLOAT_EQ(a.ranges_m.front(), 0.100f);
  EXPECT_FLOAT_EQ(b.ranges_m.front(), 0.781f);
  std::vector<float> b_reversed(b.ranges_m.rbegin(), b.ranges_m.rend());
  EXPECT_EQ(a.ranges_m, b_reversed);
  EXPECT_DOUBLE_EQ(a.angle_min_rad, b.angle_min_rad);
}

TEST(BreezySlamReaderTest, OtherFieldOfViewAndBeamCount) {
  const auto folder = test::scratchFolder("log");
  std::vector<std::string> fields = goodFields(1000, 0, 0);
  fields.resize(25 + 5);
  BreezySlamSettings settings = settingsFor(writeFile(folder / "a.dat", joined(fields)));
  settings.beam_count = 5;
  settings.field_of_view_deg = 180.0;
  BreezySlamReader reader(settings);
  const LaserScan scan = readPairs(reader).scans.at(0);
  ASSERT_EQ(scan.ranges_m.size(), 5u);
  EXPECT_NEAR(scan.angle_min_rad, -M_PI / 2, 1e-15);
  EXPECT_NEAR(scan.angle_increment_rad, M_PI / 4, 1e-15);
}

TEST(BreezySlamReaderTest, ReadsGzipLikePlainTextAndPassesOverEmptyLines) {
  const auto folder = test::scratchFolder("log");
  const std::string content =
      joined(goodFields(1000, 1, 2)) + "\n   \n" + joined(goodFields(2000, 3, 4)) + "\r\n";
  const std::string plain = writeFile(folder / "a.dat", content);
  writeGzipFile((folder / "a.dat.gz").string(), content);
  BreezySlamReader plain_reader(settingsFor(plain));
  BreezySlamReader gzip_reader(settingsFor((folder / "a.dat.gz").string()));
  const LogContents a = readPairs(plain_reader);
  const LogContents b = readPairs(gzip_reader);
  ASSERT_EQ(a.scans.size(), 2u);
  ASSERT_EQ(b.scans.size(), 2u);
  EXPECT_EQ(b.ticks[1].left, 3);
  EXPECT_EQ(b.ticks[1].stamp.ns, 2000000);
  EXPECT_EQ(a.scans[1].ranges_m, b.scans[1].ranges_m);
  EXPECT_EQ(plain_reader.counters().malformed_records, 0u);
  EXPECT_EQ(gzip_reader.counters().malformed_records, 0u);
}

TEST(BreezySlamReaderTest, DescribesItselfAndRejectsBadSettingsAndMissingFiles) {
  const auto folder = test::scratchFolder("log");
  const std::string path = writeFile(folder / "a.dat", joined(goodFields(1000, 0, 0)));
  EXPECT_EQ(BreezySlamReader(settingsFor(path)).describe(), "breezyslam log " + path);

  const auto rejects = [&](const std::function<void(BreezySlamSettings&)>& change) {
    BreezySlamSettings settings = settingsFor(path);
    change(settings);
    EXPECT_THROW(BreezySlamReader{settings}, std::invalid_argument);
  };
  rejects([](BreezySlamSettings& s) { s.beam_count = 1; });
  rejects([](BreezySlamSettings& s) { s.header_field_count = 3; });
  rejects([](BreezySlamSettings& s) { s.field_of_view_deg = 0.0; });
  rejects([](BreezySlamSettings& s) { s.field_of_view_deg = 400.0; });
  rejects([](BreezySlamSettings& s) { s.range_min_m = -0.1; });
  rejects([](BreezySlamSettings& s) { s.range_max_m = 0.01; });

  const std::string missing = (folder / "missing.dat").string();
  try {
    BreezySlamReader reader(settingsFor(missing));
    FAIL() << "opened a missing file";
  } catch (const std::runtime_error& error) {
    EXPECT_THAT(error.what(), HasSubstr(missing + ": cannot open"));
  }
}

// ---------------------------------------------------------------------------------------------
// Malformed lines: each kind, under both policies

struct Corruption {
  const char* name;
  std::function<void(std::vector<std::string>&)> change;
  const char* kind;
  const char* message;
};

void PrintTo(const Corruption& corruption, std::ostream* out) {
  *out << corruption.name;
}

class BreezySlamReaderMalformedTest : public ::testing::TestWithParam<Corruption> {
 protected:
  /// Line 1 and line 3 are good, line 2 is corrupted.
  std::string writeLog() {
    std::vector<std::string> bad = goodFields(2000, 3, 4);
    GetParam().change(bad);
    const auto folder = test::scratchFolder("log");
    return writeFile(folder / "bad.dat",
                     joined(goodFields(1000, 1, 2)) + joined(bad) + joined(goodFields(3000, 5, 6)));
  }
};

TEST_P(BreezySlamReaderMalformedTest, SkipCountsTheLineAndReadsTheGoodOnes) {
  BreezySlamReader reader(settingsFor(writeLog(), MalformedPolicy::kSkip));
  const LogContents contents = readPairs(reader);
  ASSERT_EQ(contents.ticks.size(), 2u);
  EXPECT_EQ(contents.ticks[0].stamp.ns, 1000000);
  EXPECT_EQ(contents.ticks[1].stamp.ns, 3000000);
  EXPECT_EQ(contents.ticks[1].left, 5);
  const SourceCounters counters = reader.counters();
  EXPECT_EQ(counters.malformed_records, 1u);
  EXPECT_EQ(counters.samples, 4u);
  EXPECT_EQ(reader.malformedByKind(), (std::map<std::string, std::uint64_t>{{GetParam().kind, 1}}));
}

TEST_P(BreezySlamReaderMalformedTest, StopThrowsTheFileLineAndProblem) {
  const std::string path = writeLog();
  BreezySlamReader reader(settingsFor(path, MalformedPolicy::kStop));
  ASSERT_TRUE(reader.next().has_value());  // line 1: ticks
  ASSERT_TRUE(reader.next().has_value());  // line 1: scan
  try {
    reader.next();
    FAIL() << "no error for line 2";
  } catch (const LogFormatError& error) {
    EXPECT_EQ(std::string(error.what()), path + ":2: " + GetParam().message);
    EXPECT_EQ(error.path(), path);
    EXPECT_EQ(error.line(), 2u);
    EXPECT_EQ(error.problem(), GetParam().message);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Kinds, BreezySlamReaderMalformedTest,
    ::testing::Values(Corruption{"TooFewFields", [](auto& f) { f.resize(12); }, "field count",
                                 "expected 707 fields, found 12"},
                      Corruption{"TooManyFields", [](auto& f) { f.push_back("7"); }, "field count",
                                 "expected 707 fields, found 708"},
                      Corruption{"NonIntegerStamp", [](auto& f) { f[0] = "2000.5"; },
                                 "not a number", "field 1: '2000.5' is not an integer"},
                      Corruption{"NonNumericCount", [](auto& f) { f[3] = "4x"; }, "not a number",
                                 "field 4: '4x' is not an integer"},
                      Corruption{"NonNumericHeader", [](auto& f) { f[7] = "abc"; }, "not a number",
                                 "field 8: 'abc' is not a number"},
                      Corruption{"NanHeader", [](auto& f) { f[4] = "nan"; }, "not finite",
                                 "field 5: 'nan' is not finite"},
                      Corruption{"InfHeader", [](auto& f) { f[7] = "-inf"; }, "not finite",
                                 "field 8: '-inf' is not finite"},
                      Corruption{"NonNumericRange", [](auto& f) { f[29] = "1o5"; }, "not a number",
                                 "field 30: '1o5' is not an integer"},
                      Corruption{"NanRange", [](auto& f) { f[706] = "nan"; }, "not a number",
                                 "field 707: 'nan' is not an integer"},
                      Corruption{"NegativeRange", [](auto& f) { f[25] = "-5"; }, "negative",
                                 "field 26: range -5 mm is negative"},
                      Corruption{"NegativeStamp", [](auto& f) { f[0] = "-2000"; }, "negative",
                                 "field 1: time stamp -2000 us is negative"}),
    [](const ::testing::TestParamInfo<Corruption>& param_info) {
      return std::string(param_info.param.name);
    });

}  // namespace
}  // namespace mrslam::drivers
