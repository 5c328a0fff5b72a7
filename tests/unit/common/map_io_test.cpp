#include "mrslam/common/map_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <octomap/OcTree.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <set>

#include "test_data.hpp"

namespace mrslam {
namespace {

using ::testing::HasSubstr;

std::string errorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const MapIoError& error) {
    return error.what();
  }
  return "no MapIoError";
}

void writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// A binary PGM of `width` x `height` with the given pixels (row 0 at the top).
std::string pgm(int width, int height, const std::vector<int>& pixels) {
  std::string data =
      "P5\n# hand-written\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
  for (const int p : pixels) {
    data += static_cast<char>(static_cast<unsigned char>(p));
  }
  return data;
}

std::string mapYaml(const std::string& image, const std::string& mode, int negate = 0) {
  return "image: " + image +
         "\nresolution: 0.1\norigin: [-1.0, 2.0, 0.0]\nnegate: " + std::to_string(negate) +
         "\noccupied_thresh: 0.65\nfree_thresh: 0.196\n" +
         (mode.empty() ? std::string() : "mode: " + mode + "\n");
}

GridMap randomMap(int width, int height, std::mt19937& random) {
  GridGeometry geometry;
  geometry.resolution_m = 0.05;
  geometry.width = width;
  geometry.height = height;
  geometry.origin_m = Eigen::Vector2d(-12.345678901234567, 7.1000000000000014);
  GridMap map(geometry, GridMap::kUnknown);
  std::uniform_int_distribution<int> value(-1, 100);
  for (auto& cell : map.cells) {
    cell = static_cast<std::int8_t>(value(random));
  }
  return map;
}

TEST(MapYamlTest, RoundTripIsBitEqual) {
  const auto folder = test::scratchFolder("maps");
  std::mt19937 random(42);
  const GridMap map = randomMap(37, 23, random);
  const std::string yaml = (folder / "random.yaml").string();
  saveMapYaml(map, yaml);
  ASSERT_TRUE(std::filesystem::exists(folder / "random.pgm"));
  const GridMap loaded = loadMapYaml(yaml);
  EXPECT_EQ(loaded.geometry.resolution_m, map.geometry.resolution_m);
  EXPECT_EQ(loaded.geometry.origin_m, map.geometry.origin_m);
  EXPECT_EQ(loaded, map);

  const std::string text = readFile(yaml);
  EXPECT_THAT(text, HasSubstr("image: \"random.pgm\""));
  EXPECT_THAT(text, HasSubstr("mode: scale"));
  EXPECT_THAT(text, HasSubstr("negate: 0"));
  EXPECT_THAT(text, HasSubstr("occupied_thresh: 0.65"));
  EXPECT_THAT(text, HasSubstr("free_thresh: 0.196"));
  EXPECT_THAT(text, HasSubstr(", 0.0]"));
}

TEST(MapYamlTest, PgmIsBinaryWithTheTopRowFirst) {
  const auto folder = test::scratchFolder("maps");
  GridGeometry geometry;
  geometry.width = 3;
  geometry.height = 2;
  GridMap map(geometry, GridMap::kUnknown);
  map.at(0, 1) = 100;  // top left in the image
  map.at(2, 0) = 0;    // bottom right
  saveMapYaml(map, (folder / "small.yaml").string());
  const std::string data = readFile(folder / "small.pgm");
  ASSERT_EQ(data.substr(0, 2), "P5");
  const std::string pixels = data.substr(data.size() - 6);
  EXPECT_EQ(static_cast<unsigned char>(pixels[0]), 0);    // occupied: black
  EXPECT_EQ(static_cast<unsigned char>(pixels[1]), 205);  // unknown
  EXPECT_EQ(static_cast<unsigned char>(pixels[5]), 255);  // free: white
}

