#pragma once
// Map files: PGM + YAML (map_server style), PNG pictures and OctoMap binary trees (.bt).
// Every loader checks what it reads and throws MapIoError("path: what is wrong").

#include <Eigen/Core>
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

/// Writes `<stem>.pgm` and `<stem>.yaml` (image, resolution, origin [x, y, yaw], negate,
/// occupied_thresh, free_thresh, mode: scale). Pixels: 205 unknown, else 255 - round(2.55 * v),
/// which keeps every value 0..100 distinct so the pair loads back equal.
void saveMapYaml(const GridMap& map, const std::string& yaml_path);
/// Loads a map_server YAML and the image it names (PGM or PNG; modes trinary, scale, raw).
GridMap loadMapYaml(const std::string& yaml_path);

/// A trajectory drawn over a map picture, in the map's frame.
struct MapOverlay {
  std::vector<Eigen::Vector2d> trajectory_m;
  Eigen::Vector3i bgr{0, 0, 255};  ///< colour of the trajectory (and of the cells, when tinting)
};

/// Writes a picture of the map (free white, occupied black, unknown grey, y up), with overlays.
void saveMapPng(const GridMap& map, const std::string& png_path,
                const std::vector<MapOverlay>& overlays = {});

/// Writes an OctoMap binary tree: one voxel layer at z in [0, resolution), occupied where the
/// cell is occupied (> 50), free where free (< 50); unknown cells are left out. The grid origin
/// must be a whole number of cells from the frame origin (OctoMap's voxel lattice).
void saveMapOctomap(const GridMap& map, const std::string& bt_path);
/// Loads a .bt written by saveMapOctomap back into a grid covering `geometry`:
/// occupied voxels → 100, free → 0, missing → -1.
GridMap loadMapOctomap(const std::string& bt_path, const GridGeometry& geometry);

}  // namespace mrslam
