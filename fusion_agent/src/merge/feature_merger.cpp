#include "mrslam/fusion/merge/feature_merger.hpp"

#include <chrono>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <sstream>
#include <vector>

#include "mrslam/fusion/merge/overlap_score.hpp"

namespace mrslam::fusion {
namespace {

constexpr int kUnknownGrey = 128;

struct Features {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
};

/// Matched key point positions (cell coordinates) of `from` and `to`.
struct Matches {
  std::vector<cv::Point2f> from;
  std::vector<cv::Point2f> to;
};

/// One pixel per cell, picture row r = grid row r (so key points are in cell coordinates).
cv::Mat pictureOf(const GridMap& map) {
  cv::Mat picture(map.geometry.height, map.geometry.width, CV_8UC1);
  for (int y = 0; y < map.geometry.height; ++y) {
    auto* row = picture.ptr<std::uint8_t>(y);
    for (int x = 0; x < map.geometry.width; ++x) {
      const CellClass cell = classOf(map.at(x, y));
      row[x] = static_cast<std::uint8_t>(cell == CellClass::kOccupied ? 0
                                         : cell == CellClass::kFree   ? 255
                                                                      : kUnknownGrey);
    }
  }
  return picture;
}

cv::Ptr<cv::Feature2D> makeDetector(const FeatureMergerSettings& settings) {
  if (settings.detector == "akaze") {
    return cv::AKAZE::create();
  }
  return cv::ORB::create(settings.orb_features);
}

Features detect(const GridMap& map, cv::Feature2D& detector) {
  Features features;
  detector.detectAndCompute(pictureOf(map), cv::noArray(), features.keypoints,
                            features.descriptors);
  return features;
}

/// Nearest-descriptor matches from `from` to `to` that pass the ratio test.
Matches matchFeatures(const Features& from, const Features& to, double ratio) {
  Matches matches;
  if (from.descriptors.empty() || to.descriptors.rows < 2) {
    return matches;
  }
  cv::BFMatcher matcher(cv::NORM_HAMMING);
  std::vector<std::vector<cv::DMatch>> candidates;
  matcher.knnMatch(from.descriptors, to.descriptors, candidates, 2);
  for (const auto& pair : candidates) {
    if (pair.size() == 2 && pair[0].distance < ratio * pair[1].distance) {
      matches.from.push_back(from.keypoints[static_cast<std::size_t>(pair[0].queryIdx)].pt);
      matches.to.push_back(to.keypoints[static_cast<std::size_t>(pair[0].trainIdx)].pt);
    }
  }
  return matches;
}

/// Least-squares rotation and translation taking the inliers of `from` onto those of `to`.
GridTransform rigidFit(const Matches& matches, const std::vector<std::uint8_t>& inlier) {
  Eigen::Vector2d from_mean = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_mean = Eigen::Vector2d::Zero();
  double count = 0.0;
  for (std::size_t i = 0; i < inlier.size(); ++i) {
    if (inlier[i] != 0) {
      from_mean += Eigen::Vector2d(matches.from[i].x, matches.from[i].y);
      to_mean += Eigen::Vector2d(matches.to[i].x, matches.to[i].y);
      count += 1.0;
    }
  }
  from_mean /= count;
  to_mean /= count;
  double dot = 0.0;
  double cross = 0.0;
  for (std::size_t i = 0; i < inlier.size(); ++i) {
    if (inlier[i] != 0) {
      const Eigen::Vector2d p = Eigen::Vector2d(matches.from[i].x, matches.from[i].y) - from_mean;
      const Eigen::Vector2d q = Eigen::Vector2d(matches.to[i].x, matches.to[i].y) - to_mean;
      dot += p.dot(q);
      cross += p.x() * q.y() - p.y() * q.x();
    }
  }
  GridTransform transform;
  transform.theta_rad = std::atan2(cross, dot);
  transform.t_cells = to_mean - transform.apply(from_mean);  // t is still zero in apply()
  return transform;
}

MergeResult refused(std::string reason, int trials) {
  MergeResult result;
  result.method = "feature";
  result.trials = trials;
  result.reason = std::move(reason);
  return result;
}

using Clock = std::chrono::steady_clock;

/// Adds the time since `start` to `total` and restarts the clock.
void lap(Clock::time_point& start, FeatureMergeTimings::Duration& total) {
  const Clock::time_point now = Clock::now();
  total += now - start;
  start = now;
}

std::string describe(const char* what, double value, const char* bar, double limit) {
  std::ostringstream text;
  text << what << ' ' << value << ' ' << bar << ' ' << limit;
  return text.str();
}

}  // namespace

FeatureMergerSettings loadFeatureMergerSettings(const Config& config) {
  FeatureMergerSettings s;
  s.detector = config.getChoice("detector", s.detector, {"orb", "akaze"});
  s.orb_features = static_cast<int>(config.getInt("orb_features", s.orb_features, {10, 100000}));
  s.ratio_test = config.getDouble("ratio_test", s.ratio_test, {0.1, 1.0});
  s.ransac_threshold_cells =
      config.getDouble("ransac_threshold_cells", s.ransac_threshold_cells, {0.1, 100.0});
  s.min_inliers = static_cast<int>(config.getInt("min_inliers", s.min_inliers, {3, 100000}));
  s.confidence_threshold =
      config.getDouble("confidence_threshold", s.confidence_threshold, {0.0, 1000.0});
  s.max_scale_error = config.getDouble("max_scale_error", s.max_scale_error, {0.0, 1.0});
  s.min_verification = config.getDouble("min_verification", s.min_verification, {0.0, 1.0});
  return s;
}

FeatureMerger::FeatureMerger(const FeatureMergerSettings& settings) : settings_(settings) {}

MergeResult FeatureMerger::merge(const GridMap& from, const GridMap& to) {
  timings_ = {};
  Clock::time_point clock = Clock::now();
  const cv::Ptr<cv::Feature2D> detector = makeDetector(settings_);
  const Features features_from = detect(from, *detector);
  const Features features_to = detect(to, *detector);
  lap(clock, timings_.detection);
  const Matches matches = matchFeatures(features_from, features_to, settings_.ratio_test);
  lap(clock, timings_.matching);
  const int match_count = static_cast<int>(matches.from.size());
  if (match_count < settings_.min_inliers) {
    return refused(describe("matches", match_count, "<", settings_.min_inliers), match_count);
  }
  std::vector<std::uint8_t> inlier;
  const cv::Mat similarity = cv::estimateAffinePartial2D(
      matches.from, matches.to, inlier, cv::RANSAC, settings_.ransac_threshold_cells, 5000, 0.995);
  const int inliers = cv::countNonZero(inlier);
  lap(clock, timings_.ransac);
  if (similarity.empty() || inliers < settings_.min_inliers) {
    return refused(describe("RANSAC inliers", inliers, "<", settings_.min_inliers), match_count);
  }
  const double confidence = inliers / (8.0 + 0.3 * match_count);
  if (confidence < settings_.confidence_threshold) {
    return refused(describe("confidence", confidence, "<", settings_.confidence_threshold),
                   match_count);
  }
  const double scale = std::hypot(similarity.at<double>(0, 0), similarity.at<double>(1, 0));
  if (std::abs(scale - 1.0) > settings_.max_scale_error) {
    return refused(describe("scale", scale, "off 1 by more than", settings_.max_scale_error),
                   match_count);
  }
  MergeResult result = refused("", match_count);
  result.T_to_from = rigidFit(matches, inlier);
  const OverlapScore score = scoreOverlap(from, to, result.T_to_from);
  result.verification = score.verification();
  result.entropy = score.entropy_bits;
  lap(clock, timings_.verification);
  if (result.verification < settings_.min_verification) {
    result.reason = describe("verification", result.verification, "<", settings_.min_verification);
    return result;
  }
  result.accepted = true;
  return result;
}

}  // namespace mrslam::fusion
