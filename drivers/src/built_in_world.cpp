// The built-in test building and the three robots' routes through it.
//
// World frame: x east, y north, metres, origin at the south-west outer corner; 17 × 10 m.
//   corridor   y 4.2…6.0 over the whole length; pillars on its walls at x 6.0, 9.5 and 11.5,
//              a cabinet at its west end, a bench at its east end
//   south      S1 x 0…6 (door x 3.0…3.9), S2 x 6…11.5 (door 8.85…9.75), S3 x 11.5…17
//              (door 13.4…14.3); S2 and S3 share a door at y 1.0…1.9
//   north      N1 x 0…4.5 (door x 1.6…2.5), N2 4.5…9.5 (6.2…7.1), N3 9.5…13.5 (11.0…11.9),
//              N4 13.5…17 (15.0…15.9)
//   furniture  tables, boxes, pillars, cabinets, shelves and benches in every room; two slanted
//              walls (N3's south-east corner, N4's north-west corner)

#include <cmath>
#include <stdexcept>
#include <string>

#include "mrslam/drivers/floor_plan.hpp"
#include "mrslam/drivers/simulator.hpp"

namespace mrslam::drivers {
namespace {

using P = Eigen::Vector2d;

void addOuterWallsAndCorridor(FloorPlan& plan) {
  plan.addPolyline({P(0, 0), P(17, 0), P(17, 10), P(0, 10), P(0, 0)});
  // South corridor wall (y = 4.2) with the doors of S1 [3.0, 3.9], S2 [8.85, 9.75], S3
  // [13.4, 14.3].
  plan.addWall(P(0, 4.2), P(3.0, 4.2));
  plan.addWall(P(3.9, 4.2), P(8.85, 4.2));
  plan.addWall(P(9.75, 4.2), P(13.4, 4.2));
  plan.addWall(P(14.3, 4.2), P(17, 4.2));
  // North corridor wall (y = 6) with the doors of N1 [1.6, 2.5], N2 [6.2, 7.1], N3 [11.0, 11.9],
  // N4 [15.0, 15.9].
  plan.addWall(P(0, 6), P(1.6, 6));
  plan.addWall(P(2.5, 6), P(6.2, 6));
  plan.addWall(P(7.1, 6), P(11.0, 6));
  plan.addWall(P(11.9, 6), P(15.0, 6));
  plan.addWall(P(15.9, 6), P(17, 6));
  // Pillars standing 0.25 m out of the corridor walls, a cabinet at the west end, a bench east.
  plan.addPolyline({P(5.8, 4.2), P(5.8, 4.45), P(6.2, 4.45), P(6.2, 4.2)});
  plan.addPolyline({P(11.3, 4.2), P(11.3, 4.45), P(11.7, 4.45), P(11.7, 4.2)});
  plan.addPolyline({P(9.3, 6), P(9.3, 5.75), P(9.7, 5.75), P(9.7, 6)});
  plan.addPolyline({P(0, 5.4), P(0.5, 5.4), P(0.5, 6)});
  plan.addPolyline({P(17, 4.6), P(16.6, 4.6), P(16.6, 5.6), P(17, 5.6)});
}

void addSouthRooms(FloorPlan& plan) {
  plan.addWall(P(6, 0), P(6, 4.2));  // S1 | S2
  // S2 | S3, with a door at y [1.0, 1.9].
  plan.addWall(P(11.5, 0), P(11.5, 1.0));
  plan.addWall(P(11.5, 1.9), P(11.5, 4.2));
  // S1: table, shelf on the west wall, desk on the south wall.
  plan.addBox(P(1.6, 1.2), P(2.8, 2.0));
  plan.addPolyline({P(0, 2.6), P(0.4, 2.6), P(0.4, 3.6), P(0, 3.6)});
  plan.addPolyline({P(3.9, 0), P(3.9, 0.6), P(5.2, 0.6), P(5.2, 0)});
  // S2: box, corner desk, cabinet beside the door to S3.
  plan.addBox(P(7.8, 1.6), P(8.6, 2.4));
  plan.addPolyline({P(6, 0.6), P(6.8, 0.6), P(6.8, 0)});
  plan.addPolyline({P(11.5, 2.8), P(11.0, 2.8), P(11.0, 3.8), P(11.5, 3.8)});
  // S3: pillar, bench on the east wall.
  plan.addBox(P(14.5, 1.5), P(15.0, 2.0));
  plan.addPolyline({P(17, 0.5), P(16.5, 0.5), P(16.5, 2.5), P(17, 2.5)});
}

void addNorthRooms(FloorPlan& plan) {
  plan.addWall(P(4.5, 6), P(4.5, 10));    // N1 | N2
  plan.addWall(P(9.5, 6), P(9.5, 10));    // N2 | N3
  plan.addWall(P(13.5, 6), P(13.5, 10));  // N3 | N4
  // N1: table, shelf on the north wall.
  plan.addBox(P(1.2, 7.6), P(2.4, 8.6));
  plan.addPolyline({P(3.0, 10), P(3.0, 9.6), P(4.2, 9.6), P(4.2, 10)});
  // N2: table, cabinet on the north wall, block in the south-west corner.
  plan.addBox(P(6.0, 7.8), P(7.2, 8.6));
  plan.addPolyline({P(7.6, 10), P(7.6, 9.6), P(8.6, 9.6), P(8.6, 10)});
  plan.addPolyline({P(4.5, 6.6), P(4.9, 6.6), P(4.9, 6)});
  // N3: box, a slanted cabinet across the south-east corner.
  plan.addBox(P(11.2, 7.8), P(12.2, 8.6));
  plan.addWall(P(12.8, 6), P(13.5, 6.7));
  // N4: pillar, cabinet on the east wall, a slanted wall across the north-west corner.
  plan.addBox(P(14.9, 8.0), P(15.3, 8.4));
  plan.addPolyline({P(17, 6.8), P(16.5, 6.8), P(16.5, 7.8), P(17, 7.8)});
  plan.addWall(P(13.5, 9.2), P(14.3, 10));
}

void checkRobotIndex(int robot) {
  if (robot < 0 || robot >= kBuiltInRouteCount) {
    throw std::invalid_argument("built-in routes exist for robots 0.." +
                                std::to_string(kBuiltInRouteCount - 1) + ", not " +
                                std::to_string(robot));
  }
}

}  // namespace

FloorPlan builtInFloorPlan() {
  FloorPlan plan;
  addOuterWallsAndCorridor(plan);
  addSouthRooms(plan);
  addNorthRooms(plan);
  return plan;
}

std::vector<Eigen::Vector2d> builtInRoute(int robot) {
  checkRobotIndex(robot);
  // The corridor's centre line is y = 5.1; rooms are entered through the middle of their doors
  // and circled around their furniture with at least 0.45 m between the path and any wall.
  switch (robot) {
    case 0:  // west corridor → S2 → back west → N1
      return {P(2.05, 5.1), P(9.3, 5.1), P(9.3, 3.1),  P(7.2, 3.1),  P(7.2, 0.9),
              P(9.3, 0.9),  P(9.3, 5.1), P(2.05, 5.1), P(2.05, 6.9), P(3.3, 6.9),
              P(3.3, 9.1),  P(0.7, 9.1), P(0.7, 6.9),  P(2.05, 6.9)};
    case 1:  // east corridor → N3 → back east → S3
      return {P(15.45, 5.1), P(11.45, 5.1), P(11.45, 6.9), P(10.2, 6.9),  P(10.2, 9.3),
              P(12.9, 9.3),  P(12.9, 6.9),  P(11.45, 6.9), P(11.45, 5.1), P(13.85, 5.1),
              P(13.85, 3.0), P(15.8, 3.0),  P(15.8, 0.8),  P(13.85, 0.8), P(13.85, 5.1)};
    default:  // N2 → corridor east → N4 → corridor west → N2
      return {P(7.9, 7.5),   P(7.9, 9.1),   P(5.3, 9.1),  P(5.3, 6.9),  P(6.65, 6.9), P(6.65, 5.1),
              P(15.45, 5.1), P(15.45, 7.2), P(16.0, 7.2), P(16.0, 9.2), P(14.2, 9.2), P(14.2, 7.2),
              P(15.45, 7.2), P(15.45, 5.1), P(6.65, 5.1), P(6.65, 6.9), P(7.9, 6.9)};
  }
}

SE2 builtInStartPose(int robot) {
  const std::vector<Eigen::Vector2d> route = builtInRoute(robot);
  const Eigen::Vector2d heading = route[1] - route[0];
  return SE2(route[0].x(), route[0].y(), std::atan2(heading.y(), heading.x()));
}

}  // namespace mrslam::drivers
