#pragma once
// Map files: PGM + YAML (map_server style), PNG pictures and OctoMap binary trees (.bt).
// Every loader checks what it reads and throws MapIoError("path: what is wrong").

#include <Eigen/Core>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/common/se2.hpp"

namespace mrslam {

class MapIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The map_server shade of an occupancy value: 205 for unknown (-1), else 255 - round(2.55 * v)
/// with the rounding half up, computed exactly in integers (2.55 * 50 is 127.49999… in double).
std::uint8_t occupancyToShade(std::int8_t value);

/// Writes `yaml_path` and, beside it, the image `<stem>.pgm` (binary P5, row 0 at the top) that
/// it names: image, resolution, origin [x, y, 0.0], negate 0, occupied_thresh 0.65,
/// free_thresh 0.196, mode scale; numbers with 17 significant digits so they load back
/// bit-identical. Pixels: 205 unknown, else 255 - round(2.55 * v), which keeps every value 0..100
/// distinct (and never 205 or 206) so the pair loads back equal.
void saveMapYaml(const GridMap& map, const std::string& yaml_path);
/// Loads a map_server YAML and the image it names, relative to the YAML's folder (P5/P2 PGM read
/// here; PNG and other images through OpenCV, colour as the mean of B, G, R, alpha ignored).
/// Required keys: image, resolution, origin [x, y, yaw] (yaw must be 0), negate (0/1),
/// occupied_thresh, free_thresh; mode is optional (default trinary). With negate 1 every pixel p
/// is read as 255 - p first. Modes:
///   trinary: occ = (255 - p) / 255; occ > occupied_thresh → 100, occ < free_thresh → 0, else -1.
///   scale:   the inverse of saveMapYaml: 205 → -1, else round((255 - p) / 2.55), exactly.
///   (map_server's
///            own scale mode maps the band between the thresholds to 1..98; ours restores the
///            exact values of our files.)
///   raw:     p in 0..100 is the value, 255 is -1, any other pixel is an error.
/// Unknown keys are ignored, as map_server does.
GridMap loadMapYaml(const std::string& yaml_path);

/// A trajectory drawn over a map picture, in the map's frame.
struct MapOverlay {
  std::vector<Eigen::Vector2d> trajectory_m;
  Eigen::Vector3i bgr{0, 0, 255};      ///< colour of the trajectory and cells (blue, green, red)
  std::vector<Eigen::Vector2i> cells;  ///< map cells (cx, cy) painted in that colour
};

/// Writes a picture of the map, one pixel per cell, y up (row 0 holds the largest y): free white,
/// occupied black, values between as grey occupancyToShade(v), unknown mid grey (128); each
/// overlay's trajectory as a one-pixel polyline in its colour. The format follows the extension
/// (OpenCV imwrite).
void saveMapPng(const GridMap& map, const std::string& png_path,
                const std::vector<MapOverlay>& overlays = {});
/// The same picture as PNG bytes (for the live viewer); MapIoError for an invalid or empty map.
std::vector<std::uint8_t> encodeMapPng(const GridMap& map,
                                       const std::vector<MapOverlay>& overlays = {});

/// Writes an OctoMap binary tree at the grid's resolution: one voxel layer at z in
/// [0, resolution), occupied where the cell is occupied (> 50), free where free (< 50); unknown
/// cells and 50 are left out. The grid origin must be a whole number of cells from the frame
/// origin (within 1e-6 cells: OctoMap's voxel lattice), else MapIoError.
void saveMapOctomap(const GridMap& map, const std::string& bt_path);
/// Loads a .bt written by saveMapOctomap back into a grid covering `geometry`:
/// occupied voxels → 100, free → 0, missing → -1 (queried at every cell centre, z = res / 2).
GridMap loadMapOctomap(const std::string& bt_path, const GridGeometry& geometry);

}  // namespace mrslam
