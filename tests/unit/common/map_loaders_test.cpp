#include "mrslam/common/map_loaders.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "test_data.hpp"

namespace mrslam {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

std::string errorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const MapIoError& error) {
    return error.what();
  }
  return "no MapIoError";
}

std::string writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

constexpr std::int8_t kOcc = GridMap::kOccupied;
constexpr std::int8_t kFree = GridMap::kFree;
constexpr std::int8_t kUnk = GridMap::kUnknown;

// The file's first line is the top of the map: GridMap row height - 1.
TEST(MapLoadersTest, CarpinTextPutsTheFirstLineAtTheTop) {
  const auto folder = test::scratchFolder("carpin");
  const std::string path = writeFile(folder / "map.txt", "0 127 255 \n255 255 127 \n");
  const GridMap map = loadCarpinText(path, 0.1);
  ASSERT_EQ(map.geometry.width, 3);
  ASSERT_EQ(map.geometry.height, 2);
  EXPECT_EQ(map.geometry.resolution_m, 0.1);
  EXPECT_EQ(map.geometry.origin_m, Eigen::Vector2d::Zero());
  EXPECT_EQ(map.at(0, 1), kOcc);
  EXPECT_EQ(map.at(1, 1), kUnk);
  EXPECT_EQ(map.at(2, 1), kFree);
  EXPECT_EQ(map.at(0, 0), kFree);
  EXPECT_EQ(map.at(1, 0), kFree);
  EXPECT_EQ(map.at(2, 0), kUnk);
}

TEST(MapLoadersTest, CarpinTextAcceptsWindowsLineEndsAndTrailingBlankLines) {
  const auto folder = test::scratchFolder("crlf");
  const GridMap map = loadCarpinText(writeFile(folder / "map.txt", "0 255\r\n127 0\r\n\r\n\n"));
  ASSERT_EQ(map.geometry.width, 2);
  ASSERT_EQ(map.geometry.height, 2);
  EXPECT_EQ(map.geometry.resolution_m, kDefaultMapResolution);
  EXPECT_EQ(map.at(1, 1), kFree);
  EXPECT_EQ(map.at(0, 0), kUnk);
}

TEST(MapLoadersTest, BadCarpinFilesNameThePathAndTheLine) {
  const auto folder = test::scratchFolder("bad-carpin");
  const std::string value = writeFile(folder / "value.txt", "0 255\n127 42\n");
  EXPECT_THAT(errorOf([&] { loadCarpinText(value); }),
              AllOf(StartsWith(value + ": "), HasSubstr("line 2"), HasSubstr("42")));
  const std::string ragged = writeFile(folder / "ragged.txt", "0 255 0\n127 0\n");
  EXPECT_THAT(errorOf([&] { loadCarpinText(ragged); }),
              AllOf(StartsWith(ragged + ": "), HasSubstr("line 2")));
  const std::string word = writeFile(folder / "word.txt", "0 255\n127 x\n");
  EXPECT_THAT(errorOf([&] { loadCarpinText(word); }), StartsWith(word + ": line 2"));
  const std::string hole = writeFile(folder / "hole.txt", "0 255\n\n127 0\n");
  EXPECT_THAT(errorOf([&] { loadCarpinText(hole); }), StartsWith(hole + ": line 2"));
  const std::string empty = writeFile(folder / "empty.txt", " \n\n");
  EXPECT_THAT(errorOf([&] { loadCarpinText(empty); }), StartsWith(empty + ": "));
  const std::string missing = (folder / "missing.txt").string();
  EXPECT_THAT(errorOf([&] { loadCarpinText(missing); }), StartsWith(missing + ": "));
  EXPECT_THAT(errorOf([&] { loadCarpinText(value, 0.0); }), StartsWith(value + ": resolution"));
}

// map_server trinary thresholds: p <= 89 occupied, 90..205 unknown, p >= 206 free.
TEST(MapLoadersTest, PgmShadesReadAsMapServerTrinaryWithTheFirstRowAtTheTop) {
  const auto folder = test::scratchFolder("pgm");
  std::string data = "P5\n3 2\n255\n";
  for (const int pixel : {0, 89, 90, 205, 206, 254}) {
    data += static_cast<char>(static_cast<unsigned char>(pixel));
  }
  const GridMap map = loadMapImage(writeFile(folder / "map.pgm", data));
  ASSERT_EQ(map.geometry.width, 3);
  ASSERT_EQ(map.geometry.height, 2);
  EXPECT_EQ(map.at(0, 1), kOcc);
  EXPECT_EQ(map.at(1, 1), kOcc);
  EXPECT_EQ(map.at(2, 1), kUnk);
  EXPECT_EQ(map.at(0, 0), kUnk);
  EXPECT_EQ(map.at(1, 0), kFree);
  EXPECT_EQ(map.at(2, 0), kFree);
}

