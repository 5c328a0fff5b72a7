#include "mrslam/robot/icp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mrslam/drivers/log_format.hpp"
#include "mrslam/robot/map_quality.hpp"
#include "test_data.hpp"

namespace mrslam::robot {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The scans of a log, every `stride`-th.
std::vector<LaserScan> logScans(const std::string& relative, std::size_t stride) {
  auto reader =
      drivers::openLogReader(test::sharedDataPath(relative), drivers::MalformedPolicy::kSkip);
  std::vector<LaserScan> scans;
  std::size_t index = 0;
  while (auto sample = reader->next()) {
    if (const auto* scan = std::get_if<LaserScan>(&*sample)) {
      if (index++ % stride == 0) {
        scans.push_back(*scan);
      }
    }
  }
  return scans;
}

// 50 seeded trials: a real scan with normals is the target; its points with 5 mm of noise, moved
// by a known transform (up to ±max_offset_m and ±5°), are the source; ICP from the identity must
// find the transform within 1 cm and 0.2°.
void expectRecoversKnownTransforms(const std::vector<LaserScan>& scans,
                                   const ScanPointSettings& points, double max_offset_m) {
  ASSERT_GE(scans.size(), 10u);
  std::mt19937 rng(42);
  std::uniform_int_distribution<std::size_t> pick(0, scans.size() - 1);
  std::uniform_real_distribution<double> offset(-max_offset_m, max_offset_m);
  std::uniform_real_distribution<double> turn(-5.0 * kDeg, 5.0 * kDeg);
  std::normal_distribution<double> noise(0.0, 0.005);
  IcpSettings settings;
  for (int trial = 0; trial < 50; ++trial) {
    const ScanHits hits = scanHits(scans[pick(rng)], SE2(), points);
    const IcpTarget target(orientedHits(hits, points));
    const SE2 T_target_source(offset(rng), offset(rng), turn(rng));
    std::vector<Eigen::Vector2d> source;
    for (const Eigen::Vector2d& p : target.points().points) {
      source.push_back(T_target_source.inverse() * p + Eigen::Vector2d(noise(rng), noise(rng)));
    }
    const IcpResult result = alignPointToLine(target, source, SE2(), settings);
    ASSERT_TRUE(result.converged) << "trial " << trial << ": " << icpStatusName(result.status);
    const SE2 error = T_target_source.inverse() * result.T_target_source;
    EXPECT_LT(error.translation().norm(), 0.01) << "trial " << trial;
    EXPECT_LT(std::abs(error.theta()), 0.2 * kDeg) << "trial " << trial;
    EXPECT_GT(result.inlier_fraction, 0.5) << "trial " << trial;
  }
}

TEST(IcpTest, RecoversKnownTransformsOfIntelScans) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/carmen-intel-corrected.log.gz");
  ScanPointSettings points;
  points.max_step_m = 0.3;
  expectRecoversKnownTransforms(logScans("logs/carmen-intel-corrected.log.gz", 9), points, 0.2);
}

TEST(IcpTest, RecoversKnownTransformsOfBreezySlamScans) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/breezyslam-exp1.dat");
  ScanPointSettings points;
  points.max_range_m = 4.0;
  points.min_spacing_m = 0.03;
  points.max_step_m = 0.1;
  expectRecoversKnownTransforms(logScans("logs/breezyslam-exp1.dat", 7), points, 0.15);
}

// Points along the walls of a w × h room, `spacing` apart.
std::vector<Eigen::Vector2d> roomOutline(double w, double h, double spacing) {
  std::vector<Eigen::Vector2d> points;
  for (double s = 0.0; s < w; s += spacing) {
    points.emplace_back(s, 0.0);
    points.emplace_back(s, h);
  }
  for (double s = spacing; s < h; s += spacing) {
    points.emplace_back(0.0, s);
    points.emplace_back(w, s);
  }
  return points;
}

IcpTarget targetOf(const std::vector<Eigen::Vector2d>& points) {
  return IcpTarget(withNeighbourNormals(points, 6, 0.3, 0.3));
}

TEST(IcpTest, OutliersInTheSourceDoNotPullTheFit) {
  const std::vector<Eigen::Vector2d> room = roomOutline(6.0, 4.0, 0.05);
  const IcpTarget target = targetOf(room);
  const SE2 T_target_source(0.12, -0.08, 3.0 * kDeg);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> anywhere(-1.0, 7.0);
  std::vector<Eigen::Vector2d> source;
  for (const Eigen::Vector2d& p : room) {
    source.push_back(T_target_source.inverse() * p);
  }
  for (std::size_t i = 0; i < room.size() / 4; ++i) {
    source.emplace_back(anywhere(rng), anywhere(rng) * 0.5);  // clutter: a quarter more points
  }
  const IcpResult result = alignPointToLine(target, source, SE2(), IcpSettings{});
  ASSERT_TRUE(result.converged);
  const SE2 error = T_target_source.inverse() * result.T_target_source;
  EXPECT_LT(error.translation().norm(), 0.005);
  EXPECT_LT(std::abs(error.theta()), 0.1 * kDeg);
  EXPECT_LT(result.inlier_fraction, 0.95);  // the clutter was left out
}

