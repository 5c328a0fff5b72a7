// OctoMap binary trees (.bt): the grid as one layer of voxels on OctoMap's lattice.
#include <octomap/OcTree.h>

#include <cmath>
#include <filesystem>

#include "mrslam/common/map_io.hpp"

namespace mrslam {
namespace {

constexpr double kAlignmentTolerance = 1e-6;  ///< cells

/// The key of the voxel holding the centre of cell (cx, cy) in the layer z in [0, resolution).
bool cellKey(const octomap::OcTree& tree, const GridGeometry& g, int cx, int cy,
             octomap::OcTreeKey& key) {
  const Eigen::Vector2d centre = g.cellCenter(cx, cy);
  return tree.coordToKeyChecked(centre.x(), key[0]) && tree.coordToKeyChecked(centre.y(), key[1]) &&
         tree.coordToKeyChecked(0.5 * g.resolution_m, key[2]);
}

}  // namespace

void saveMapOctomap(const GridMap& map, const std::string& bt_path) {
  if (!map.isValid()) {
    throw MapIoError(bt_path + ": refusing to save an invalid map (size or values)");
  }
  const GridGeometry& g = map.geometry;
  const Eigen::Vector2d origin_cells = g.origin_m / g.resolution_m;
  if ((origin_cells - origin_cells.array().round().matrix()).cwiseAbs().maxCoeff() >
      kAlignmentTolerance) {
    throw MapIoError(bt_path + ": origin (" + std::to_string(g.origin_m.x()) + ", " +
                     std::to_string(g.origin_m.y()) +
                     ") is not a whole number of cells from the frame origin (OctoMap's lattice)");
  }
  octomap::OcTree tree(g.resolution_m);
  const float occupied = tree.getClampingThresMaxLog();
  const float free = tree.getClampingThresMinLog();
  for (int cy = 0; cy < g.height; ++cy) {
    for (int cx = 0; cx < g.width; ++cx) {
      const int v = map.at(cx, cy);
      if (v == GridMap::kUnknown || v == 50) {
        continue;  // unknown, or neither occupied nor free
      }
      octomap::OcTreeKey key;
      if (!cellKey(tree, g, cx, cy, key)) {
        throw MapIoError(bt_path + ": cell (" + std::to_string(cx) + ", " + std::to_string(cy) +
                         ") lies outside OctoMap's range");
      }
      tree.setNodeValue(key, v > 50 ? occupied : free, true);
    }
  }
  tree.updateInnerOccupancy();
  if (!tree.writeBinary(bt_path)) {
    throw MapIoError(bt_path + ": cannot write");
  }
}

GridMap loadMapOctomap(const std::string& bt_path, const GridGeometry& geometry) {
  if (!(geometry.resolution_m > 0.0) || geometry.width < 0 || geometry.height < 0 ||
      !geometry.origin_m.allFinite()) {
    throw MapIoError(bt_path + ": bad grid geometry to load into");
  }
  if (!std::filesystem::is_regular_file(bt_path)) {
    throw MapIoError(bt_path + ": cannot open (no such file)");
  }
  octomap::OcTree tree(geometry.resolution_m);
  if (!tree.readBinary(bt_path)) {
    throw MapIoError(bt_path + ": not an OctoMap binary tree (.bt)");
  }
  GridMap map(geometry, GridMap::kUnknown);
  for (int cy = 0; cy < geometry.height; ++cy) {
    for (int cx = 0; cx < geometry.width; ++cx) {
      octomap::OcTreeKey key;
      if (!cellKey(tree, geometry, cx, cy, key)) {
        continue;  // outside the tree's range: nothing known there
      }
      const octomap::OcTreeNode* node = tree.search(key);
      if (node != nullptr) {
        map.at(cx, cy) = tree.isNodeOccupied(node) ? GridMap::kOccupied : GridMap::kFree;
      }
    }
  }
  return map;
}

}  // namespace mrslam
