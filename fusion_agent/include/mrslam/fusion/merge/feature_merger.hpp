#pragma once
// The feature baseline, after the approach of ROS multirobot_map_merge (Hörner 2016), which
// follows image stitching (Brown & Lowe, IJCV 2007):
//   1. each grid becomes a grey picture (occupied black, free white, unknown mid grey), one pixel
//      per cell, so picture coordinates are cell coordinates;
//   2. ORB (or AKAZE) key points and binary descriptors on both pictures (ORB: more cases
//      merged on the known-answer suite than AKAZE, and faster);
//   3. matches of nearest descriptors that pass Lowe's ratio test;
//   4. RANSAC fit of a similarity (cv::estimateAffinePartial2D) to the matches;
//   5. confidence = inliers / (8 + 0.3 · matches) (Brown & Lowe's match test) against a bar;
//   6. a rigid least-squares refit on the inliers gives T_to_from; V and H as the tools score them.

#include <chrono>
#include <string>

#include "mrslam/common/config.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"

namespace mrslam::fusion {

struct FeatureMergerSettings {
  std::string detector = "orb";         ///< key points and descriptors: "orb" or "akaze"
  int orb_features = 3000;              ///< ORB: most key points per map
  double ratio_test = 0.8;              ///< best / second-best descriptor distance must be below
  double ransac_threshold_cells = 3.0;  ///< RANSAC: largest reprojection error of an inlier
  int min_inliers = 8;                  ///< fewer RANSAC inliers: refused
  double confidence_threshold = 1.0;    ///< inliers / (8 + 0.3 · matches) below this: refused
  double max_scale_error = 0.1;         ///< |scale − 1| of the fitted similarity above: refused
  double min_verification = 0.0;        ///< V below this: refused (0: the confidence test alone)
};

/// Reads the settings from a config section (every key optional, defaults above); throws
/// ConfigError for a wrong type or an out-of-range value.
FeatureMergerSettings loadFeatureMergerSettings(const Config& config);

/// Time spent in each step by the last merge (zero for the steps it did not reach).
struct FeatureMergeTimings {
  using Duration = std::chrono::duration<double, std::milli>;
  Duration detection{};     ///< steps 1-2, both maps
  Duration matching{};      ///< step 3
  Duration ransac{};        ///< steps 4-5
  Duration verification{};  ///< step 6
};

class FeatureMerger : public MapMerger {
 public:
  explicit FeatureMerger(const FeatureMergerSettings& settings);
  MergeResult merge(const GridMap& from, const GridMap& to) override;
  std::string name() const override { return "feature"; }
  const FeatureMergeTimings& lastTimings() const { return timings_; }

 private:
  const FeatureMergerSettings settings_;
  FeatureMergeTimings timings_;
};

}  // namespace mrslam::fusion
