#include "mrslam/robot/slam/fast_correlative_matcher.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "mrslam/robot/slam/correlative_matcher.hpp"
#include "slam_matcher_cases.hpp"
#include "test_data.hpp"

namespace mrslam::robot::slam {
namespace {

using test::SyntheticRoom;

constexpr double kDegree = M_PI / 180.0;

/// Every best candidate of the exhaustive search over the matcher's discretisation (window
/// around the guess: whole cells, rotations j·δθ), scored on the matcher's stored probabilities.
struct Exhaustive {
  double score = -1.0;
  std::vector<SE2> best;  ///< every candidate with that score
};

Exhaustive exhaustiveSearch(const FastCorrelativeMatcher& matcher, double resolution_m,
                            const Eigen::Vector2i& origin_cell, const SE2& guess,
                            const std::vector<Eigen::Vector2d>& points, double window_m,
                            double window_rad) {
  const double step = angularSearchStep(resolution_m, points);
  const int w = static_cast<int>(std::ceil(window_m / resolution_m - 1e-9));
  const int w_theta = static_cast<int>(std::ceil(window_rad / step - 1e-9));
  Exhaustive result;
  std::vector<Eigen::Vector2i> cells(points.size());
  for (int j_theta = -w_theta; j_theta <= w_theta; ++j_theta) {
    const SE2 rotated(guess.x(), guess.y(), guess.theta() + j_theta * step);
    for (std::size_t k = 0; k < points.size(); ++k) {
      const Eigen::Vector2d p = rotated * points[k];
      cells[k] = Eigen::Vector2i(static_cast<int>(std::floor(p.x() / resolution_m)),
                                 static_cast<int>(std::floor(p.y() / resolution_m))) -
                 origin_cell;
    }
    for (int jy = -w; jy <= w; ++jy) {
      for (int jx = -w; jx <= w; ++jx) {
        double sum = 0.0;
        for (const Eigen::Vector2i& cell : cells) {
          sum += matcher.precomputed(0, cell + Eigen::Vector2i(jx, jy));
        }
        const double score = sum / static_cast<double>(points.size());
        const SE2 pose(guess.x() + jx * resolution_m, guess.y() + jy * resolution_m,
                       guess.theta() + j_theta * step);
        if (score > result.score + 1e-12) {
          result.score = score;
          result.best = {pose};
        } else if (std::abs(score - result.score) <= 1e-12) {
          result.best.push_back(pose);
        }
      }
    }
  }
  return result;
}

bool samePose(const SE2& a, const SE2& b) {
  return std::abs(a.x() - b.x()) < 1e-9 && std::abs(a.y() - b.y()) < 1e-9 &&
         std::abs(wrapAngle(a.theta() - b.theta())) < 1e-9;
}

bool isAmong(const SE2& pose, const std::vector<SE2>& poses) {
  return std::any_of(poses.begin(), poses.end(), [&](const SE2& p) { return samePose(p, pose); });
}

FastCorrelativeSettings settingsOf(double window_m, double window_rad, int depth) {
  FastCorrelativeSettings settings;
  settings.linear_search_window_m = window_m;
  settings.angular_search_window_rad = window_rad;
  settings.branch_and_bound_depth = depth;
  return settings;
}

/// Expects `pose` within one cell (per axis) and one angular step of `expected`.
void expectNear(const SE2& pose, const SE2& expected, double cell_m, double step_rad) {
  EXPECT_LE(std::abs(pose.x() - expected.x()), cell_m);
  EXPECT_LE(std::abs(pose.y() - expected.y()), cell_m);
  EXPECT_LE(std::abs(wrapAngle(pose.theta() - expected.theta())), step_rad);
}

// ---------------------------------------------------------------------------------------------
// Precomputation

TEST(FastCorrelativeMatcherTest, PrecomputedGridsAreWindowMaxima) {
  std::mt19937 random(42);
  const SyntheticRoom room = test::syntheticRoom(random);
  const FastCorrelativeMatcher matcher(room.grid, settingsOf(1.0, 0.3, 5));
  const ProbabilityGrid& grid = room.grid;
  const double p_min = grid.settings().min_probability;
  const double half_level = 0.5 * (grid.settings().max_probability - p_min) / 255.0;
  for (int y = -3; y < grid.height() + 3; ++y) {
    for (int x = -3; x < grid.width() + 3; ++x) {
      const double p = grid.probability({x, y}, static_cast<float>(p_min));
      ASSERT_NEAR(matcher.precomputed(0, {x, y}), p, half_level + 1e-7);
    }
  }
  for (int h = 1; h < matcher.depth(); ++h) {
    const int size = 1 << h;
    for (int y = -size - 1; y < grid.height() + 1; y += 3) {
      for (int x = -size - 1; x < grid.width() + 1; x += 2) {
        double expected = p_min;
        for (int dy = 0; dy < size; ++dy) {
          for (int dx = 0; dx < size; ++dx) {
            expected = std::max(expected, matcher.precomputed(0, {x + dx, y + dy}));
          }
        }
        ASSERT_DOUBLE_EQ(matcher.precomputed(h, {x, y}), expected) << h << " " << x << " " << y;
      }
    }
  }
  EXPECT_THROW(matcher.precomputed(5, {0, 0}), std::out_of_range);
}

TEST(FastCorrelativeMatcherTest, MemoryIsOneBytePerCellAndHeight) {
  std::mt19937 random(42);
  const SyntheticRoom room = test::syntheticRoom(random);
  const FastCorrelativeMatcher matcher(room.grid, settingsOf(1.0, 0.3, 7));
  const std::size_t padded_width = static_cast<std::size_t>(room.grid.width() + 63);
  const std::size_t padded_height = static_cast<std::size_t>(room.grid.height() + 63);
  EXPECT_EQ(matcher.memoryBytes(), 7 * padded_width * padded_height);
}

// ---------------------------------------------------------------------------------------------
// Branch and bound against the exhaustive search

TEST(FastCorrelativeMatcherTest, BranchAndBoundEqualsExhaustiveSearch) {
  constexpr double kWindowM = 1.0;
  constexpr double kWindowRad = 25.0 * kDegree;
  std::mt19937 random(42);
  std::uniform_real_distribution<double> offset_m(-0.6, 0.6);
  std::uniform_real_distribution<double> offset_rad(-0.3, 0.3);
  int cases = 0;
  int single_best = 0;
  for (int room_number = 0; room_number < 3; ++room_number) {
    const SyntheticRoom room = test::syntheticRoom(random);
    const double r = room.grid.resolution();
    std::vector<std::unique_ptr<FastCorrelativeMatcher>> matchers;
    for (const int depth : {1, 2, 4, 7}) {
      matchers.push_back(std::make_unique<FastCorrelativeMatcher>(
          room.grid, settingsOf(kWindowM, kWindowRad, depth)));
    }
    for (int i = 0; i < 17; ++i) {
      const SE2 guess(room.T_submap_robot.x() + offset_m(random),
                      room.T_submap_robot.y() + offset_m(random),
                      room.T_submap_robot.theta() + offset_rad(random));
      const Exhaustive exhaustive = exhaustiveSearch(*matchers.front(), r, room.grid.originCell(),
                                                     guess, room.scan_robot, kWindowM, kWindowRad);
      ++cases;
      single_best += exhaustive.best.size() == 1 ? 1 : 0;
      for (const auto& matcher : matchers) {
        SCOPED_TRACE(testing::Message()
                     << "room " << room_number << " guess " << i << " depth " << matcher->depth());
        const std::optional<FastMatch> found = matcher->match(guess, room.scan_robot, 0.0);
        ASSERT_TRUE(found);
        EXPECT_NEAR(found->score, exhaustive.score, 1e-12);
        EXPECT_TRUE(isAmong(found->T_submap_robot, exhaustive.best));
        EXPECT_DOUBLE_EQ(matcher->score(found->T_submap_robot, room.scan_robot), found->score);
        // Only a score above min_score is a match (a bar a hair above the best: the scores are
        // means of quantised cells, compared as sums).
        EXPECT_FALSE(matcher->match(guess, room.scan_robot, exhaustive.score + 1e-9));
        const std::optional<FastMatch> just_above =
            matcher->match(guess, room.scan_robot, exhaustive.score - 1e-6);
        ASSERT_TRUE(just_above);
        EXPECT_NEAR(just_above->score, exhaustive.score, 1e-12);
      }
    }
  }
  // Most cases have one best candidate, so the pose itself is pinned down.
  EXPECT_GE(single_best, cases / 2) << single_best << " of " << cases;
}

TEST(FastCorrelativeMatcherTest, RecoversSyntheticOffset) {
  std::mt19937 random(42);
  const SyntheticRoom room = test::syntheticRoom(random);
  const FastCorrelativeMatcher matcher(room.grid, settingsOf(1.0, 30.0 * kDegree, 7));
  const SE2 guess = room.T_submap_robot * SE2(0.3, -0.2, 5.0 * kDegree);
  const std::optional<FastMatch> found = matcher.match(guess, room.scan_robot, 0.5);
  ASSERT_TRUE(found);
  const double step = angularSearchStep(room.grid.resolution(), room.scan_robot);
  expectNear(found->T_submap_robot, room.T_submap_robot, room.grid.resolution(), step);
}

TEST(FastCorrelativeMatcherTest, FindsSyntheticScanInFullSubmap) {
  std::mt19937 random(7);
  const SyntheticRoom room = test::syntheticRoom(random);
  const FastCorrelativeMatcher matcher(room.grid, FastCorrelativeSettings{});
  const std::optional<FastMatch> found = matcher.matchFullSubmap(room.scan_robot, 0.5);
  ASSERT_TRUE(found);
  // The whole submap at every turn: nothing scores below the truth's cell and step.
  const double truth_score = matcher.score(room.T_submap_robot, room.scan_robot);
  EXPECT_GE(found->score, truth_score - 1e-9);
  const double step = angularSearchStep(room.grid.resolution(), room.scan_robot);
  if (found->score > truth_score + 1e-9) {
    return;  // a rotationally symmetric room scores some other turn higher: no truth to find
  }
  expectNear(found->T_submap_robot, room.T_submap_robot, room.grid.resolution(), step);
}

// ---------------------------------------------------------------------------------------------
// A real submap: 30 consecutive intel scans at their corrected poses

class FastCorrelativeMatcherIntelTest : public ::testing::Test {
 protected:
  void SetUp() override {
    MRSLAM_REQUIRE_SHARED_DATA(test::kIntelLog);
    scans_ = test::carmenScans(::mrslam::test::sharedDataPath(test::kIntelLog), 30);
    ASSERT_EQ(scans_.size(), 30u);
    grid_ = std::make_unique<ProbabilityGrid>(test::submapOf(scans_));
    matcher_ = std::make_unique<FastCorrelativeMatcher>(*grid_, FastCorrelativeSettings{});
  }

