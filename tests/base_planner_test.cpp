#include <gtest/gtest.h>

#include <cmath>

#include "env/world/world.hpp"
#include "primitives/base_planner.hpp"
#include "test_util.hpp"

namespace chore {
namespace {

constexpr double kBaseRadius = 0.3;

TEST(BasePlanner, FindsACollisionFreePathFromTheLivingRoomToTheKitchen) {
  World world(Scene::load("apartment"));  // robot at (3.4, 1.9) in the living room
  const OccupancyMap map(world, kBaseRadius + 0.05);
  const Pose2 goal{6.2, 2.0, 0.0};  // the kitchen, through the door at x = 4.8
  ASSERT_TRUE(map.free(goal.x, goal.y));
  ASSERT_EQ(world.scene().room_at(goal.x, goal.y)->name, "kitchen_0");
  const BasePath path = plan_base_path(world, map, goal, 7);
  ASSERT_TRUE(path.success) << path.reason;
  ASSERT_GE(path.waypoints.size(), 2u);
  EXPECT_NEAR(path.waypoints.front().x, world.base_pose().x, 1e-9);
  EXPECT_NEAR(path.waypoints.back().x, goal.x, 1e-9);
  EXPECT_NEAR(path.waypoints.back().y, goal.y, 1e-9);
  // Every point along every segment is free (checked every 2 cm).
  for (size_t k = 0; k + 1 < path.waypoints.size(); ++k) {
    const Pose2 &a = path.waypoints[k], &b = path.waypoints[k + 1];
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    for (double t = 0; t <= length; t += 0.02) {
      const double f = length > 0 ? t / length : 0;
      EXPECT_TRUE(map.free(a.x + f * (b.x - a.x), a.y + f * (b.y - a.y))) << "segment " << k;
    }
  }
}

TEST(BasePlanner, WallsAndFurnitureAreOccupiedAndGoalsInThemAreRefused) {
  World world(Scene::load("apartment"));
  const OccupancyMap map(world, kBaseRadius + 0.05);
  EXPECT_FALSE(map.free(4.8, 0.5));   // the living room / kitchen wall
  EXPECT_FALSE(map.free(100, 100));   // outside the apartment
  EXPECT_TRUE(map.free(world.base_pose().x, world.base_pose().y));
  const BasePath path = plan_base_path(world, map, {4.8, 0.5, 0}, 7);
  EXPECT_FALSE(path.success);
  EXPECT_EQ(path.reason, "the goal pose is not in free space");
}

}  // namespace
}  // namespace chore
