// map_server style maps: a YAML description and the image it names (PGM written here; PGM or any
// image OpenCV reads, loaded).
#include <yaml-cpp/yaml.h>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "mrslam/common/map_io.hpp"

namespace mrslam {
namespace {

constexpr int kUnknownPixel = 205;  ///< map_server's unknown shade

/// An 8-bit grey image, row 0 at the top.
struct GreyImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw MapIoError(path + ": " + what);
}

std::string readWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    fail(path, "cannot open");
  }
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Reads the next header number of a PGM, skipping whitespace and '#' comments.
long pgmHeaderNumber(const std::string& data, std::size_t& pos, const std::string& path) {
  while (pos < data.size()) {
    if (data[pos] == '#') {
      while (pos < data.size() && data[pos] != '\n') {
        ++pos;
      }
    } else if (std::isspace(static_cast<unsigned char>(data[pos])) != 0) {
      ++pos;
    } else {
      break;
    }
  }
  const std::size_t begin = pos;
  while (pos < data.size() && pos - begin < 10 &&
         std::isdigit(static_cast<unsigned char>(data[pos]))) {
    ++pos;
  }
  if (pos == begin || (pos < data.size() && std::isdigit(static_cast<unsigned char>(data[pos])))) {
    fail(path, "bad PGM header (expected a number at byte " + std::to_string(begin) + ")");
  }
  return std::stol(data.substr(begin, pos - begin));
}

/// A binary (P5) or plain (P2) PGM with maxval <= 255; values are scaled to 0..255.
GreyImage parsePgm(const std::string& data, const std::string& path) {
  if (data.size() < 2 || data[0] != 'P' || (data[1] != '5' && data[1] != '2')) {
    fail(path, "bad PGM header (no P5/P2 magic)");
  }
  const bool binary = data[1] == '5';
  std::size_t pos = 2;
  const long width = pgmHeaderNumber(data, pos, path);
  const long height = pgmHeaderNumber(data, pos, path);
  const long max_value = pgmHeaderNumber(data, pos, path);
  if (width <= 0 || height <= 0 || width > 1000000 || height > 1000000) {
    fail(path,
         "bad PGM header (size " + std::to_string(width) + "x" + std::to_string(height) + ")");
  }
  if (max_value < 1 || max_value > 255) {
    fail(path, "unsupported PGM maxval " + std::to_string(max_value) + " (1..255 only)");
  }
  GreyImage image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  image.pixels.resize(count);
  if (binary) {
    ++pos;  // the single whitespace byte after maxval
    const std::size_t available = pos <= data.size() ? data.size() - pos : 0;
    if (available != count) {
      fail(path, "size mismatch: header says " + std::to_string(width) + "x" +
                     std::to_string(height) + " (" + std::to_string(count) +
                     " bytes of pixels), file holds " + std::to_string(available));
    }
    std::copy(data.begin() + static_cast<std::ptrdiff_t>(pos), data.end(), image.pixels.begin());
  } else {
    std::istringstream in(data.substr(pos));
    for (std::size_t i = 0; i < count; ++i) {
      long value = -1;
      if (!(in >> value) || value < 0 || value > max_value) {
        fail(path, "size mismatch or bad value: pixel " + std::to_string(i) + " of " +
                       std::to_string(count));
      }
      image.pixels[i] = static_cast<std::uint8_t>(value);
    }
  }
  if (max_value != 255) {
    for (auto& pixel : image.pixels) {
      pixel =
          static_cast<std::uint8_t>(std::lround(pixel * 255.0 / static_cast<double>(max_value)));
    }
  }
  return image;
}

