#include "mrslam/dds/convert.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace mrslam::dds {
namespace {

using ::testing::HasSubstr;

GridMap smallMap() {
  GridGeometry geometry;
  geometry.resolution_m = 0.05;
  geometry.width = 4;
  geometry.height = 3;
  geometry.origin_m = Eigen::Vector2d(-3.2, 1.25);
  GridMap map(geometry, GridMap::kUnknown);
  map.at(0, 0) = 0;
  map.at(3, 2) = 100;
  map.at(1, 1) = 57;
  return map;
}

TEST(ConvertTest, StampRoundTripsIncludingNegativeTimes) {
  for (const std::int64_t ns :
       {0LL, 1LL, 999999999LL, 1234567890123456789LL, -1LL, -1500000000LL}) {
    EXPECT_EQ(fromMsg(toMsg(Stamp{ns})).ns, ns);
  }
  const msg::Time time = toMsg(Stamp{-1500000000});
  EXPECT_EQ(time.sec(), -2);
  EXPECT_EQ(time.nanosec(), 500000000u);
}

TEST(ConvertTest, GridRoundTripsExactly) {
  const GridMap map = smallMap();
  msg::GridInfo info;
  std::vector<std::uint8_t> data;
  gridToMsg(map, info, data);
  EXPECT_EQ(data[0], 0u);
  EXPECT_EQ(data[1], 0xFFu);  // -1 as an octet
  const Result<GridMap> back = gridFromMsg(info, data, 1000);
  ASSERT_TRUE(back.ok()) << back.reason();
  EXPECT_EQ(back.value(), map);
}

TEST(ConvertTest, RefusesGridsWhoseHeaderDisagreesWithTheData) {
  const GridMap map = smallMap();
  msg::GridInfo info;
  std::vector<std::uint8_t> data;
  gridToMsg(map, info, data);

  std::vector<std::uint8_t> short_data(data.begin(), data.end() - 1);
  EXPECT_THAT(gridFromMsg(info, short_data, 1000).reason(), HasSubstr("data holds 11"));

  msg::GridInfo nan_origin = info;
  nan_origin.origin().x(std::numeric_limits<double>::quiet_NaN());
  EXPECT_THAT(gridFromMsg(nan_origin, data, 1000).reason(), HasSubstr("origin is not finite"));

  msg::GridInfo zero_resolution = info;
  zero_resolution.resolution(0.0);
  EXPECT_THAT(gridFromMsg(zero_resolution, data, 1000).reason(), HasSubstr("resolution"));

  msg::GridInfo rotated = info;
  rotated.origin().theta(0.3);
  EXPECT_THAT(gridFromMsg(rotated, data, 1000).reason(), HasSubstr("rotated"));

  EXPECT_THAT(gridFromMsg(info, data, 11).reason(), HasSubstr("exceed the limit"));

  std::vector<std::uint8_t> bad_value = data;
  bad_value[5] = 101;
  EXPECT_THAT(gridFromMsg(info, bad_value, 1000).reason(), HasSubstr("outside -1..100"));
  bad_value[5] = static_cast<std::uint8_t>(-2);
  EXPECT_THAT(gridFromMsg(info, bad_value, 1000).reason(), HasSubstr("outside -1..100"));

  msg::GridInfo huge = info;
  huge.width(4000000000u);
  huge.height(4000000000u);
  EXPECT_THAT(gridFromMsg(huge, data, 1000).reason(), HasSubstr("exceed the limit"));
}

}  // namespace
}  // namespace mrslam::dds
