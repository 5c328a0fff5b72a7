#include <gtest/gtest.h>

#include "mrslam/fusion/merge/map_merger.hpp"

namespace mrslam::fusion {
namespace {

GridGeometry geometryAt(double x, double y) {
  GridGeometry geometry;
  geometry.resolution_m = 0.05;
  geometry.width = 100;
  geometry.height = 80;
  geometry.origin_m = Eigen::Vector2d(x, y);
  return geometry;
}

TEST(GridTransformTest, InverseUndoesTheTransform) {
  GridTransform transform;
  transform.theta_rad = 0.7;
  transform.t_cells = Eigen::Vector2d(12.5, -3.0);
  const Eigen::Vector2d p(4.0, 9.0);
  EXPECT_NEAR((transform.inverse().apply(transform.apply(p)) - p).norm(), 0.0, 1e-12);
}

TEST(GridTransformTest, CellMappingEqualsApplyBitForBit) {
  for (const double theta : {0.0, 0.7, -2.9, M_PI, 1e-9}) {
    GridTransform transform;
    transform.theta_rad = theta;
    transform.t_cells = Eigen::Vector2d(12.5, -3.25);
    const CellMapping mapping(transform);
    for (const Eigen::Vector2d& p :
         {Eigen::Vector2d(4.0, 9.0), Eigen::Vector2d(-311.5, 0.125), Eigen::Vector2d(1e5, -7.0)}) {
      EXPECT_EQ(mapping(p), transform.apply(p)) << theta;
    }
  }
}

TEST(GridTransformTest, MetricAndCellTransformsAgreeOnCellCentres) {
  const GridGeometry from = geometryAt(-1.3, 2.15);
  const GridGeometry to = geometryAt(0.45, -0.8);
  const SE2 T_to_from(1.2, -0.4, 0.9);
  const GridTransform cells = metricToGridTransform(T_to_from, from, to);
  for (const auto& [i, j] : {std::pair{0, 0}, std::pair{10, 3}, std::pair{57, 71}}) {
    const Eigen::Vector2d metric_to = T_to_from * from.cellCenter(i, j);
    const Eigen::Vector2d cell_to = cells.apply(Eigen::Vector2d(i, j));
    const Eigen::Vector2d centre_to = to.origin_m + (cell_to + Eigen::Vector2d(0.5, 0.5)) * 0.05;
    EXPECT_NEAR((centre_to - metric_to).norm(), 0.0, 1e-9);
  }
  const SE2 back = gridTransformToMetric(cells, from, to);
  EXPECT_NEAR(back.x(), T_to_from.x(), 1e-9);
  EXPECT_NEAR(back.y(), T_to_from.y(), 1e-9);
  EXPECT_NEAR(back.theta(), T_to_from.theta(), 1e-12);
}

}  // namespace
}  // namespace mrslam::fusion
