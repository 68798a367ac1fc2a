#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstdio>
#include <functional>

#include "base/error.hpp"
#include "test_util.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"
#include "world/sampling.hpp"

namespace chore {
namespace {

class Predicates : public ::testing::Test {
 protected:
  Predicates() : scene_(Scene::load(test::data_path("scenes/predicate_room.json"))), world_(scene_) {}

  int object(const char* name) const {
    const SceneObject* o = scene_->find_object(name);
    return o ? static_cast<int>(o - scene_->objects().data()) : -1;
  }
  int room(const char* name) const {
    for (size_t i = 0; i < scene_->rooms().size(); ++i) {
      if (scene_->rooms()[i].name == name) return static_cast<int>(i);
    }
    return -1;
  }
  void reset() { world_.reset(scene_->robot_start()); }
  // Moves a free object's origin (bottom centre) to p and lets physics find contacts.
  void put(int o, double x, double y, double z) {
    const mjModel* m = world_.model();
    double* q = world_.data()->qpos + m->jnt_qposadr[m->body_jntadr[scene_->objects()[o].body]];
    q[0] = x;
    q[1] = y;
    q[2] = z;
    mj_forward(world_.model(), world_.data());
    world_.step(30);
  }

  // Samples `n` seeded placements and counts those the checker confirms; a
  // failed sample counts against it.
  int agreement(int n, const std::function<bool(Rng&)>& sample, const std::function<bool()>& check) {
    int sampled = 0, agree = 0;
    for (int seed = 0; seed < n; ++seed) {
      reset();
      Rng rng(seed);
      if (!sample(rng)) continue;
      ++sampled;
      agree += check();
    }
    std::printf("[ agreement] %s: %d sampled, %d of %d confirmed by the checker\n",
                ::testing::UnitTest::GetInstance()->current_test_info()->name(), sampled, agree, n);
    return agree;
  }

  std::shared_ptr<const Scene> scene_;
  World world_;
};

TEST_F(Predicates, KnownStatesOfTheStartingScene) {
  const int apple = object("apple_1"), table = object("table_1"), cabinet = object("cabinet_1");
  world_.step(10);
  EXPECT_TRUE(onfloor(world_, apple, room("living_room_0")));
  EXPECT_FALSE(onfloor(world_, apple, room("kitchen_0")));
  EXPECT_TRUE(inroom(world_, apple, room("living_room_0")));
  EXPECT_TRUE(inroom(world_, cabinet, room("kitchen_0")));
  EXPECT_FALSE(ontop(world_, apple, table));
  EXPECT_FALSE(inside(world_, apple, table));
  EXPECT_FALSE(is_open(world_, cabinet));
  EXPECT_FALSE(nextto(world_, apple, object("cup_1")));        // 30 cm apart: far for their size
  put(object("cup_1"), 1.0 + 0.04 + 0.035 + 0.01, -0.2, 0.0);  // 1 cm gap
  EXPECT_TRUE(nextto(world_, apple, object("cup_1")));
}

TEST_F(Predicates, HandPlacedStates) {
  const int apple = object("apple_1"), table = object("table_1"), cup = object("cup_1");
  put(apple, 1.5, 1.5, 0.76);  // on the table top (0.75 m)
  EXPECT_TRUE(ontop(world_, apple, table));
  EXPECT_TRUE(touching(world_, apple, table));
  EXPECT_FALSE(under(world_, apple, table));
  put(cup, 1.5, 1.5, 0.0);  // on the floor below it
  EXPECT_TRUE(under(world_, cup, table));
  EXPECT_FALSE(ontop(world_, cup, table));
  EXPECT_FALSE(nextto(world_, cup, object("trash_bin_1")));
  put(cup, 1.5, -1.5, 0.03);  // dropped into the bin
  EXPECT_TRUE(inside(world_, cup, object("trash_bin_1")));
  // The drawer: open past 5% of its travel.
  const int cabinet = object("cabinet_1");
  const mjModel* m = world_.model();
  const int j = scene_->objects()[cabinet].joints.at(0);
  world_.data()->qpos[m->jnt_qposadr[j]] = 0.1 * m->jnt_range[2 * j + 1];
  mj_forward(world_.model(), world_.data());
  EXPECT_TRUE(is_open(world_, cabinet));
}

TEST_F(Predicates, SamplingFixedObjectsIsAnError) {
  Rng rng(0);
  EXPECT_THROW(sample_ontop(world_, object("table_1"), object("cabinet_1"), rng), Error);
}

// The seed's bar: the checker agrees with the sampler on >= 99% of 1,000
// seeded samples per predicate.
constexpr int kSamples = 1000;
constexpr int kAgreement = 990;

TEST_F(Predicates, OnTopSamplesAreOnTop) {
  const int apple = object("apple_1"), table = object("table_1"), cabinet = object("cabinet_1");
  EXPECT_GE(agreement(
                kSamples, [&](Rng& r) { return sample_ontop(world_, apple, table, r); },
                [&] { return ontop(world_, apple, table); }),
            kAgreement);
  EXPECT_GE(agreement(
                kSamples, [&](Rng& r) { return sample_ontop(world_, apple, cabinet, r); },
                [&] { return ontop(world_, apple, cabinet); }),
            kAgreement);
}

TEST_F(Predicates, InsideSamplesAreInside) {
  const int apple = object("apple_1");
  for (const char* container : {"cabinet_1", "trash_bin_1", "shelf_1"}) {
    const int c = object(container);
    EXPECT_GE(agreement(
                  kSamples, [&](Rng& r) { return sample_inside(world_, apple, c, r); },
                  [&] { return inside(world_, apple, c); }),
              kAgreement)
        << container;
  }
}

TEST_F(Predicates, UnderAndOnFloorSamplesHold) {
  const int cup = object("cup_1"), table = object("table_1");
  EXPECT_GE(agreement(
                kSamples, [&](Rng& r) { return sample_under(world_, cup, table, r); },
                [&] { return under(world_, cup, table); }),
            kAgreement);
  const int kitchen = room("kitchen_0");
  EXPECT_GE(agreement(
                kSamples, [&](Rng& r) { return sample_onfloor(world_, cup, kitchen, r); },
                [&] { return onfloor(world_, cup, kitchen) && inroom(world_, cup, kitchen); }),
            kAgreement);
}

TEST_F(Predicates, OpenAndClosedSamplesHold) {
  const int cabinet = object("cabinet_1");
  EXPECT_EQ(agreement(
                kSamples,
                [&](Rng& r) {
                  sample_open(world_, cabinet, true, r);
                  return true;
                },
                [&] { return is_open(world_, cabinet); }),
            kSamples);
  EXPECT_EQ(agreement(
                kSamples,
                [&](Rng& r) {
                  sample_open(world_, cabinet, false, r);
                  return true;
                },
                [&] { return !is_open(world_, cabinet); }),
            kSamples);
}

}  // namespace
}  // namespace chore
