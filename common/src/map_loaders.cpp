// Map files of every kind the tools read: map_server YAML, bare pictures, Carpin ASCII grids.
#include "mrslam/common/map_loaders.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <vector>

namespace mrslam {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw MapIoError(path + ": " + what);
}

void requireFile(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) {
    fail(path, "cannot open (no such file)");
  }
}

void requireResolution(const std::string& path, double resolution_m) {
  if (!(resolution_m > 0.0) || !std::isfinite(resolution_m)) {
    fail(path, "resolution must be > 0 (got " + std::to_string(resolution_m) + ")");
  }
}

std::string lowerExtension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

GridMap emptyMap(int width, int height, double resolution_m) {
  GridGeometry geometry;
  geometry.resolution_m = resolution_m;
  geometry.width = width;
  geometry.height = height;
  return GridMap(geometry, GridMap::kUnknown);
}

/// map_server trinary reading with occupied_thresh 0.65 and free_thresh 0.196.
std::int8_t trinaryValue(int pixel) {
  const double occ = (255.0 - pixel) / 255.0;
  if (occ > 0.65) {
    return GridMap::kOccupied;
  }
  return occ < 0.196 ? GridMap::kFree : GridMap::kUnknown;
}

/// Grey level of pixel `col` of an 8-bit row with `channels` channels (mean of B, G, R).
int greyAt(const std::uint8_t* row, int col, int channels) {
  const std::uint8_t* pixel = row + col * channels;
  return channels == 1 ? pixel[0] : (pixel[0] + pixel[1] + pixel[2] + 1) / 3;
}

std::string readWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    fail(path, "cannot open");
  }
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::int8_t carpinValue(long value, const std::string& path, int line, int column) {
  switch (value) {
    case 0:
      return GridMap::kOccupied;
    case 127:
      return GridMap::kUnknown;
    case 255:
      return GridMap::kFree;
    default:
      fail(path, "line " + std::to_string(line) + ", value " + std::to_string(column) + ": " +
                     std::to_string(value) + " is not 0, 127 or 255");
  }
}

/// The integers of one text line (without its end of line).
std::vector<std::int8_t> parseCarpinRow(const std::string& text, const std::string& path,
                                        int line) {
  std::vector<std::int8_t> row;
  std::size_t pos = 0;
  while (true) {
    while (pos < text.size() && std::isspace(static_cast<unsigned char>(text[pos])) != 0) {
      ++pos;
    }
    if (pos == text.size()) {
      return row;
    }
    const std::size_t begin = pos;
    while (pos < text.size() && std::isdigit(static_cast<unsigned char>(text[pos])) != 0 &&
           pos - begin < 4) {
      ++pos;
    }
    const bool separated =
        pos == text.size() || std::isspace(static_cast<unsigned char>(text[pos])) != 0;
    const int column = static_cast<int>(row.size()) + 1;
    if (pos == begin || !separated) {
      fail(path, "line " + std::to_string(line) + ", value " + std::to_string(column) +
                     ": not a small non-negative integer");
    }
    row.push_back(carpinValue(std::stol(text.substr(begin, pos - begin)), path, line, column));
  }
}

/// The non-blank lines of a Carpin file, parsed; blank lines are allowed only at the end.
std::vector<std::vector<std::int8_t>> parseCarpinRows(const std::string& data,
                                                      const std::string& path) {
  std::vector<std::vector<std::int8_t>> rows;
  std::size_t pos = 0;
  int line = 0;
  int first_blank_line = 0;
  while (pos < data.size()) {
    const std::size_t end = std::min(data.find('\n', pos), data.size());
    ++line;
    std::vector<std::int8_t> row = parseCarpinRow(data.substr(pos, end - pos), path, line);
    pos = end + 1;
    if (row.empty()) {
      first_blank_line = first_blank_line == 0 ? line : first_blank_line;
      continue;
    }
    if (first_blank_line != 0) {
      fail(path, "line " + std::to_string(first_blank_line) + ": empty row inside the grid");
    }
    if (!rows.empty() && row.size() != rows.front().size()) {
      fail(path, "line " + std::to_string(line) + ": " + std::to_string(row.size()) +
                     " values, the first row has " + std::to_string(rows.front().size()));
    }
    rows.push_back(std::move(row));
  }
  if (rows.empty()) {
    fail(path, "no grid rows (empty file)");
  }
  return rows;
}

}  // namespace

MapFileFormat mapFileFormatOf(const std::string& path) {
  const std::string extension = lowerExtension(path);
  if (extension == ".yaml" || extension == ".yml") {
    return MapFileFormat::kYaml;
  }
  if (extension == ".txt") {
    return MapFileFormat::kCarpinText;
  }
  for (const char* image : {".pgm", ".png", ".bmp", ".jpg", ".jpeg", ".tif", ".tiff"}) {
    if (extension == image) {
      return MapFileFormat::kImage;
    }
  }
  fail(path, "unknown map format '" + extension +
                 "' (expected .yaml, .yml, .pgm, .png, .bmp, .jpg, .tif or Carpin .txt)");
}

GridMap loadMapImage(const std::string& path, double resolution_m) {
  requireResolution(path, resolution_m);
  requireFile(path);
  cv::Mat image;
  try {
    image = cv::imread(path, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& error) {
    fail(path, std::string("cannot read image (") + error.what() + ")");
  }
  if (image.empty()) {
    fail(path, "cannot read image (not a picture OpenCV decodes)");
  }
  const int channels = image.channels();
  if (image.depth() != CV_8U || channels == 2 || channels > 4) {
    fail(path, "unsupported image type (8-bit grey, BGR or BGRA only)");
  }
  GridMap map = emptyMap(image.cols, image.rows, resolution_m);
  for (int row = 0; row < image.rows; ++row) {
    const std::uint8_t* pixels = image.ptr<std::uint8_t>(row);
    for (int col = 0; col < image.cols; ++col) {
      map.at(col, image.rows - 1 - row) = trinaryValue(greyAt(pixels, col, channels));
    }
  }
  return map;
}

GridMap loadCarpinText(const std::string& path, double resolution_m) {
  requireResolution(path, resolution_m);
  requireFile(path);
  const std::vector<std::vector<std::int8_t>> rows = parseCarpinRows(readWholeFile(path), path);
  const int height = static_cast<int>(rows.size());
  GridMap map = emptyMap(static_cast<int>(rows.front().size()), height, resolution_m);
  for (int row = 0; row < height; ++row) {
    const auto& values = rows[static_cast<std::size_t>(row)];
    std::copy(
        values.begin(), values.end(),
        map.cells.begin() + static_cast<std::ptrdiff_t>(map.geometry.index(0, height - 1 - row)));
  }
  return map;
}

GridMap loadMapFile(const std::string& path, double resolution_m) {
  switch (mapFileFormatOf(path)) {
    case MapFileFormat::kYaml:
      return loadMapYaml(path);
    case MapFileFormat::kImage:
      return loadMapImage(path, resolution_m);
    case MapFileFormat::kCarpinText:
      return loadCarpinText(path, resolution_m);
  }
  fail(path, "unknown map format");
}

}  // namespace mrslam
