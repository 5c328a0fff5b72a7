// truthSlide (truth_slide.hpp): how many disagreeing cells the best placement slid 3-8 cells from
// a transform adds, on hand-built grids whose answer is known.

#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/truth_slide.hpp"

namespace mrslam::fusion {
namespace {

GridMap unknownMap(int width, int height) {
  GridGeometry geometry;
  geometry.width = width;
  geometry.height = height;
  return GridMap(geometry, GridMap::kUnknown);
}

// A corridor along x across the whole map: walls on rows 10 and 20, open floor between them.
GridMap corridor() {
  GridMap map = unknownMap(120, 31);
  for (int x = 0; x < 120; ++x) {
    for (int y = 10; y <= 20; ++y) {
      map.at(x, y) = (y == 10 || y == 20) ? GridMap::kOccupied : GridMap::kFree;
    }
  }
  return map;
}

// A closed room: walls around x, y in [10, 50], open floor inside.
GridMap room() {
  GridMap map = unknownMap(61, 61);
  for (int y = 10; y <= 50; ++y) {
    for (int x = 10; x <= 50; ++x) {
      const bool wall = x == 10 || x == 50 || y == 10 || y == 50;
      map.at(x, y) = wall ? GridMap::kOccupied : GridMap::kFree;
    }
  }
  return map;
}

TEST(MergeTruthSlideTest, ACorridorSlidAlongItsWallsCostsNothing) {
  const GridMap map = corridor();
  const TruthSlide slide = truthSlide(map, map, GridTransform{});
  EXPECT_EQ(slide.at_truth.disagreement, 0);
  EXPECT_EQ(slide.truth_shift, Eigen::Vector2i(0, 0));  // ties keep the larger overlap
  ASSERT_TRUE(slide.slid_found);
  EXPECT_EQ(slide.margin(), 0);
  EXPECT_EQ(slide.slide.y(), 0) << "a slide across the corridor puts its walls on its floor";
  EXPECT_GE(std::abs(slide.slide.x()), 3);
  // The slide that loses least of the overlap is the shortest along the corridor: 3 cells.
  EXPECT_EQ(std::abs(slide.slide.x()), 3);
}

TEST(MergeTruthSlideTest, EverySlideOfAClosedRoomPutsWallsOnFloor) {
  const GridMap map = room();
  const TruthSlide slide = truthSlide(map, map, GridTransform{});
  EXPECT_EQ(slide.at_truth.disagreement, 0);
  EXPECT_EQ(slide.at_truth.agreement, 41 * 41);
  ASSERT_TRUE(slide.slid_found);
  // The cheapest slide is 3 cells along an axis (it keeps 38/41 of the overlap): one side wall's
  // 39 cells between the corners land on floor, and 39 cells of floor land on the other side
  // wall; the moved wall's other side lands on unknown cells, and the walls along the slide stay
  // on walls. Longer or diagonal slides put more walls on floor.
  EXPECT_EQ(slide.margin(), 2 * 39);
  EXPECT_EQ(std::max(std::abs(slide.slide.x()), std::abs(slide.slide.y())), 3);
  EXPECT_TRUE(slide.slide.x() == 0 || slide.slide.y() == 0);
}

TEST(MergeTruthSlideTest, TheTruthsBasinIsTheCleanestPlacementWithinACell) {
  const GridMap map = room();
  GridTransform off_by_one;
  off_by_one.t_cells = Eigen::Vector2d(1.0, 0.0);  // the truth given one cell off
  const TruthSlide slide = truthSlide(map, map, off_by_one);
  EXPECT_EQ(slide.truth_shift, Eigen::Vector2i(-1, 0));
  EXPECT_EQ(slide.at_truth.disagreement, 0);
}

TEST(MergeTruthSlideTest, SlidesThatLoseTheOverlapAreNotCounted) {
  // A strip of 6 columns: any slide of 3 cells along x keeps half of it, less than 0.9; a slide
  // along y runs off the known rows too. No slid placement keeps the overlap.
  GridMap strip = unknownMap(40, 40);
  for (int x = 17; x < 23; ++x) {
    for (int y = 17; y < 23; ++y) {
      strip.at(x, y) = GridMap::kFree;
    }
  }
  const TruthSlide slide = truthSlide(strip, strip, GridTransform{});
  EXPECT_EQ(slide.at_truth.agreement, 36);
  EXPECT_FALSE(slide.slid_found);
  TruthSlideSettings lenient;
  lenient.min_overlap_share = 0.0;
  const TruthSlide any = truthSlide(strip, strip, GridTransform{}, lenient);
  EXPECT_TRUE(any.slid_found);
}

TEST(MergeTruthSlideTest, BadSettingsAreRefused) {
  const GridMap map = room();
  TruthSlideSettings settings;
  settings.reach = 0;
  EXPECT_THROW(truthSlide(map, map, GridTransform{}, settings), std::invalid_argument);
  settings = {};
  settings.min_slide = 1;  // would count the truth's own basin as a slide
  EXPECT_THROW(truthSlide(map, map, GridTransform{}, settings), std::invalid_argument);
  settings = {};
  settings.min_slide = settings.reach + 1;
  EXPECT_THROW(truthSlide(map, map, GridTransform{}, settings), std::invalid_argument);
}

}  // namespace
}  // namespace mrslam::fusion
