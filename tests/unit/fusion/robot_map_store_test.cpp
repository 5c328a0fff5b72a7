#include "mrslam/fusion/robot_map_store.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace mrslam::fusion {
namespace {

RobotMap mapOf(const std::string& id, std::uint64_t sequence, bool is_final = false) {
  RobotMap map;
  map.robot_id = id;
  map.sequence = sequence;
  map.is_final = is_final;
  return map;
}

TEST(RobotMapStoreTest, KeepsTheNewestMapOfEachRobot) {
  RobotMapStore store;
  EXPECT_EQ(store.update(mapOf("b", 1)), RobotMapStore::Outcome::kStored);
  EXPECT_EQ(store.update(mapOf("a", 3)), RobotMapStore::Outcome::kStored);
  EXPECT_EQ(store.update(mapOf("a", 2)), RobotMapStore::Outcome::kOutdated);
  EXPECT_EQ(store.update(mapOf("a", 3)), RobotMapStore::Outcome::kOutdated);
  EXPECT_EQ(store.version(), 2u);
  EXPECT_EQ(store.update(mapOf("a", 4, true)), RobotMapStore::Outcome::kStored);
  const auto maps = store.snapshot();
  ASSERT_EQ(maps.size(), 2u);
  EXPECT_EQ(maps[0].robot_id, "a");
  EXPECT_EQ(maps[0].sequence, 4u);
  EXPECT_TRUE(store.isFinal("a"));
  EXPECT_FALSE(store.isFinal("b"));
  EXPECT_FALSE(store.has("c"));
}

TEST(RobotMapStoreTest, AWaiterWakesWhenAMapIsStoredAndNotBefore) {
  RobotMapStore store;
  const std::uint64_t seen = store.version();
  EXPECT_FALSE(store.waitForChange(seen, std::chrono::milliseconds(10)));  // nothing came
  std::thread sender([&store] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    store.update(mapOf("a", 1));
  });
  EXPECT_TRUE(store.waitForChange(seen, std::chrono::seconds(10)));
  sender.join();
  EXPECT_EQ(store.version(), seen + 1);
  EXPECT_TRUE(store.waitForChange(seen, std::chrono::milliseconds(0)));  // already past it
  EXPECT_FALSE(store.update(mapOf("a", 1)) == RobotMapStore::Outcome::kStored);
  EXPECT_FALSE(store.waitForChange(seen + 1, std::chrono::milliseconds(10)));  // outdated: no
}

TEST(RobotMapStoreTest, AStaleMapIsKeptFlaggedUntilTheRobotSendsAgain) {
  RobotMapStore store;
  EXPECT_FALSE(store.setStale("a", true));  // no map of it
  store.update(mapOf("a", 5));
  const std::uint64_t version = store.version();
  EXPECT_TRUE(store.setStale("a", true));
  EXPECT_FALSE(store.setStale("a", true));  // already stale: nothing changes
  EXPECT_GT(store.version(), version);
  ASSERT_EQ(store.snapshot().size(), 1u);
  EXPECT_TRUE(store.snapshot()[0].stale);
  EXPECT_EQ(store.snapshot()[0].sequence, 5u);  // the last map stays
  EXPECT_EQ(store.staleCount(), 1u);
  store.update(mapOf("a", 6));
  EXPECT_FALSE(store.snapshot()[0].stale);
  EXPECT_EQ(store.staleCount(), 0u);
}

TEST(RobotMapStoreTest, ARestartedRobotNumbersAgainAndReplacesItsOldMap) {
  RobotMapStore store;
  store.update(mapOf("a", 40));
  EXPECT_EQ(store.update(mapOf("a", 1)), RobotMapStore::Outcome::kOutdated);
  EXPECT_EQ(store.update(mapOf("a", 1), true), RobotMapStore::Outcome::kStored);
  EXPECT_EQ(store.snapshot()[0].sequence, 1u);
  EXPECT_EQ(store.update(mapOf("a", 2)), RobotMapStore::Outcome::kStored);
}

}  // namespace
}  // namespace mrslam::fusion
