#pragma once
// The fusion agent's configuration (config/fusion*.yaml), validated on load.

#include <map>
#include <string>
#include <vector>

#include "mrslam/common/dds_settings.hpp"
#include "mrslam/common/se2.hpp"
#include "mrslam/fusion/map_composer.hpp"
#include "mrslam/fusion/merge_scheduler.hpp"
#include "mrslam/fusion/rendezvous.hpp"

namespace mrslam::fusion {

/// The live map viewer: a page on a local HTTP port.
struct ViewerSettings {
  bool enabled = false;            ///< serve the page
  std::string host = "127.0.0.1";  ///< address to listen on (0.0.0.0: every interface)
  int port = 8080;                 ///< TCP port; 0: any free port (logged)
};

struct FusionConfig {
  std::string fusion_id = "fusion";  ///< name of this fusion agent in logs and files
  std::string reference_robot;       ///< the global map's frame; empty: the first robot placed
  /// Known placements of robots' map origins in the reference frame (T_reference_robot).
  std::map<std::string, SE2> fixed_transforms;
  std::vector<std::string> expected_robots;  ///< robots the run waits for
  bool exit_when_final = false;   ///< exit once every expected robot has sent its final map
  double max_runtime_s = 0.0;     ///< give up after this long (exit code 2); 0: run until stopped
  double publish_period_s = 1.0;  ///< time between global map updates
  double write_period_s = 0.0;    ///< time between map file writes while running; 0: at exit only
  std::string output_folder = "out/fusion";  ///< where the map files go
  bool write_robot_maps = true;        ///< also write each robot's received map (robots/<id>.*)
  std::size_t max_cells = 16'000'000;  ///< larger grids from the network are refused
  std::vector<std::string> allowed_robots;  ///< robot ids accepted; empty: any
  ComposerSettings composer;
  std::string merge_method = "none";     ///< merger that finds the transforms; "none": config only
  MergeSchedulerSettings merge;          ///< when and how often pairs are merged
  double final_merge_timeout_s = 120.0;  ///< at the end, wait this long for the last merges
  MergeScheduler::MergerFactory make_merger;  ///< set when merge_method is not "none"
  DdsSettings dds;
  bool ros2_map = true;               ///< also publish the global map on ROS 2's rt/map
  std::string ros2_frame_id = "map";  ///< its frame (the reference robot's map frame)
  ViewerSettings viewer;
  RendezvousSettings rendezvous;  ///< checking the robots' rendezvous against the maps
};

/// Loads and validates a fusion config; throws ConfigError (`file:line: key: what is wrong`).
FusionConfig loadFusionConfig(const std::string& path);

}  // namespace mrslam::fusion