TEST(MapYamlTest, EveryValueHasItsOwnPixelAndNoneIs205Or206) {
  const auto folder = test::scratchFolder("maps");
  GridGeometry geometry;
  geometry.width = 102;
  geometry.height = 1;
  GridMap map(geometry, GridMap::kUnknown);
  for (int v = 0; v <= 100; ++v) {
    map.at(v, 0) = static_cast<std::int8_t>(v);
  }
  saveMapYaml(map, (folder / "all.yaml").string());
  const std::string data = readFile(folder / "all.pgm");
  const std::string pixels = data.substr(data.size() - 102);
  std::set<int> shades;
  for (int v = 0; v <= 100; ++v) {
    const int shade = static_cast<unsigned char>(pixels[static_cast<std::size_t>(v)]);
    EXPECT_NE(shade, 205) << "value " << v;
    EXPECT_NE(shade, 206) << "value " << v;
    shades.insert(shade);
  }
  EXPECT_EQ(shades.size(), 101u);
  EXPECT_EQ(static_cast<unsigned char>(pixels[101]), 205);
  EXPECT_EQ(loadMapYaml((folder / "all.yaml").string()), map);
}

TEST(MapYamlTest, LoadsHandWrittenTrinaryMap) {
  const auto folder = test::scratchFolder("maps");
  writeFile(folder / "hand.pgm", pgm(3, 2, {0, 254, 205, 255, 100, 230}));
  writeFile(folder / "hand.yaml", mapYaml("hand.pgm", "trinary"));
  const GridMap map = loadMapYaml((folder / "hand.yaml").string());
  EXPECT_EQ(map.geometry.width, 3);
  EXPECT_EQ(map.geometry.height, 2);
  EXPECT_EQ(map.geometry.resolution_m, 0.1);
  EXPECT_EQ(map.geometry.origin_m, Eigen::Vector2d(-1.0, 2.0));
  // Image row 0 is the top: grid row 1.
  EXPECT_EQ(map.at(0, 1), 100);
  EXPECT_EQ(map.at(1, 1), 0);
  EXPECT_EQ(map.at(2, 1), -1);  // 205: occ = 0.19608 lies between the thresholds
  EXPECT_EQ(map.at(0, 0), 0);
  EXPECT_EQ(map.at(1, 0), -1);  // occ = 0.608
  EXPECT_EQ(map.at(2, 0), 0);   // occ = 0.098

  // No mode key: trinary, as map_server.
  writeFile(folder / "default.yaml", mapYaml("hand.pgm", ""));
  EXPECT_EQ(loadMapYaml((folder / "default.yaml").string()), map);

  // negate 1 reads every pixel p as 255 - p.
  writeFile(folder / "negated.yaml", mapYaml("hand.pgm", "trinary", 1));
  const GridMap negated = loadMapYaml((folder / "negated.yaml").string());
  EXPECT_EQ(negated.at(0, 1), 0);
  EXPECT_EQ(negated.at(1, 1), 100);
  EXPECT_EQ(negated.at(0, 0), 100);
}

TEST(MapYamlTest, LoadsPlainPgmAndPngImages) {
  const auto folder = test::scratchFolder("maps");
  writeFile(folder / "plain.pgm", "P2\n# comment\n2 2\n# another\n15\n0 15\n 7 15\n");
  writeFile(folder / "plain.yaml", mapYaml("plain.pgm", "trinary"));
  const GridMap plain = loadMapYaml((folder / "plain.yaml").string());
  EXPECT_EQ(plain.cells, (std::vector<std::int8_t>{-1, 0, 100, 0}));  // 7/15 → 119: occ 0.53

  const cv::Mat grey = (cv::Mat_<std::uint8_t>(1, 3) << 0, 255, 205);
  ASSERT_TRUE(cv::imwrite((folder / "grey.png").string(), grey));
  writeFile(folder / "grey.yaml", mapYaml("grey.png", "trinary"));
  EXPECT_EQ(loadMapYaml((folder / "grey.yaml").string()).cells,
            (std::vector<std::int8_t>{100, 0, -1}));
}