  std::vector<LaserScan> scans_;
  std::unique_ptr<ProbabilityGrid> grid_;
  std::unique_ptr<FastCorrelativeMatcher> matcher_;
};

TEST_F(FastCorrelativeMatcherIntelTest, RecoversOffsetWithinOneCellAndStep) {
  for (const std::size_t index : {5u, 15u, 25u}) {
    SCOPED_TRACE(testing::Message() << "scan " << index);
    const SE2& T_submap_laser = *scans_[index].logged_pose;
    const std::vector<Eigen::Vector2d> points = test::hitsOf(scans_[index]);
    const SE2 guess(T_submap_laser.x() + 0.3, T_submap_laser.y() - 0.2,
                    T_submap_laser.theta() + 5.0 * kDegree);
    const std::optional<FastMatch> found = matcher_->match(guess, points, 0.55);
    ASSERT_TRUE(found);
    expectNear(found->T_submap_robot, T_submap_laser, grid_->resolution(),
               angularSearchStep(grid_->resolution(), points));
    EXPECT_GT(found->score, 0.55);  // clears the loop closure's score bar
  }
}

TEST_F(FastCorrelativeMatcherIntelTest, FindsScanInFullSubmap) {
  const SE2& T_submap_laser = *scans_[15].logged_pose;
  const std::vector<Eigen::Vector2d> points = test::hitsOf(scans_[15]);
  const std::optional<FastMatch> found = matcher_->matchFullSubmap(points, 0.55);
  ASSERT_TRUE(found);
  expectNear(found->T_submap_robot, T_submap_laser, grid_->resolution(),
             angularSearchStep(grid_->resolution(), points));
}

TEST_F(FastCorrelativeMatcherIntelTest, MemoryOfTheSubmap) {
  const std::size_t padded = static_cast<std::size_t>(grid_->width() + 63) *
                             static_cast<std::size_t>(grid_->height() + 63);
  EXPECT_EQ(matcher_->memoryBytes(), 7 * padded);
  RecordProperty("grid_cells",
                 std::to_string(grid_->width()) + "x" + std::to_string(grid_->height()));
  RecordProperty("precomputed_bytes", std::to_string(matcher_->memoryBytes()));
}

// ---------------------------------------------------------------------------------------------
// Edge cases

TEST(FastCorrelativeMatcherTest, NoPointsGiveNothing) {
  std::mt19937 random(42);
  const SyntheticRoom room = test::syntheticRoom(random);
  const FastCorrelativeMatcher matcher(room.grid, FastCorrelativeSettings{});
  EXPECT_FALSE(matcher.match(room.T_submap_robot, {}, 0.0));
  EXPECT_FALSE(matcher.matchFullSubmap({}, 0.0));
}

TEST(FastCorrelativeMatcherTest, MinScoreAboveEveryCandidateGivesNothing) {
  std::mt19937 random(42);
  const SyntheticRoom room = test::syntheticRoom(random);
  const FastCorrelativeMatcher matcher(room.grid, FastCorrelativeSettings{});
  EXPECT_FALSE(matcher.match(room.T_submap_robot, room.scan_robot, 0.9));
  EXPECT_FALSE(matcher.match(room.T_submap_robot, room.scan_robot, 2.0));
  EXPECT_FALSE(matcher.matchFullSubmap(room.scan_robot, 0.9));
}

TEST(FastCorrelativeMatcherTest, GuessFarOutsideTheGridGivesNothing) {
  std::mt19937 random(42);
  const SyntheticRoom room = test::syntheticRoom(random);
  const FastCorrelativeMatcher matcher(room.grid, FastCorrelativeSettings{});
  for (const SE2& guess : {SE2(100.0, -50.0, 0.3), SE2(1e12, 1e12, 0.0), SE2(-1e15, 3e14, 2.0)}) {
    EXPECT_FALSE(matcher.match(guess, room.scan_robot, 0.2));
    // Nothing known: the best candidate scores p_min.
    const std::optional<FastMatch> any = matcher.match(guess, room.scan_robot, 0.0);
    ASSERT_TRUE(any);
    EXPECT_DOUBLE_EQ(any->score, room.grid.settings().min_probability);
  }
}

TEST(FastCorrelativeMatcherTest, EmptyGridGivesNothing) {
  const ProbabilityGrid empty{ProbabilityGridSettings{}};
  const FastCorrelativeMatcher matcher(empty, FastCorrelativeSettings{});
  const std::vector<Eigen::Vector2d> points = {{1.0, 0.0}, {0.0, 2.0}};
  EXPECT_FALSE(matcher.match(SE2(), points, 0.2));
  EXPECT_FALSE(matcher.matchFullSubmap(points, 0.2));
}

TEST(FastCorrelativeMatcherTest, RejectsBadSettings) {
  const ProbabilityGrid empty{ProbabilityGridSettings{}};
  EXPECT_THROW(FastCorrelativeMatcher(empty, settingsOf(-1.0, 0.3, 7)), std::invalid_argument);
  EXPECT_THROW(FastCorrelativeMatcher(empty, settingsOf(1.0, NAN, 7)), std::invalid_argument);
  EXPECT_THROW(FastCorrelativeMatcher(empty, settingsOf(1.0, 0.3, 0)), std::invalid_argument);
  EXPECT_THROW(FastCorrelativeMatcher(empty, settingsOf(1.0, 0.3, 17)), std::invalid_argument);
  const FastCorrelativeMatcher matcher(empty, FastCorrelativeSettings{});
  EXPECT_THROW(matcher.match(SE2(), {{1.0, 0.0}}, 0.5, -1.0, 0.1), std::invalid_argument);
}

}  // namespace
}  // namespace mrslam::robot::slam
