#pragma once
// Loading any map file the tools meet: map_server YAML, bare grey images (PGM, PNG, ...) and the
// ASCII grids of Carpin's map-merging data sets. Every error is a MapIoError("path: what").
//
// Orientation: in every format the first row of the file is the TOP of the map (largest y), as in
// a picture; it becomes GridMap row height - 1. Column 0 is the left edge (smallest x). Checked on
// the shared maps: carpin-intel.txt read this way is freiburg-intel.pgm turned by ~15°, not its
// mirror image.

#include <string>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/common/map_io.hpp"

namespace mrslam {

/// The usual cell size of the shared maps, which record none (metres per cell).
constexpr double kDefaultMapResolution = 0.05;

enum class MapFileFormat {
  kYaml,        ///< .yaml / .yml: map_server description (resolution and origin from the file)
  kImage,       ///< .pgm / .png / .bmp / .jpg / .jpeg / .tif / .tiff: a bare grey picture
  kCarpinText,  ///< .txt: rows of integers, 0 occupied, 127 unknown, 255 free
};

/// The format of a map file by its extension (case-insensitive); MapIoError for any other.
MapFileFormat mapFileFormatOf(const std::string& path);

/// A bare picture read as map_server's trinary mode with its default thresholds: with
/// occ = (255 - p) / 255 per pixel p, occ > 0.65 (p <= 89, dark) is occupied (100),
/// occ < 0.196 (p >= 206, light) is free (0), the grey between (90..205) is unknown (-1); so the
/// map_server shades 0 / 205 / 254 read as occupied / unknown / free. Colour pixels are the mean
/// of B, G, R; alpha is ignored; only 8-bit pictures. Origin (0, 0).
GridMap loadMapImage(const std::string& path, double resolution_m = kDefaultMapResolution);

/// A Carpin grid: one text line per map row (first line at the top), each row the same number of
/// whitespace-separated integers, 0 occupied, 127 unknown, 255 free; any other value, a ragged
/// row or an empty file is an error naming the line. Origin (0, 0).
GridMap loadCarpinText(const std::string& path, double resolution_m = kDefaultMapResolution);

/// Any of the above by extension. A YAML file carries its own resolution (`resolution_m` is
/// ignored for it); the others get `resolution_m`, which must be > 0.
GridMap loadMapFile(const std::string& path, double resolution_m = kDefaultMapResolution);

}  // namespace mrslam