/// Any 8-bit image OpenCV reads; colour pixels become the mean of their B, G, R (alpha ignored).
GreyImage readImageWithOpenCv(const std::string& path) {
  const cv::Mat mat = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (mat.empty()) {
    fail(path, "cannot read image");
  }
  if (mat.depth() != CV_8U || mat.channels() == 2 || mat.channels() > 4) {
    fail(path, "unsupported image type (8-bit grey, BGR or BGRA only)");
  }
  GreyImage image;
  image.width = mat.cols;
  image.height = mat.rows;
  image.pixels.resize(static_cast<std::size_t>(mat.cols) * static_cast<std::size_t>(mat.rows));
  const int channels = mat.channels();
  for (int row = 0; row < mat.rows; ++row) {
    const std::uint8_t* in = mat.ptr<std::uint8_t>(row);
    for (int col = 0; col < mat.cols; ++col) {
      const std::uint8_t* pixel = in + col * channels;
      const int value = channels == 1 ? pixel[0] : (pixel[0] + pixel[1] + pixel[2] + 1) / 3;
      image.pixels[static_cast<std::size_t>(row) * static_cast<std::size_t>(mat.cols) +
                   static_cast<std::size_t>(col)] = static_cast<std::uint8_t>(value);
    }
  }
  return image;
}

GreyImage readGreyImage(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) {
    fail(path, "cannot open (no such file)");
  }
  const std::string data = readWholeFile(path);
  if (data.size() >= 2 && data[0] == 'P' && (data[1] == '5' || data[1] == '2')) {
    return parsePgm(data, path);
  }
  return readImageWithOpenCv(path);
}

YAML::Node requireKey(const YAML::Node& root, const char* key, const std::string& path) {
  const YAML::Node node = root[key];
  if (!node) {
    fail(path, std::string("missing key '") + key + "'");
  }
  return node;
}

template <typename T>
T readValue(const YAML::Node& root, const char* key, const std::string& path) {
  const YAML::Node node = requireKey(root, key, path);
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    fail(path, std::to_string(node.Mark().line + 1) + ": " + key + ": wrong type");
  }
}

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
    }
    out += c;
  }
  return out + "\"";
}

constexpr int kBadPixel = -2;  ///< a pixel that has no meaning in the map's mode

/// The value of every pixel shade under a mode (`negate` applied first); kBadPixel where the shade
/// has no meaning. trinary: occ = (255 - p) / 255 against the thresholds. scale (our own files):
/// 205 unknown, else round((255 - p) / 2.55). raw: p in 0..100 is the value, 255 unknown.
std::array<int, 256> pixelTable(const std::string& mode, bool negate, double occupied_thresh,
                                double free_thresh) {
  std::array<int, 256> table{};
  for (int shade = 0; shade < 256; ++shade) {
    const int p = negate ? 255 - shade : shade;
    int value = kBadPixel;
    if (mode == "trinary") {
      const double occ = (255.0 - p) / 255.0;
      value = occ > occupied_thresh ? GridMap::kOccupied
              : occ < free_thresh   ? GridMap::kFree
                                    : GridMap::kUnknown;
    } else if (mode == "scale") {
      value = p == kUnknownPixel ? GridMap::kUnknown
                                 : (200 * (255 - p) + 255) / 510;  // round(k / 2.55)
    } else if (p <= GridMap::kOccupied || p == 255) {
      value = p == 255 ? GridMap::kUnknown : p;
    }
    table[static_cast<std::size_t>(shade)] = value;
  }
  return table;
}

}  // namespace

std::uint8_t occupancyToShade(std::int8_t value) {
  if (value < 0) {
    return kUnknownPixel;
  }
  return static_cast<std::uint8_t>(255 - (255 * value + 50) / 100);  // 255 - round(2.55 * v)
}

