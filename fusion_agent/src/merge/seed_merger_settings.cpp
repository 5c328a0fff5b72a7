// loadSeedMergerSettings: the seed merger's config section, every key optional.

#include <cmath>

#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion {

namespace {

constexpr double kDegree = M_PI / 180.0;

int readInt(const Config& section, const std::string& key, int value, Range range) {
  return static_cast<int>(section.getInt(key, value, range));
}

void readEdgeAndSegmentSettings(const Config& section, SeedMergerSettings& settings) {
  EdgeSettings& edges = settings.edges;
  edges.occupied_threshold =
      readInt(section, "occupied_threshold", edges.occupied_threshold, {1, 100});
  settings.similarity.occupied_threshold = edges.occupied_threshold;
  edges.smoothing_sigma = section.getDouble("smoothing_sigma", edges.smoothing_sigma, {0.1, 10.0});
  edges.canny_low = section.getDouble("canny_low", edges.canny_low, {0.0, 1000.0});
  edges.canny_high = section.getDouble("canny_high", edges.canny_high, {0.0, 1000.0});
  if (edges.canny_low > edges.canny_high) {
    section.fail("canny_low", "must not exceed canny_high");
  }
  edges.edge_merge_distance_dt =
      readInt(section, "edge_merge_distance_dt", edges.edge_merge_distance_dt, {2, 50});
  SegmentSettings& segments = settings.segments;
  segments.turn_chord_k = readInt(section, "turn_chord_k", segments.turn_chord_k, {1, 20});
  segments.segment_points_n = readInt(section, "segment_points_n", segments.segment_points_n,
                                      {4.0 * segments.turn_chord_k + 6.0, 1000});
  segments.gap_jump_cells = readInt(section, "gap_jump_cells", segments.gap_jump_cells, {1, 5});
}

void readShapeSettings(const Config& section, SeedMergerSettings& settings) {
  SegmentVerificationSettings& verification = settings.verification;
  verification.distance_bins =
      readInt(section, "distance_bins", verification.distance_bins, {1, 100});
  verification.arc_bins = readInt(section, "arc_bins", verification.arc_bins, {2, 360});
  verification.histogram_spread_hd =
      section.getDouble("histogram_spread_hd", verification.histogram_spread_hd, {0.0, 1000.0});
  verification.max_turn_omega_c =
      kDegree * section.getDouble("max_turn_omega_c_deg", verification.max_turn_omega_c / kDegree,
                                  {1.0, 180.0});
  CorrelationSettings& correlation = settings.correlation;
  correlation.histogram_weight =
      section.getDouble("histogram_weight", correlation.histogram_weight, {0.0, 1.0});
  correlation.min_overlap_fraction =
      section.getDouble("min_overlap_fraction", correlation.min_overlap_fraction, {0.1, 1.0});
  RadonSettings& radon = settings.radon;
  radon.angle_step_rad =
      kDegree * section.getDouble("radon_step_deg", radon.angle_step_rad / kDegree, {0.05, 5.0});
  radon.rotation_window_rad =
      kDegree *
      section.getDouble("rotation_window_deg", radon.rotation_window_rad / kDegree, {0.5, 90.0});
  radon.profile_highpass_rad =
      kDegree *
      section.getDouble("profile_highpass_deg", radon.profile_highpass_rad / kDegree, {0.0, 45.0});
}

void readSearchSettings(const Config& section, SeedMergerSettings& settings) {
  SimilaritySettings& similarity = settings.similarity;
  similarity.free_threshold =
      readInt(section, "free_threshold", similarity.free_threshold, {0, 99});
  if (similarity.free_threshold >= similarity.occupied_threshold) {
    section.fail("free_threshold", "must be below occupied_threshold");
  }
  similarity.cell_certainty =
      section.getDouble("cell_certainty", similarity.cell_certainty, {0.51, 0.9999});
  settings.segment_trials =
      readInt(section, "segment_trials", settings.segment_trials, {1, 100000});
  settings.max_segments = readInt(section, "max_segments", settings.max_segments, {1, 10000});
  settings.correlated_pairs =
      readInt(section, "correlated_pairs", settings.correlated_pairs, {1, 10000000});
  settings.pose_trials = readInt(section, "pose_trials", settings.pose_trials, {1, 100000});
  settings.coarse_radius_cells =
      readInt(section, "coarse_radius_cells", settings.coarse_radius_cells, {0, 20});
  settings.coarse_samples =
      readInt(section, "coarse_samples", settings.coarse_samples, {10, 1000000});
  settings.refined_hypotheses =
      readInt(section, "refined_hypotheses", settings.refined_hypotheses, {1, 1000});
  settings.translation_window_delta =
      readInt(section, "translation_window_delta", settings.translation_window_delta, {0, 100});
  settings.search_occupied_samples =
      readInt(section, "search_occupied_samples", settings.search_occupied_samples, {10, 10000000});
  settings.search_free_samples =
      readInt(section, "search_free_samples", settings.search_free_samples, {10, 10000000});
  settings.rotation_polish_rad =
      kDegree *
      section.getDouble("rotation_polish_deg", settings.rotation_polish_rad / kDegree, {0.0, 10.0});
  settings.rotation_polish_step_rad =
      kDegree * section.getDouble("rotation_polish_step_deg",
                                  settings.rotation_polish_step_rad / kDegree, {0.01, 5.0});
}

void readAcceptanceSettings(const Config& section, SeedMergerSettings& settings) {
  settings.min_verification_v =
      section.getDouble("min_verification_v", settings.min_verification_v, {0.0, 1.0});
  settings.min_overlap_cells =
      section.getInt("min_overlap_cells", settings.min_overlap_cells, {0.0, 1e9});
  settings.small_overlap_cells =
      section.getInt("small_overlap_cells", settings.small_overlap_cells, {0.0, 1e9});
  settings.small_overlap_structure =
      section.getDouble("small_overlap_structure", settings.small_overlap_structure, {0.0, 1.0});
  settings.clean_small_overlap_structure = section.getDouble(
      "clean_small_overlap_structure", settings.clean_small_overlap_structure, {0.0, 1.0});
  settings.clean_small_overlap_min_v = section.getDouble(
      "clean_small_overlap_min_v", settings.clean_small_overlap_min_v, {0.0, 2.0});
  settings.min_structure_agreement =
      section.getDouble("min_structure_agreement", settings.min_structure_agreement, {0.0, 1.0});
  settings.min_structure_off_frontier = section.getDouble(
      "min_structure_off_frontier", settings.min_structure_off_frontier, {0.0, 2.0});
  settings.min_v_off_frontier =
      section.getDouble("min_v_off_frontier", settings.min_v_off_frontier, {0.0, 2.0});
  settings.entropy_agreement_cells =
      section.getDouble("entropy_agreement_cells", settings.entropy_agreement_cells, {0.0, 1000.0});
  settings.max_translation_ambiguity = section.getDouble(
      "max_translation_ambiguity", settings.max_translation_ambiguity, {0.0, 1.0});
  settings.max_rival_share =
      section.getDouble("max_rival_share", settings.max_rival_share, {0.0, 1.0});
  settings.cleaner_rival_rate =
      section.getDouble("cleaner_rival_rate", settings.cleaner_rival_rate, {0.0, 1.0});
  settings.dirtier_rival_structure =
      section.getDouble("dirtier_rival_structure", settings.dirtier_rival_structure, {0.0, 1.0});
  settings.dirtier_rival_rate =
      section.getDouble("dirtier_rival_rate", settings.dirtier_rival_rate, {1.0, 100.0});
  settings.judged_candidates =
      static_cast<int>(section.getInt("judged_candidates", settings.judged_candidates, {1, 100}));
  settings.late_rank = readInt(section, "late_rank", settings.late_rank, {0, 100});
  settings.late_rank_min_verification = section.getDouble(
      "late_rank_min_verification", settings.late_rank_min_verification, {0.0, 1.0});
  settings.wall_anchor = section.getBool("wall_anchor", settings.wall_anchor);
  settings.wall_ranking = section.getBool("wall_ranking", settings.wall_ranking);
  settings.refined_rivals = readInt(section, "refined_rivals", settings.refined_rivals, {0, 10});
  settings.rank_by_overlap = section.getBool("rank_by_overlap", settings.rank_by_overlap);
  settings.decisive_wall_ambiguity =
      section.getDouble("decisive_wall_ambiguity", settings.decisive_wall_ambiguity, {0.0, 1.0});
  settings.max_open_floor_ambiguity =
      section.getDouble("max_open_floor_ambiguity", settings.max_open_floor_ambiguity, {0.0, 1.0});
  settings.walls_over_floor_min_v =
      section.getDouble("walls_over_floor_min_v", settings.walls_over_floor_min_v, {0.0, 2.0});
  settings.decisive_wall_margin =
      section.getInt("decisive_wall_margin", settings.decisive_wall_margin, {0, 1000000});
  settings.clean_walls_over_floor_min_v = section.getDouble(
      "clean_walls_over_floor_min_v", settings.clean_walls_over_floor_min_v, {0.0, 2.0});
  settings.clean_decisive_wall_margin = section.getInt(
      "clean_decisive_wall_margin", settings.clean_decisive_wall_margin, {0, 1000000});
  settings.wall_icp_iterations = static_cast<int>(
      section.getInt("wall_icp_iterations", settings.wall_icp_iterations, {0, 1000}));
  settings.wall_icp_samples = static_cast<int>(
      section.getInt("wall_icp_samples", settings.wall_icp_samples, {0, 10000000}));
  settings.wall_icp_distance_cells =
      section.getDouble("wall_icp_distance_cells", settings.wall_icp_distance_cells, {0.5, 50.0});
  settings.radon_fallback = section.getBool("radon_fallback", settings.radon_fallback);
  settings.fallback_rotations =
      readInt(section, "fallback_rotations", settings.fallback_rotations, {1, 360});
  settings.fallback_translations =
      readInt(section, "fallback_translations", settings.fallback_translations, {1, 1000});
  settings.seed =
      static_cast<std::uint32_t>(section.getInt("seed", settings.seed, {0, 4294967295.0}));
}

void readGlobalSearchSettings(const Config& section, SeedMergerSettings& settings) {
  settings.global_search = section.getBool("global_search", settings.global_search);
  settings.global_fine_cells =
      readInt(section, "global_fine_cells", settings.global_fine_cells, {0, 64});
  settings.global_max_grid_cells =
      readInt(section, "global_max_grid_cells", settings.global_max_grid_cells, {0, 100000});
  settings.global_fine_min_verification = section.getDouble(
      "global_fine_min_verification", settings.global_fine_min_verification, {0.0, 1.0});
  settings.global_free_min_verification = section.getDouble(
      "global_free_min_verification", settings.global_free_min_verification, {0.0, 1.0});
  settings.global.coarse_cells =
      readInt(section, "global_coarse_cells", settings.global.coarse_cells, {1, 64});
  settings.global.rotation_step_rad =
      kDegree * section.getDouble("global_rotation_step_deg",
                                  settings.global.rotation_step_rad / kDegree, {0.1, 45.0});
  settings.global.peaks_per_rotation =
      readInt(section, "global_peaks_per_rotation", settings.global.peaks_per_rotation, {1, 100});
  settings.global.kept_hypotheses =
      readInt(section, "global_hypotheses", settings.global.kept_hypotheses, {1, 1000});
  settings.global.free_weight =
      section.getDouble("global_free_weight", settings.global.free_weight, {0.0, 10.0});
  settings.global.free_agreement_weight = section.getDouble(
      "global_free_agreement_weight", settings.global.free_agreement_weight, {0.0, 10.0});
  settings.global.free_agreement_hypotheses =
      readInt(section, "global_free_agreement_hypotheses",
              settings.global.free_agreement_hypotheses, {0, 1000});
  settings.global_polish_step_rad =
      kDegree * section.getDouble("global_polish_step_deg",
                                  settings.global_polish_step_rad / kDegree, {0.05, 10.0});
  settings.global_candidates =
      readInt(section, "global_candidates", settings.global_candidates, {1, 1000});
}

void readAlignmentSettings(const Config& section, SeedMergerSettings& settings) {
  WallAlignmentSettings& alignment = settings.wall_alignment;
  alignment.enabled = section.getBool("wall_alignment", alignment.enabled);
  alignment.sigma_cells =
      section.getDouble("wall_alignment_sigma_cells", alignment.sigma_cells, {0.1, 10.0});
  alignment.max_turn_deg =
      section.getDouble("wall_alignment_turn_deg", alignment.max_turn_deg, {0.0, 10.0});
  alignment.max_shift_cells =
      section.getDouble("wall_alignment_shift_cells", alignment.max_shift_cells, {0.0, 20.0});
  alignment.starts = readInt(section, "wall_alignment_starts", alignment.starts, {1, 100});
  settings.settle_alignment = section.getBool("settle_alignment", settings.settle_alignment);
  alignment.turn_check_deg =
      section.getDouble("wall_turn_check_deg", alignment.turn_check_deg, {0.1, 45.0});
  alignment.turn_check_shift_cells = section.getDouble(
      "wall_turn_check_shift_cells", alignment.turn_check_shift_cells, {0.0, 20.0});
  alignment.max_turn_share =
      section.getDouble("max_wall_turn_share", alignment.max_turn_share, {0.0, 10.0});
}

}  // namespace

SeedMergerSettings loadSeedMergerSettings(const Config& section) {
  SeedMergerSettings settings;
  readEdgeAndSegmentSettings(section, settings);
  readShapeSettings(section, settings);
  readSearchSettings(section, settings);
  readAcceptanceSettings(section, settings);
  readGlobalSearchSettings(section, settings);
  readAlignmentSettings(section, settings);
  return settings;
}

}  // namespace mrslam::fusion
