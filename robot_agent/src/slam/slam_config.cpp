#include "mrslam/robot/slam/slam_config.hpp"

#include <cmath>

namespace mrslam::robot::slam {

namespace {

int readInt(const Config& section, const char* key, int value, Range range) {
  return static_cast<int>(section.getInt(key, value, range));
}

RangeDataSettings loadRange(const Config& s, RangeDataSettings r) {
  r.min_range_m = s.getDouble("min_range_m", r.min_range_m, {0.0, 100.0});
  r.max_range_m = s.getDouble("max_range_m", r.max_range_m, {0.1, 1000.0});
  r.missing_data_ray_length_m =
      s.getDouble("missing_data_ray_length_m", r.missing_data_ray_length_m, {0.0, 100.0});
  r.voxel_m = s.getDouble("voxel_m", r.voxel_m, {0.0, 1.0});
  r.match_voxel_m = s.getDouble("match_voxel_m", r.match_voxel_m, {0.001, 1.0});
  r.match_max_points = readInt(s, "match_max_points", r.match_max_points, {10, 100000});
  r.match_min_points = readInt(s, "match_min_points", r.match_min_points, {1, 100000});
  if (r.match_min_points > r.match_max_points) {
    s.fail("match_min_points", "must not exceed match_max_points");
  }
  if (r.min_range_m >= r.max_range_m) {
    s.fail("min_range_m", "must be below max_range_m");
  }
  return r;
}

SubmapSettings loadSubmaps(const Config& s, SubmapSettings m) {
  m.num_range_data = readInt(s, "num_range_data", m.num_range_data, {1, 100000});
  m.grid.resolution_m = s.getDouble("resolution_m", m.grid.resolution_m, {0.005, 1.0});
  m.grid.hit_probability = s.getDouble("hit_probability", m.grid.hit_probability, {0.5001, 0.999});
  m.grid.miss_probability =
      s.getDouble("miss_probability", m.grid.miss_probability, {0.001, 0.4999});
  return m;
}

CeresScanMatcherSettings loadMatcher(const Config& s, CeresScanMatcherSettings m) {
  m.occupied_space_weight =
      s.getDouble("occupied_space_weight", m.occupied_space_weight, {1e-6, 1e6});
  m.translation_weight = s.getDouble("translation_weight", m.translation_weight, {0.0, 1e6});
  m.rotation_weight = s.getDouble("rotation_weight", m.rotation_weight, {0.0, 1e6});
  m.max_iterations = readInt(s, "max_iterations", m.max_iterations, {1, 1000});
  m.covariance_scale = s.getDouble("covariance_scale", m.covariance_scale, {1e-12, 1e6});
  m.min_sigma_xy_m = s.getDouble("min_sigma_xy_m", m.min_sigma_xy_m, {0.0, 10.0});
  m.min_sigma_theta_rad = s.getDouble("min_sigma_theta_rad", m.min_sigma_theta_rad, {0.0, 10.0});
  return m;
}

void loadCorrelative(const Config& s, SlamSettings& settings) {
  CorrelativeMatcherSettings& c = settings.correlative;
  c.linear_search_window_m = s.getDouble("linear_window_m", c.linear_search_window_m, {0.0, 10.0});
  c.angular_search_window_rad =
      s.getDouble("angular_window_rad", c.angular_search_window_rad, {0.0, M_PI});
  settings.correlative_sigma_xy_m =
      s.getDouble("sigma_xy_m", settings.correlative_sigma_xy_m, {0.0, 100.0});
  settings.correlative_sigma_theta_rad =
      s.getDouble("sigma_theta_rad", settings.correlative_sigma_theta_rad, {0.0, 10.0});
}

MotionFilterSettings loadMotionFilter(const Config& s, MotionFilterSettings f) {
  f.max_distance_m = s.getDouble("max_distance_m", f.max_distance_m, {0.0, 100.0});
  f.max_angle_rad = s.getDouble("max_angle_rad", f.max_angle_rad, {0.0, M_PI});
  f.max_time_s = s.getDouble("max_time_s", f.max_time_s, {0.0, 3600.0});
  return f;
}

PoseGraphSettings loadPoseGraph(const Config& s, PoseGraphSettings g) {
  g.local_sigma_m = s.getDouble("local_sigma_m", g.local_sigma_m, {1e-6, 100.0});
  g.local_sigma_rad = s.getDouble("local_sigma_rad", g.local_sigma_rad, {1e-6, 10.0});
  g.intra_sigma_m = s.getDouble("intra_sigma_m", g.intra_sigma_m, {1e-6, 100.0});
  g.intra_sigma_rad = s.getDouble("intra_sigma_rad", g.intra_sigma_rad, {1e-6, 10.0});
  g.closure_sigma_m = s.getDouble("closure_sigma_m", g.closure_sigma_m, {1e-6, 100.0});
  g.closure_sigma_rad = s.getDouble("closure_sigma_rad", g.closure_sigma_rad, {1e-6, 10.0});
  g.closure_huber_scale = s.getDouble("closure_huber_scale", g.closure_huber_scale, {1e-3, 1e6});
  g.max_closure_error_m = s.getDouble("max_closure_error_m", g.max_closure_error_m, {0.0, 100.0});
  g.max_closure_error_rad =
      s.getDouble("max_closure_error_rad", g.max_closure_error_rad, {0.0, M_PI});
  g.max_iterations = readInt(s, "max_iterations", g.max_iterations, {1, 10000});
  return g;
}

LoopClosureSettings loadLoopClosure(const Config& s, LoopClosureSettings l) {
  l.enabled = s.getBool("enabled", l.enabled);
  l.sampling_ratio = s.getDouble("sampling_ratio", l.sampling_ratio, {0.0, 1.0});
  l.max_constraint_distance_m =
      s.getDouble("max_constraint_distance_m", l.max_constraint_distance_m, {0.0, 1000.0});
  l.min_score = s.getDouble("min_score", l.min_score, {0.0, 1.0});
  l.min_window_m = s.getDouble("min_window_m", l.min_window_m, {0.0, 100.0});
  l.min_window_rad = s.getDouble("min_window_rad", l.min_window_rad, {0.0, M_PI});
  l.window_growth_per_m = s.getDouble("window_growth_per_m", l.window_growth_per_m, {0.0, 10.0});
  l.window_growth_rad_per_m =
      s.getDouble("window_growth_rad_per_m", l.window_growth_rad_per_m, {0.0, 10.0});
  l.max_range_m = s.getDouble("max_range_m", l.max_range_m, {0.1, 1000.0});
  l.search.linear_search_window_m =
      s.getDouble("max_window_m", l.search.linear_search_window_m, {0.0, 100.0});
  l.search.angular_search_window_rad =
      s.getDouble("max_window_rad", l.search.angular_search_window_rad, {0.0, M_PI});
  l.search.branch_and_bound_depth =
      readInt(s, "branch_and_bound_depth", l.search.branch_and_bound_depth, {1, 12});
  if (l.min_window_m > l.search.linear_search_window_m) {
    s.fail("min_window_m", "must not exceed max_window_m");
  }
  if (l.min_window_rad > l.search.angular_search_window_rad) {
    s.fail("min_window_rad", "must not exceed max_window_rad");
  }
  return l;
}

OdometryNoise loadFrontEndOdometry(const Config& s, OdometryNoise n) {
  n.translation_per_m = s.getDouble("translation_per_m", n.translation_per_m, {0.0, 10.0});
  n.rotation_per_rad = s.getDouble("rotation_per_rad", n.rotation_per_rad, {0.0, 10.0});
  n.rotation_per_m = s.getDouble("rotation_per_m", n.rotation_per_m, {0.0, 10.0});
  return n;
}

}  // namespace

SlamSettings loadSlamSettings(const Config& section, SlamSettings settings) {
  settings.odometry = loadFrontEndOdometry(section.section("odometry_noise"), settings.odometry);
  settings.range_data = loadRange(section.section("range"), settings.range_data);
  settings.submaps = loadSubmaps(section.section("submaps"), settings.submaps);
  settings.local_matching = loadMatcher(section.section("local_matching"), settings.local_matching);
  loadCorrelative(section.section("correlative"), settings);
  settings.gate_matches = section.getBool("gate_matches", settings.gate_matches);
  settings.motion_filter =
      loadMotionFilter(section.section("motion_filter"), settings.motion_filter);
  settings.pose_graph = loadPoseGraph(section.section("pose_graph"), settings.pose_graph);
  settings.loop_closure = loadLoopClosure(section.section("loop_closure"), settings.loop_closure);
  settings.optimise_every_n_nodes =
      readInt(section, "optimise_every_n_nodes", settings.optimise_every_n_nodes, {1, 1000000});
  settings.map_resolution_m =
      section.getDouble("map_resolution_m", settings.map_resolution_m, {0.005, 1.0});
  return settings;
}

}  // namespace mrslam::robot::slam
