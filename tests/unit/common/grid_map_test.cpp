#include "mrslam/common/grid_map.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace mrslam {
namespace {

GridMap oneRowMap(int width) {
  GridGeometry geometry;
  geometry.width = width;
  geometry.height = 1;
  return GridMap(geometry, GridMap::kUnknown);
}

// Every byte value in every position of a row longer than one vector register: only kUnknown and
// kFree..kOccupied are cell values.
TEST(GridMapTest, OnlyUnknownAndZeroToHundredAreValidCellValues) {
  for (int value = std::numeric_limits<std::int8_t>::min();
       value <= std::numeric_limits<std::int8_t>::max(); ++value) {
    const bool expected =
        value == GridMap::kUnknown || (value >= GridMap::kFree && value <= GridMap::kOccupied);
    for (const int position : {0, 1, 31, 32, 63, 64, 70}) {
      GridMap map = oneRowMap(71);
      map.at(position, 0) = static_cast<std::int8_t>(value);
      EXPECT_EQ(map.isValid(), expected) << "value " << value << " at " << position;
    }
  }
}

TEST(GridMapTest, AGeometryThatDoesNotFitItsCellsIsInvalid) {
  GridMap map = oneRowMap(8);
  ASSERT_TRUE(map.isValid());
  map.cells.pop_back();
  EXPECT_FALSE(map.isValid());
  GridMap unscaled = oneRowMap(8);
  unscaled.geometry.resolution_m = 0.0;
  EXPECT_FALSE(unscaled.isValid());
}

}  // namespace
}  // namespace mrslam