TEST(MapLoadersTest, ColourPngReadsAsTheMeanOfItsChannels) {
  const auto folder = test::scratchFolder("png");
  cv::Mat picture(2, 2, CV_8UC3, cv::Scalar(205, 205, 205));
  picture.at<cv::Vec3b>(0, 1) = cv::Vec3b(0, 30, 60);      // top right: dark
  picture.at<cv::Vec3b>(1, 0) = cv::Vec3b(250, 254, 240);  // bottom left: light
  const std::string path = (folder / "map.png").string();
  ASSERT_TRUE(cv::imwrite(path, picture));
  const GridMap map = loadMapFile(path, 0.2);
  EXPECT_EQ(map.geometry.resolution_m, 0.2);
  EXPECT_EQ(map.at(1, 1), kOcc);
  EXPECT_EQ(map.at(0, 0), kFree);
  EXPECT_EQ(map.at(0, 1), kUnk);
  EXPECT_EQ(map.at(1, 0), kUnk);
}

TEST(MapLoadersTest, BadPicturesNameThePath) {
  const auto folder = test::scratchFolder("bad-image");
  const std::string junk = writeFile(folder / "junk.png", "not a picture");
  EXPECT_THAT(errorOf([&] { loadMapImage(junk); }), StartsWith(junk + ": cannot read image"));
  const std::string deep = (folder / "deep.png").string();
  ASSERT_TRUE(cv::imwrite(deep, cv::Mat(2, 2, CV_16UC1, cv::Scalar(1000))));
  EXPECT_THAT(errorOf([&] { loadMapImage(deep); }), StartsWith(deep + ": unsupported"));
  const std::string missing = (folder / "missing.pgm").string();
  EXPECT_THAT(errorOf([&] { loadMapFile(missing); }), StartsWith(missing + ": "));
}

TEST(MapLoadersTest, LoadMapFileChoosesTheReaderByExtension) {
  const auto folder = test::scratchFolder("dispatch");
  EXPECT_EQ(mapFileFormatOf("a/b.YAML"), MapFileFormat::kYaml);
  EXPECT_EQ(mapFileFormatOf("b.yml"), MapFileFormat::kYaml);
  EXPECT_EQ(mapFileFormatOf("b.Pgm"), MapFileFormat::kImage);
  EXPECT_EQ(mapFileFormatOf("b.txt"), MapFileFormat::kCarpinText);
  EXPECT_THAT(errorOf([&] { mapFileFormatOf("dir/map.bt"); }),
              AllOf(StartsWith("dir/map.bt: "), HasSubstr("unknown map format")));

  GridGeometry geometry;
  geometry.resolution_m = 0.25;
  geometry.width = 3;
  geometry.height = 2;
  geometry.origin_m = Eigen::Vector2d(1.5, -2.0);
  GridMap saved(geometry, kUnk);
  saved.at(0, 0) = kOcc;
  saved.at(2, 1) = kFree;
  const std::string yaml = (folder / "map.yaml").string();
  saveMapYaml(saved, yaml);
  EXPECT_EQ(loadMapFile(yaml, 0.05), saved);  // the YAML's resolution and origin win
  const GridMap text = loadMapFile(writeFile(folder / "map.txt", "0 255\n"), 0.5);
  EXPECT_EQ(text.geometry.resolution_m, 0.5);
  EXPECT_EQ(text.at(0, 0), kOcc);
}

struct SharedMapSize {
  const char* file;
  int width;
  int height;
};

TEST(MapLoadersTest, SharedMapsLoadWithTheirDocumentedSizes) {
  for (const SharedMapSize& expected :
       std::vector<SharedMapSize>{{"maps/carpin-robot0_cast.txt", 450, 300},
                                  {"maps/carpin-robot1_cast.txt", 450, 300},
                                  {"maps/carpin-robot2_cast.txt", 450, 300},
                                  {"maps/carpin-robot3_cast.txt", 450, 300},
                                  {"maps/carpin-LongRun6.txt", 900, 900},
                                  {"maps/carpin-LongRun7.txt", 900, 900},
                                  {"maps/carpin-intel.txt", 800, 800},
                                  {"maps/freiburg-intel.pgm", 888, 848},
                                  {"maps/freiburg-aces.pgm", 1129, 1134}}) {
    MRSLAM_REQUIRE_SHARED_DATA(expected.file);
    const GridMap map = loadMapFile(test::sharedDataPath(expected.file));
    EXPECT_EQ(map.geometry.width, expected.width) << expected.file;
    EXPECT_EQ(map.geometry.height, expected.height) << expected.file;
    EXPECT_TRUE(map.isValid()) << expected.file;
    const auto occupied = std::count(map.cells.begin(), map.cells.end(), kOcc);
    const auto free = std::count(map.cells.begin(), map.cells.end(), kFree);
    EXPECT_GT(occupied, 1000) << expected.file;
    EXPECT_GT(free, occupied) << expected.file;
  }
}

// The shared PGM through our picture reader equals map_server's reading of it (trinary YAML).
TEST(MapLoadersTest, SharedPgmReadsAsMapServerWouldReadIt) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  const auto folder = test::scratchFolder("map-server");
  const std::string yaml = writeFile(folder / "intel.yaml",
                                     "image: " + test::sharedDataPath("maps/freiburg-intel.pgm") +
                                         "\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
                                         "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  EXPECT_EQ(loadMapFile(test::sharedDataPath("maps/freiburg-intel.pgm")), loadMapYaml(yaml));
}

}  // namespace
}  // namespace mrslam
