#include "mrslam/drivers/floor_plan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

namespace mrslam::drivers {
namespace {

using P = Eigen::Vector2d;

// A 4 × 4 m room with a 1 × 1 m box standing in it at (2…3, 2…3).
FloorPlan squareRoomWithBox() {
  FloorPlan plan;
  plan.addPolyline({P(0, 0), P(4, 0), P(4, 4), P(0, 4), P(0, 0)});
  plan.addBox(P(3, 3), P(2, 2));
  return plan;
}

double cross(const P& u, const P& v) {
  return u.x() * v.y() - u.y() * v.x();
}

TEST(FloorPlanTest, RayHitsTheNearestWallAtTheHandComputedDistance) {
  const FloorPlan plan = squareRoomWithBox();
  ASSERT_EQ(plan.walls().size(), 8u);
  // East from (1, 1): the box (y 2…3) is not in the way, the east wall is 3 m off.
  EXPECT_NEAR(plan.castRay(P(1, 1), 0.0, 10.0).value(), 3.0, 1e-12);
  // North from (2.5, 0.5): the box's south face (y = 2) comes before the north wall.
  EXPECT_NEAR(plan.castRay(P(2.5, 0.5), M_PI / 2, 10.0).value(), 1.5, 1e-12);
  // West from (3.5, 2.5): the box's east face at x = 3.
  EXPECT_NEAR(plan.castRay(P(3.5, 2.5), M_PI, 10.0).value(), 0.5, 1e-12);
  // Towards (4, 2) from (1, 1): passes below the box (y = 1.33 at x = 2, 1.67 at x = 3) and hits
  // the east wall at (4, 2), √10 away.
  EXPECT_NEAR(plan.castRay(P(1, 1), std::atan2(1.0, 3.0), 10.0).value(), std::sqrt(10.0), 1e-12);
  // Diagonally from (1, 1): exactly through the box's corner (2, 2).
  EXPECT_NEAR(plan.castRay(P(1, 1), M_PI / 4, 10.0).value(), std::sqrt(2.0), 1e-9);
  // South-west from (3, 1): reaches the south wall at (2, 0), √2 away.
  EXPECT_NEAR(plan.castRay(P(3, 1), -3 * M_PI / 4, 10.0).value(), std::sqrt(2.0), 1e-9);
  // Into the room's corner (0, 0), shared by two walls.
  EXPECT_NEAR(plan.castRay(P(1, 1), -3 * M_PI / 4, 10.0).value(), std::sqrt(2.0), 1e-9);
}

TEST(FloorPlanTest, RayMissesWallsBeyondRangeBehindItOrBesideIt) {
  FloorPlan plan;
  plan.addWall(P(2, -1), P(2, 1));
  EXPECT_FALSE(plan.castRay(P(0, 0), 0.0, 1.5).has_value());         // 2 m away
  EXPECT_NEAR(plan.castRay(P(0, 0), 0.0, 2.0).value(), 2.0, 1e-12);  // at the limit: a hit
  EXPECT_FALSE(plan.castRay(P(0, 0), M_PI, 100.0).has_value());      // behind the origin
  EXPECT_FALSE(plan.castRay(P(0, 0), M_PI / 2, 100.0).has_value());  // parallel to the wall
  EXPECT_FALSE(plan.castRay(P(0, 0), std::atan2(1.2, 2.0), 100.0).has_value());  // past its end
  EXPECT_NEAR(plan.castRay(P(0, 0), std::atan2(1.0, 2.0), 100.0).value(), std::sqrt(5.0),
              1e-9);  // grazing its end point
  EXPECT_FALSE(FloorPlan().castRay(P(0, 0), 0.0, 100.0).has_value());
}

TEST(FloorPlanTest, DistanceToTheNearestWall) {
  FloorPlan plan;
  plan.addPolyline({P(0, 0), P(4, 0), P(4, 3)});
  EXPECT_NEAR(plan.distanceToNearestWall(P(2, 1)), 1.0, 1e-12);             // foot inside
  EXPECT_NEAR(plan.distanceToNearestWall(P(-3, -4)), 5.0, 1e-12);           // end point (0, 0)
  EXPECT_NEAR(plan.distanceToNearestWall(P(5, 5)), std::sqrt(5.0), 1e-12);  // end point (4, 3)
  EXPECT_NEAR(plan.distanceToNearestWall(P(3.5, 1)), 0.5, 1e-12);           // second wall
  EXPECT_EQ(FloorPlan().distanceToNearestWall(P(0, 0)), std::numeric_limits<double>::infinity());
}

TEST(FloorPlanTest, WallsNearAnswersRaysWithinItsRadiusLikeTheWholePlan) {
  const FloorPlan plan = squareRoomWithBox();
  // From (1, 1): the south and west walls are 1 m off, the box corner √2, the others 3 m.
  EXPECT_EQ(plan.wallsNear(P(1, 1), 1.2).walls().size(), 2u);
  EXPECT_EQ(plan.wallsNear(P(1, 1), 1.5).walls().size(), 4u);
  const FloorPlan near = plan.wallsNear(P(1, 1), 2.5);
  for (int i = 0; i < 360; ++i) {
    const double angle = i * M_PI / 180.0 + 0.001;
    EXPECT_EQ(near.castRay(P(1, 1), angle, 2.5), plan.castRay(P(1, 1), angle, 2.5)) << i;
  }
}

TEST(FloorPlanTest, RejectsDegenerateWallsAndReportsBounds) {
  FloorPlan plan;
  EXPECT_THROW(plan.addWall(P(1, 1), P(1, 1)), std::invalid_argument);
  EXPECT_THROW(plan.addWall(P(1, 1), P(std::nan(""), 1)), std::invalid_argument);
  plan.addWall(P(1, -2), P(3, 5));
  plan.addWall(P(-1, 0), P(0, 0));
  EXPECT_EQ(plan.bounds().min, P(-1, -2));
  EXPECT_EQ(plan.bounds().max, P(3, 5));
}

TEST(BuiltInFloorPlanTest, IsAboutSeventeenByTenMetres) {
  const PlanBounds bounds = builtInFloorPlan().bounds();
  const P size = bounds.max - bounds.min;
  EXPECT_NEAR(size.x(), 17.0, 0.5);
  EXPECT_NEAR(size.y(), 10.0, 0.5);
}

TEST(BuiltInFloorPlanTest, RaysFromInsideNeverEscape) {
  const FloorPlan plan = builtInFloorPlan();
  const PlanBounds bounds = plan.bounds();
  const double diagonal = (bounds.max - bounds.min).norm();
  int rays = 0;
  for (double x = bounds.min.x() + 0.13; x < bounds.max.x(); x += 0.25) {
    for (double y = bounds.min.y() + 0.11; y < bounds.max.y(); y += 0.25) {
      const P origin(x, y);
      if (plan.distanceToNearestWall(origin) < 0.01) {
        continue;
      }
      // 120 directions, including ones that pass exactly through corners of the grid of walls.
      for (int i = 0; i < 120; ++i) {
        const double angle = i * 2.0 * M_PI / 120.0;
        const std::optional<double> hit = plan.castRay(origin, angle, 1e3);
        ASSERT_TRUE(hit.has_value())
            << "a ray escapes from (" << x << ", " << y << ") at " << angle;
        EXPECT_LE(*hit, diagonal);
        ++rays;
      }
    }
  }
  EXPECT_GT(rays, 200000);
}

TEST(BuiltInFloorPlanTest, NoTwoWallsOverlapOrCross) {
  const FloorPlan plan = builtInFloorPlan();
  const std::vector<WallSegment>& walls = plan.walls();
  for (std::size_t i = 0; i < walls.size(); ++i) {
    for (std::size_t j = i + 1; j < walls.size(); ++j) {
      const WallSegment& u = walls[i];
      const WallSegment& w = walls[j];
      const P e = u.b - u.a;
      const P f = w.b - w.a;
      const double denominator = cross(e, f);
      if (std::abs(denominator) < 1e-9 * e.norm() * f.norm()) {
        if (std::abs(cross(e, w.a - u.a)) > 1e-9 * e.norm()) {
          continue;  // parallel, on different lines
        }
        // Collinear: the projections of w onto u's line may touch but not overlap.
        const double s0 = (w.a - u.a).dot(e) / e.squaredNorm();
        const double s1 = (w.b - u.a).dot(e) / e.squaredNorm();
        const double overlap = std::min(1.0, std::max(s0, s1)) - std::max(0.0, std::min(s0, s1));
        EXPECT_LE(overlap * e.norm(), 1e-9) << "walls " << i << " and " << j << " overlap";
        continue;
      }
      // Crossing: the intersection lies inside both (touching at an end point is a joint).
      const double s = cross(w.a - u.a, f) / denominator;
      const double t = cross(w.a - u.a, e) / denominator;
      const double eps = 1e-9;
      EXPECT_FALSE(s > eps && s < 1 - eps && t > eps && t < 1 - eps)
          << "walls " << i << " and " << j << " cross";
    }
  }
}

TEST(BuiltInFloorPlanTest, DoorsAreOpenAndWideEnoughForTheRobot) {
  const FloorPlan plan = builtInFloorPlan();
  // Door centres: S1, S2, S3 on y = 4.2; N1…N4 on y = 6; the door between S2 and S3 on x = 11.5.
  const P doors[] = {P(3.45, 4.2), P(9.3, 4.2),   P(13.85, 4.2), P(2.05, 6.0),
                     P(6.65, 6.0), P(11.45, 6.0), P(15.45, 6.0), P(11.5, 1.45)};
  for (const P& door : doors) {
    // Half the door width (0.9 m) clear all round: the 0.25 m robot passes with 0.2 m to spare.
    EXPECT_GE(plan.distanceToNearestWall(door), 0.45 - 1e-9) << door.transpose();
  }
}

TEST(BuiltInFloorPlanTest, HasCornersAndStructureBeyondParallelWalls) {
  const FloorPlan plan = builtInFloorPlan();
  const std::vector<WallSegment>& walls = plan.walls();
  EXPECT_GE(walls.size(), 60u);
  std::set<int> directions;  // wall directions in whole degrees, modulo 180°
  int short_walls = 0;       // furniture and pillar faces
  for (const WallSegment& wall : walls) {
    const P e = wall.b - wall.a;
    const int degrees = static_cast<int>(std::lround(std::atan2(e.y(), e.x()) * 180.0 / M_PI));
    directions.insert(((degrees % 180) + 180) % 180);
    short_walls += e.norm() < 1.5 ? 1 : 0;
  }
  EXPECT_GE(directions.size(), 3u);  // not only two families of parallel walls
  EXPECT_GE(short_walls, 30);
  // Corners: end points where two walls at an angle meet.
  int corners = 0;
  for (std::size_t i = 0; i < walls.size(); ++i) {
    for (std::size_t j = i + 1; j < walls.size(); ++j) {
      const P e = walls[i].b - walls[i].a;
      const P f = walls[j].b - walls[j].a;
      if (std::abs(cross(e.normalized(), f.normalized())) < 0.5) {
        continue;
      }
      for (const P& p : {walls[i].a, walls[i].b}) {
        for (const P& q : {walls[j].a, walls[j].b}) {
          corners += (p - q).norm() < 1e-9 ? 1 : 0;
        }
      }
    }
  }
  EXPECT_GE(corners, 40);
}

}  // namespace
}  // namespace mrslam::drivers
