#pragma once
// Places every robot in the reference frame and composes the global map; writes the results.

#include <optional>
#include <string>
#include <vector>

#include "mrslam/common/map_io.hpp"
#include "mrslam/fusion/fusion_config.hpp"
#include "mrslam/fusion/placement.hpp"
#include "mrslam/fusion/robot_map_store.hpp"

namespace mrslam::fusion {

struct GlobalMapResult {
  std::string reference_robot;
  Stamp stamp;  ///< the newest stamp of the maps it was built from
  GridMap map;
  std::vector<Placement> placements;  ///< one per received robot, in robot id order
};

/// The reference robot: the configured one, or else the first robot with a map.
std::string chooseReference(const std::vector<RobotMap>& maps, const FusionConfig& config);

/// The global map of the placed robots, in the reference robot's frame. `placements` holds one
/// entry per robot of `maps`, in the same order.
GlobalMapResult buildGlobalMap(const std::vector<RobotMap>& maps, const std::string& reference,
                               const std::vector<Placement>& placements,
                               const ComposerSettings& composer);

/// A distinct colour (blue, green, red) for the robot at `index` of the id-ordered robots.
Eigen::Vector3i robotColour(std::size_t index);

/// Each placed robot's occupied cells and trajectory in its colour, over `result.map`.
std::vector<MapOverlay> robotOverlays(const GlobalMapResult& result,
                                      const std::vector<RobotMap>& maps);

/// Writes global_map.{pgm,yaml,png,bt}, transforms.json, robots.json (what was received from
/// each robot) and (if asked) robots/<id>.{pgm,yaml}
/// into `folder`. Throws MapIoError when a file cannot be written.
void writeFusionOutputs(const GlobalMapResult& result, const std::vector<RobotMap>& maps,
                        const std::string& folder, bool write_robot_maps);

}  // namespace mrslam::fusion
