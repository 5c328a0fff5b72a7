#include "mrslam/fusion/fusion_config.hpp"

#include <algorithm>

#include "mrslam/fusion/merge/merger_registry.hpp"

namespace mrslam::fusion {

namespace {

std::vector<std::string> readIdList(const Config& config, const std::string& key) {
  std::vector<std::string> ids;
  for (const Config& item : config.sectionList(key)) {
    const std::string id = item.requireString("id");
    if (!isValidRobotId(id)) {
      item.fail("id", "'" + id + "' is not a robot id (1-64 of A-Z a-z 0-9 _ -)");
    }
    ids.push_back(id);
  }
  return ids;
}

void readFixedTransforms(const Config& config, FusionConfig& fusion) {
  for (const Config& robot : config.sectionList("robots")) {
    const std::string id = robot.requireString("id");
    if (!isValidRobotId(id)) {
      robot.fail("id", "'" + id + "' is not a robot id (1-64 of A-Z a-z 0-9 _ -)");
    }
    if (fusion.fixed_transforms.count(id) != 0) {
      robot.fail("id", "robot '" + id + "' is listed twice");
    }
    const std::vector<double> pose = robot.getDoubles("T_reference_robot", {0.0, 0.0, 0.0}, 3);
    fusion.fixed_transforms[id] = SE2(pose[0], pose[1], pose[2]);
  }
}

// `method` names the merger; a section under its name (`seed:`, `feature:`) holds its settings.
// Every present method section is checked at load, so a bad merger setting stops the start.
void loadMergerChoice(const Config& section, FusionConfig& fusion) {
  std::vector<std::string> choices = mergerNames();
  choices.push_back("none");
  fusion.merge_method = section.getChoice("method", fusion.merge_method, choices);
  for (const std::string& name : mergerNames()) {
    if (section.has(name)) {
      makeMergerFrom(name, section);
    }
  }
  if (fusion.merge_method == "none") {
    fusion.make_merger = nullptr;
    return;
  }
  const std::string method = fusion.merge_method;
  fusion.make_merger = [method, section]() { return makeMergerFrom(method, section); };
}

void loadMerge(const Config& section, FusionConfig& fusion) {
  loadMergerChoice(section, fusion);
  MergeSchedulerSettings& merge = fusion.merge;
  merge.min_interval_s = section.getDouble("min_interval_s", merge.min_interval_s, {0.0, 3600.0});
  merge.material_change = section.getDouble("material_change", merge.material_change, {0.0, 10.0});
  merge.refine_accepted = section.getBool("refine_accepted", merge.refine_accepted);
  merge.threads = static_cast<int>(section.getInt("threads", merge.threads, {1, 64}));
  merge.confirmations =
      static_cast<int>(section.getInt("confirmations", merge.confirmations, {1, 100}));
  merge.confirm_distance_m =
      section.getDouble("confirm_distance_m", merge.confirm_distance_m, {0.0, 100.0});
  merge.confirm_angle_rad =
      section.getDouble("confirm_angle_deg", merge.confirm_angle_rad * 180.0 / M_PI, {0.0, 180.0}) *
      M_PI / 180.0;
  fusion.final_merge_timeout_s =
      section.getDouble("final_timeout_s", fusion.final_merge_timeout_s, {0.0, 3600.0});
}

}  // namespace

FusionConfig loadFusionConfig(const std::string& path) {
  const Config config = Config::loadFile(path);
  FusionConfig fusion;
  fusion.fusion_id = config.getString("fusion_id", fusion.fusion_id);
  fusion.reference_robot = config.getString("reference_robot", "");
  readFixedTransforms(config, fusion);
  if (!fusion.fixed_transforms.empty() && fusion.reference_robot.empty()) {
    config.fail("robots", "configured transforms need reference_robot (the frame they are in)");
  }
  fusion.expected_robots = readIdList(config, "expected_robots");
  fusion.exit_when_final = config.getBool("exit_when_final", fusion.exit_when_final);
  if (fusion.exit_when_final && fusion.expected_robots.empty()) {
    config.fail("exit_when_final", "needs expected_robots");
  }
  fusion.max_runtime_s = config.getDouble("max_runtime_s", fusion.max_runtime_s, {0.0, 1e7});
  fusion.publish_period_s =
      config.getDouble("publish_period_s", fusion.publish_period_s, {0.01, 3600.0});
  fusion.write_period_s = config.getDouble("write_period_s", fusion.write_period_s, {0.0, 1e6});
  const Config output = config.section("output");
  fusion.output_folder = output.getPath("folder", fusion.output_folder);
  fusion.write_robot_maps = output.getBool("write_robot_maps", fusion.write_robot_maps);
  const Config limits = config.section("limits");
  fusion.max_cells = static_cast<std::size_t>(
      limits.getInt("max_cells", static_cast<long long>(fusion.max_cells), {1.0, 1e9}));
  fusion.allowed_robots = readIdList(limits, "allowed_robots");
  const Config global_map = config.section("global_map");
  fusion.composer.resolution_m = global_map.getDouble("resolution_m", 0.0, {0.0, 10.0});
  loadMerge(config.section("merge"), fusion);
  fusion.dds = loadDdsSettings(config.section("dds"), kFusionParticipantProfile);
  const Config ros2 = config.section("ros2");
  fusion.ros2_map = ros2.getBool("map", fusion.ros2_map);
  fusion.ros2_frame_id = ros2.getString("frame_id", fusion.ros2_frame_id);
  if (fusion.ros2_frame_id.empty()) {
    ros2.fail("frame_id", "must not be empty");
  }
  const Config viewer = config.section("viewer");
  fusion.viewer.enabled = viewer.getBool("enabled", fusion.viewer.enabled);
  fusion.viewer.host = viewer.getString("host", fusion.viewer.host);
  if (fusion.viewer.host.empty()) {
    viewer.fail("host", "must not be empty");
  }
  fusion.viewer.port = static_cast<int>(viewer.getInt("port", fusion.viewer.port, {0.0, 65535.0}));
  const Config rendezvous = config.section("rendezvous");
  RendezvousSettings& meet = fusion.rendezvous;
  meet.max_time_gap_s = rendezvous.getDouble("max_time_gap_s", meet.max_time_gap_s, {0.0, 60.0});
  meet.min_verification_v =
      rendezvous.getDouble("min_verification_v", meet.min_verification_v, {0.0, 1.0});
  meet.min_overlap_cells = static_cast<std::size_t>(rendezvous.getInt(
      "min_overlap_cells", static_cast<long long>(meet.min_overlap_cells), {0.0, 1e9}));
  meet.min_structure_agreement =
      rendezvous.getDouble("min_structure_agreement", meet.min_structure_agreement, {0.0, 1.0});
  meet.rotation_step_rad =
      rendezvous.getDouble("rotation_step_rad", meet.rotation_step_rad, {1e-4, 0.1});
  meet.max_refinement_m =
      rendezvous.getDouble("max_refinement_m", meet.max_refinement_m, {0.0, 100.0});
  meet.max_refinement_rad =
      rendezvous.getDouble("max_refinement_rad", meet.max_refinement_rad, {0.0, M_PI});
  config.checkNoUnknownKeys();
  return fusion;
}

}  // namespace mrslam::fusion