TEST(MapYamlTest, RawModeReadsValuesAndRejectsOthers) {
  const auto folder = test::scratchFolder("maps");
  writeFile(folder / "raw.pgm", pgm(4, 1, {0, 37, 100, 255}));
  writeFile(folder / "raw.yaml", mapYaml("raw.pgm", "raw"));
  EXPECT_EQ(loadMapYaml((folder / "raw.yaml").string()).cells,
            (std::vector<std::int8_t>{0, 37, 100, -1}));
  writeFile(folder / "bad.pgm", pgm(2, 1, {0, 150}));
  writeFile(folder / "bad.yaml", mapYaml("bad.pgm", "raw"));
  EXPECT_THAT(errorOf([&] { loadMapYaml((folder / "bad.yaml").string()); }),
              HasSubstr((folder / "bad.pgm").string() + ": pixel 150"));
}

TEST(MapYamlTest, EveryErrorNamesThePath) {
  const auto folder = test::scratchFolder("maps");
  writeFile(folder / "good.pgm", pgm(2, 2, {0, 0, 255, 255}));
  const auto yamlError = [&](const std::string& name, const std::string& text) {
    const std::string path = (folder / name).string();
    writeFile(path, text);
    return errorOf([&] { loadMapYaml(path); });
  };
  const std::string missing = (folder / "absent.yaml").string();
  EXPECT_THAT(errorOf([&] { loadMapYaml(missing); }), HasSubstr(missing + ": cannot open"));

  EXPECT_THAT(yamlError("syntax.yaml", "image: [unclosed\n"),
              HasSubstr((folder / "syntax.yaml").string() + ": bad YAML"));
  EXPECT_THAT(yamlError("mode.yaml", mapYaml("good.pgm", "fancy")),
              HasSubstr((folder / "mode.yaml").string() + ": bad mode 'fancy'"));
  EXPECT_THAT(yamlError("res.yaml",
                        "image: good.pgm\nresolution: 0\norigin: [0, 0, 0]\n"
                        "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"),
              HasSubstr((folder / "res.yaml").string() + ": resolution"));
  EXPECT_THAT(yamlError("type.yaml",
                        "image: good.pgm\nresolution: fine\norigin: [0, 0, 0]\n"
                        "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"),
              HasSubstr((folder / "type.yaml").string() + ": 2: resolution: wrong type"));
  for (const std::string key :
       {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh"}) {
    std::string text = mapYaml("good.pgm", "trinary");
    const std::size_t line = text.find(key + ":");
    ASSERT_NE(line, std::string::npos);
    text.erase(line, text.find('\n', line) - line + 1);
    EXPECT_THAT(yamlError("no_" + key + ".yaml", text),
                HasSubstr((folder / ("no_" + key + ".yaml")).string() + ": missing key '" + key))
        << key;
  }

  const std::string absent_image = (folder / "nowhere.pgm").string();
  EXPECT_THAT(yamlError("image.yaml", mapYaml("nowhere.pgm", "trinary")),
              HasSubstr(absent_image + ": cannot open"));
  writeFile(folder / "header.pgm", "P7\n2 2\n255\n0000");
  EXPECT_THAT(yamlError("header.yaml", mapYaml("header.pgm", "trinary")),
              HasSubstr((folder / "header.pgm").string() + ": "));
  writeFile(folder / "header2.pgm", "P5\n2 x\n255\n0000");
  EXPECT_THAT(yamlError("header2.yaml", mapYaml("header2.pgm", "trinary")),
              HasSubstr((folder / "header2.pgm").string() + ": bad PGM header"));
  writeFile(folder / "short.pgm", "P5\n3 3\n255\n0123");
  EXPECT_THAT(yamlError("short.yaml", mapYaml("short.pgm", "trinary")),
              HasSubstr((folder / "short.pgm").string() + ": size mismatch"));
  writeFile(folder / "deep.pgm", "P5\n1 1\n65535\n00");
  EXPECT_THAT(yamlError("deep.yaml", mapYaml("deep.pgm", "trinary")),
              HasSubstr((folder / "deep.pgm").string() + ": unsupported PGM maxval"));
}

TEST(MapYamlTest, SaveErrorsNameThePath) {
  const auto folder = test::scratchFolder("maps");
  GridGeometry geometry;
  geometry.width = 2;
  geometry.height = 2;
  const std::string unwritable = (folder / "no/such/dir/map.yaml").string();
  EXPECT_THAT(errorOf([&] { saveMapYaml(GridMap(geometry, 0), unwritable); }),
              HasSubstr((folder / "no/such/dir/map.pgm").string() + ": cannot write"));
  GridMap invalid(geometry, 0);
  invalid.cells[1] = 101;
  const std::string path = (folder / "invalid.yaml").string();
  EXPECT_THAT(errorOf([&] { saveMapYaml(invalid, path); }), HasSubstr(path + ": refusing"));
  EXPECT_THAT(errorOf([&] { saveMapYaml(GridMap(), path); }), HasSubstr(path + ": refusing"));
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(MapPngTest, PictureHasSizeOrientationColoursAndTrajectory) {
  const auto folder = test::scratchFolder("maps");
  GridGeometry geometry;
  geometry.resolution_m = 0.1;
  geometry.width = 20;
  geometry.height = 10;
  geometry.origin_m = Eigen::Vector2d(-1.0, 3.0);
  GridMap map(geometry, GridMap::kFree);
  map.at(0, 9) = GridMap::kOccupied;  // top left of the picture
  map.at(19, 0) = GridMap::kUnknown;  // bottom right
  map.at(5, 0) = 50;
  MapOverlay overlay;
  overlay.bgr = Eigen::Vector3i(255, 0, 0);
  overlay.trajectory_m = {geometry.cellCenter(2, 6), geometry.cellCenter(12, 6)};
  const std::string path = (folder / "map.png").string();
  saveMapPng(map, path, {overlay});

  const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.cols, 20);
  EXPECT_EQ(image.rows, 10);
  EXPECT_EQ(image.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(image.at<cv::Vec3b>(9, 19), cv::Vec3b(128, 128, 128));
  EXPECT_EQ(image.at<cv::Vec3b>(9, 5), cv::Vec3b(127, 127, 127));
  EXPECT_EQ(image.at<cv::Vec3b>(9, 0), cv::Vec3b(255, 255, 255));
  for (int column = 2; column <= 12; ++column) {
    EXPECT_EQ(image.at<cv::Vec3b>(3, column), cv::Vec3b(255, 0, 0)) << column;  // row 9 - 6
  }
  EXPECT_EQ(image.at<cv::Vec3b>(3, 13), cv::Vec3b(255, 255, 255));
  EXPECT_EQ(image.at<cv::Vec3b>(2, 7), cv::Vec3b(255, 255, 255));

  EXPECT_THAT(errorOf([&] { saveMapPng(map, (folder / "no/such/dir/map.png").string()); }),
              HasSubstr((folder / "no/such/dir/map.png").string() + ": cannot write"));
}

GridGeometry octomapGeometry() {
  GridGeometry geometry;
  geometry.resolution_m = 0.05;
  geometry.width = 30;
  geometry.height = 20;
  geometry.origin_m = Eigen::Vector2d(-30 * 0.05, 41 * 0.05);
  return geometry;
}

TEST(MapOctomapTest, RoundTripKeepsEveryCellsClass) {
  const auto folder = test::scratchFolder("maps");
  GridMap map(octomapGeometry(), GridMap::kUnknown);
  std::mt19937 random(3);
  std::uniform_int_distribution<int> pick(0, 2);
  for (auto& cell : map.cells) {
    cell = std::array<std::int8_t, 3>{-1, 0, 100}[static_cast<std::size_t>(pick(random))];
  }
  const std::string path = (folder / "map.bt").string();
  saveMapOctomap(map, path);
  EXPECT_EQ(loadMapOctomap(path, map.geometry), map);

  // Values in between keep their class; 50 is left out.
  GridMap shades(octomapGeometry(), GridMap::kUnknown);
  shades.at(0, 0) = 30;
  shades.at(1, 0) = 70;
  shades.at(2, 0) = 50;
  saveMapOctomap(shades, path);
  const GridMap loaded = loadMapOctomap(path, shades.geometry);
  EXPECT_EQ(loaded.at(0, 0), GridMap::kFree);
  EXPECT_EQ(loaded.at(1, 0), GridMap::kOccupied);
  EXPECT_EQ(loaded.at(2, 0), GridMap::kUnknown);
  EXPECT_EQ(std::count(loaded.cells.begin(), loaded.cells.end(), GridMap::kUnknown),
            static_cast<long>(loaded.cells.size()) - 2);
}

TEST(MapOctomapTest, VoxelsSitOnTheCellCentresInOneLayer) {
  const auto folder = test::scratchFolder("maps");
  GridMap map(octomapGeometry(), GridMap::kUnknown);
  map.at(0, 0) = GridMap::kOccupied;
  map.at(29, 19) = GridMap::kFree;
  map.at(7, 3) = GridMap::kOccupied;
  const std::string path = (folder / "map.bt").string();
  saveMapOctomap(map, path);

  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary(path));
  EXPECT_DOUBLE_EQ(tree.getResolution(), 0.05);
  std::map<std::pair<int, int>, bool> voxels;  // cell -> occupied
  for (auto it = tree.begin_leafs(); it != tree.end_leafs(); ++it) {
    EXPECT_EQ(it.getDepth(), tree.getTreeDepth());
    EXPECT_NEAR(it.getZ(), 0.025, 1e-6);
    const double cx = (it.getX() - map.geometry.origin_m.x()) / 0.05 - 0.5;
    const double cy = (it.getY() - map.geometry.origin_m.y()) / 0.05 - 0.5;
    EXPECT_NEAR(cx, std::round(cx), 1e-3);
    EXPECT_NEAR(cy, std::round(cy), 1e-3);
    voxels[{static_cast<int>(std::lround(cx)), static_cast<int>(std::lround(cy))}] =
        tree.isNodeOccupied(*it);
  }
  EXPECT_EQ(voxels, (std::map<std::pair<int, int>, bool>{
                        {{0, 0}, true}, {{7, 3}, true}, {{29, 19}, false}}));
}

TEST(MapOctomapTest, MisalignedOriginAndMissingFileThrow) {
  const auto folder = test::scratchFolder("maps");
  GridGeometry geometry = octomapGeometry();
  geometry.origin_m.x() += 0.01;
  const std::string path = (folder / "misaligned.bt").string();
  EXPECT_THAT(errorOf([&] { saveMapOctomap(GridMap(geometry, 0), path); }),
              HasSubstr(path + ": origin"));
  EXPECT_FALSE(std::filesystem::exists(path));
  const std::string absent = (folder / "absent.bt").string();
  EXPECT_THAT(errorOf([&] { loadMapOctomap(absent, geometry); }),
              HasSubstr(absent + ": cannot open"));
  const std::string junk = (folder / "junk.bt").string();
  writeFile(junk, "not a tree\n");
  EXPECT_THAT(errorOf([&] { loadMapOctomap(junk, geometry); }), HasSubstr(junk + ": "));
}

TEST(MapYamlTest, LoadsFreiburgIntelMap) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  const auto folder = test::scratchFolder("maps");
  const std::string yaml = (folder / "intel.yaml").string();
  writeFile(yaml, "image: " + test::sharedDataPath("maps/freiburg-intel.pgm") +
                      "\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
                      "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n");
  const GridMap map = loadMapYaml(yaml);
  EXPECT_EQ(map.geometry.width, 888);  // the PGM header says "888 848": width first
  EXPECT_EQ(map.geometry.height, 848);
  std::map<int, long> counts;
  for (const std::int8_t value : map.cells) {
    ++counts[value];
  }
  EXPECT_GT(counts[GridMap::kOccupied], 0);
  EXPECT_GT(counts[GridMap::kFree], 0);
  EXPECT_GT(counts[GridMap::kUnknown], 0);
  EXPECT_EQ(counts[GridMap::kOccupied] + counts[GridMap::kFree] + counts[GridMap::kUnknown],
            888L * 848L);
}

}  // namespace
}  // namespace mrslam
