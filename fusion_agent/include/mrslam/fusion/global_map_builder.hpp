#pragma once
// Places every robot in the reference frame and composes the global map; writes the results.

#include <optional>
#include <string>
#include <vector>

#include "mrslam/fusion/fusion_config.hpp"
#include "mrslam/fusion/robot_map_store.hpp"

namespace mrslam::fusion {

/// Where one robot's map origin lies in the reference frame, if known.
struct Placement {
  std::string robot_id;
  bool placed = false;
  SE2 T_reference_robot;
  std::optional<double> verification;  ///< V of the merge that placed it (none when configured)
  std::string source;                  ///< "reference", "config", or why it is not placed
};

struct GlobalMapResult {
  std::string reference_robot;
  Stamp stamp;  ///< the newest stamp of the maps it was built from
  GridMap map;
  std::vector<Placement> placements;  ///< one per received robot, in robot id order
};

/// Placements from the configured transforms, and the composed map of the placed robots.
GlobalMapResult buildGlobalMap(const std::vector<RobotMap>& maps, const FusionConfig& config);

/// Writes global_map.{pgm,yaml,png,bt}, transforms.json, robots.json (what was received from
/// each robot) and (if asked) robots/<id>.{pgm,yaml}
/// into `folder`. Throws MapIoError when a file cannot be written.
void writeFusionOutputs(const GlobalMapResult& result, const std::vector<RobotMap>& maps,
                        const std::string& folder, bool write_robot_maps);

}  // namespace mrslam::fusion