TEST(IcpTest, CovarianceIsLargeAlongACorridor) {
  // Two long parallel walls (along x): x is barely constrained, y and θ are.
  std::vector<Eigen::Vector2d> corridor;
  for (double x = -10.0; x <= 10.0; x += 0.05) {
    corridor.emplace_back(x, 1.0);
    corridor.emplace_back(x, -1.0);
  }
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<Eigen::Vector2d> source;
  for (std::size_t i = 0; i < corridor.size(); i += 3) {
    source.push_back(corridor[i] + Eigen::Vector2d(noise(rng), noise(rng)));
  }
  const IcpResult result = alignPointToLine(targetOf(corridor), source, SE2(), IcpSettings{});
  EXPECT_GT(result.covariance(0, 0), 100.0 * result.covariance(1, 1));
  EXPECT_LT(std::sqrt(result.covariance(1, 1)), 0.005);
  EXPECT_NEAR(result.rms_m, 0.01, 0.005);
}

TEST(IcpTest, APriorOnTheGuessWeighsAgainstThePairs) {
  const std::vector<Eigen::Vector2d> room = roomOutline(6.0, 4.0, 0.05);
  const IcpTarget target = targetOf(room);
  const SE2 T_target_source(0.10, -0.06, 2.0 * kDeg);
  std::vector<Eigen::Vector2d> source;
  for (const Eigen::Vector2d& p : room) {
    source.push_back(T_target_source.inverse() * p);
  }
  const IcpResult plain = alignPointToLine(target, source, SE2(), IcpSettings{});
  ASSERT_TRUE(plain.converged);
  // A loose prior (σ far above the offset) leaves the pairs in charge, and eq. 4 is theirs alone.
  IcpSettings loose;
  loose.prior_sigma_xy_m = 1.0;
  loose.prior_sigma_theta_rad = 1.0;
  const IcpResult held_loosely = alignPointToLine(target, source, SE2(), loose);
  ASSERT_TRUE(held_loosely.converged);
  const SE2 error = T_target_source.inverse() * held_loosely.T_target_source;
  EXPECT_LT(error.translation().norm(), 0.002);
  EXPECT_LT(std::abs(error.theta()), 0.05 * kDeg);
  EXPECT_TRUE(held_loosely.covariance.isApprox(plain.covariance, 0.05));
  // A tight prior (σ far below the offset) keeps the estimate at the guess.
  IcpSettings tight;
  tight.prior_sigma_xy_m = 1e-5;
  tight.prior_sigma_theta_rad = 1e-6;
  const IcpResult held_tightly = alignPointToLine(target, source, SE2(), tight);
  EXPECT_LT(held_tightly.T_target_source.translation().norm(), 0.005);
  EXPECT_LT(std::abs(held_tightly.T_target_source.theta()), 0.1 * kDeg);
}

TEST(IcpTest, APriorHoldsACorridorsLengthAtTheGuess) {
  // Two parallel walls along x: the pairs fix y and θ, nothing holds x but the prior.
  std::vector<Eigen::Vector2d> corridor;
  for (double x = -10.0; x <= 10.0; x += 0.05) {
    corridor.emplace_back(x, 1.0);
    corridor.emplace_back(x, -1.0);
  }
  std::vector<Eigen::Vector2d> source;
  for (std::size_t i = 0; i < corridor.size(); i += 3) {
    source.push_back(corridor[i] + Eigen::Vector2d(0.0, -0.04));
  }
  IcpSettings settings;
  settings.prior_sigma_xy_m = 0.03;
  settings.prior_sigma_theta_rad = 0.02;
  const SE2 guess(0.2, 0.0, 0.0);
  const IcpResult result = alignPointToLine(targetOf(corridor), source, guess, settings);
  ASSERT_TRUE(result.converged) << icpStatusName(result.status);
  EXPECT_NEAR(result.T_target_source.x(), guess.x(), 0.01);
  EXPECT_NEAR(result.T_target_source.y(), 0.04, 0.002);
  EXPECT_NEAR(result.T_target_source.theta(), 0.0, 0.05 * kDeg);
}

TEST(IcpTest, TooFewPointsIsAFailureNotACrash) {
  const IcpTarget target = targetOf(roomOutline(2.0, 2.0, 0.1));
  const IcpResult result = alignPointToLine(target, {{1.0, 0.0}, {1.0, 0.1}}, SE2(), IcpSettings{});
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.status, IcpStatus::kTooFewPoints);
}

TEST(IcpTest, ASourceFarFromTheTargetFindsTooFewPairs) {
  const std::vector<Eigen::Vector2d> room = roomOutline(4.0, 4.0, 0.05);
  std::vector<Eigen::Vector2d> far_away;
  for (const Eigen::Vector2d& p : room) {
    far_away.push_back(p + Eigen::Vector2d(50.0, 50.0));
  }
  const IcpResult result = alignPointToLine(targetOf(room), far_away, SE2(), IcpSettings{});
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.status, IcpStatus::kTooFewInliers);
}

TEST(IcpTest, TargetNeedsOneNormalPerPoint) {
  OrientedPoints broken;
  broken.points = {{0.0, 0.0}, {1.0, 0.0}};
  broken.normals = {{0.0, 1.0}};
  EXPECT_THROW(IcpTarget{broken}, std::invalid_argument);
}

}  // namespace
}  // namespace mrslam::robot