void saveMapYaml(const GridMap& map, const std::string& yaml_path) {
  if (!map.isValid() || map.geometry.cellCount() == 0) {
    fail(yaml_path, "refusing to save an invalid or empty map");
  }
  std::filesystem::path image_path(yaml_path);
  image_path.replace_extension(".pgm");
  const GridGeometry& g = map.geometry;

  std::ofstream image(image_path, std::ios::binary);
  image << "P5\n# mrslam map\n" << g.width << ' ' << g.height << "\n255\n";
  std::vector<char> row(static_cast<std::size_t>(g.width));
  for (int cy = g.height - 1; cy >= 0; --cy) {  // image row 0 is the top (largest y)
    for (int cx = 0; cx < g.width; ++cx) {
      row[static_cast<std::size_t>(cx)] = static_cast<char>(occupancyToShade(map.at(cx, cy)));
    }
    image.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
  image.close();
  if (!image) {
    fail(image_path.string(), "cannot write");
  }

  char numbers[128];
  std::snprintf(numbers, sizeof numbers, "resolution: %.17g\norigin: [%.17g, %.17g, 0.0]\n",
                g.resolution_m, g.origin_m.x(), g.origin_m.y());
  std::ofstream yaml(yaml_path);
  yaml << "image: " << quoted(image_path.filename().string()) << '\n'
       << numbers << "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: scale\n";
  yaml.close();
  if (!yaml) {
    fail(yaml_path, "cannot write");
  }
}

GridMap loadMapYaml(const std::string& yaml_path) {
  if (!std::filesystem::is_regular_file(yaml_path)) {
    fail(yaml_path, "cannot open (no such file)");
  }
  YAML::Node root;
  try {
    root = YAML::LoadFile(yaml_path);
  } catch (const YAML::Exception& error) {
    fail(yaml_path, std::string("bad YAML: ") + error.what());
  }
  if (!root.IsMap()) {
    fail(yaml_path, "not a map_server YAML (expected a mapping)");
  }
  const auto image_name = readValue<std::string>(root, "image", yaml_path);
  const auto resolution = readValue<double>(root, "resolution", yaml_path);
  const auto origin = readValue<std::vector<double>>(root, "origin", yaml_path);
  const auto negate = readValue<int>(root, "negate", yaml_path);
  const auto occupied_thresh = readValue<double>(root, "occupied_thresh", yaml_path);
  const auto free_thresh = readValue<double>(root, "free_thresh", yaml_path);
  const std::string mode =
      root["mode"] ? readValue<std::string>(root, "mode", yaml_path) : std::string("trinary");
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    fail(yaml_path, "resolution must be > 0");
  }
  if (origin.size() != 3 || !std::isfinite(origin[0]) || !std::isfinite(origin[1])) {
    fail(yaml_path, "origin must be [x, y, yaw] with finite x, y");
  }
  if (origin[2] != 0.0) {
    fail(yaml_path, "origin yaw must be 0 (rotated maps are not supported)");
  }
  if (negate != 0 && negate != 1) {
    fail(yaml_path, "negate must be 0 or 1");
  }
  if (!(0.0 <= free_thresh && free_thresh <= occupied_thresh && occupied_thresh <= 1.0)) {
    fail(yaml_path, "thresholds must satisfy 0 <= free_thresh <= occupied_thresh <= 1");
  }
  if (mode != "trinary" && mode != "scale" && mode != "raw") {
    fail(yaml_path, "bad mode '" + mode + "' (trinary, scale or raw)");
  }

  std::filesystem::path image_path(image_name);
  if (image_path.is_relative()) {
    image_path = std::filesystem::path(yaml_path).parent_path() / image_path;
  }
  const GreyImage image = readGreyImage(image_path.string());

  GridGeometry geometry;
  geometry.resolution_m = resolution;
  geometry.width = image.width;
  geometry.height = image.height;
  geometry.origin_m = Eigen::Vector2d(origin[0], origin[1]);
  GridMap map(geometry, GridMap::kUnknown);
  const std::array<int, 256> table = pixelTable(mode, negate == 1, occupied_thresh, free_thresh);
  for (int row = 0; row < image.height; ++row) {
    const std::uint8_t* pixels =
        image.pixels.data() + static_cast<std::size_t>(row) * static_cast<std::size_t>(image.width);
    for (int col = 0; col < image.width; ++col) {
      const int value = table[pixels[col]];
      if (value == kBadPixel) {
        fail(image_path.string(), "pixel " + std::to_string(pixels[col]) + " at column " +
                                      std::to_string(col) + ", row " + std::to_string(row) +
                                      " has no meaning in raw mode (0..100 or 255 only)");
      }
      map.at(col, image.height - 1 - row) = static_cast<std::int8_t>(value);
    }
  }
  return map;
}

}  // namespace mrslam
