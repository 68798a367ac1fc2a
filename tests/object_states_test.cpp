#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <array>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "base/error.hpp"
#include "test_util.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"
#include "world/renderer.hpp"
#include "world/sampling.hpp"
#include "world/state_rules.hpp"

namespace chore {
namespace {

class ObjectStatesTest : public ::testing::Test {
 protected:
  ObjectStatesTest() : scene_(Scene::load(test::data_path("scenes/predicate_room.json"))), world_(scene_) {}

  int object(const char* name) const { return static_cast<int>(scene_->find_object(name) - scene_->objects().data()); }
  int floating_switch();
  // Teleports a free object's origin (bottom centre) and lets it settle.
  void put(int o, double x, double y, double z, int steps = 8) {
    const mjModel* m = world_.model();
    const int joint = m->body_jntadr[scene_->objects()[o].body];
    double* q = world_.data()->qpos + m->jnt_qposadr[joint];
    q[0] = x;
    q[1] = y;
    q[2] = z;
    std::fill_n(world_.data()->qvel + m->jnt_dofadr[joint], 6, 0.0);
    mj_forward(world_.model(), world_.data());
    for (int i = 0; i < steps; ++i) world_.step(4);
  }
  // The apple keeps a temperature; the table is a stove, switched by a toggle
  // when `needs_toggle`.
  void make_stove(int apple, int table, bool needs_toggle) {
    ObjectAbilities food;
    food.temperature = true;
    ObjectAbilities stove;
    stove.heat_source = ThermalSource{200, 0.5, 0.05, needs_toggle, false, false};
    stove.toggleable = needs_toggle;
    world_.states().configure(apple, food);
    world_.states().configure(table, stove);
  }
  void run(double seconds) {
    for (int i = 0; i < static_cast<int>(seconds * 30); ++i) world_.step(4);
  }

  std::shared_ptr<const Scene> scene_;
  World world_;
};

TEST_F(ObjectStatesTest, HeatSourceCooksWhatIsNearItAndTheHighestTemperatureIsKept) {
  const int apple = object("apple_1"), table = object("table_1");
  make_stove(apple, table, true);
  put(apple, 1.5, 1.5, 0.76);
  run(2);
  EXPECT_NEAR(world_.states().state(apple).temperature, kRoomTemperature, 1e-9);  // stove off
  world_.states().state(table).toggled = true;
  run(2);
  EXPECT_TRUE(hot(world_, apple));
  EXPECT_TRUE(cooked(world_, apple));
  EXPECT_FALSE(burnt(world_, apple));
  put(apple, 1.0, -0.2, 0.0);  // away from the stove: cools, stays cooked
  const double peak = world_.states().state(apple).max_temperature;
  run(3);
  EXPECT_LT(world_.states().state(apple).temperature, peak);
  EXPECT_EQ(world_.states().state(apple).max_temperature, peak);
  EXPECT_TRUE(cooked(world_, apple));
}

TEST_F(ObjectStatesTest, ObjectStateUpdatesCanBeSwitchedOff) {
  const int apple = object("apple_1"), table = object("table_1");
  make_stove(apple, table, false);
  world_.set_state_updates(false);
  put(apple, 1.5, 1.5, 0.76);
  run(2);
  EXPECT_FALSE(cooked(world_, apple));
}

TEST_F(ObjectStatesTest, WaterInAContainerSoaksWhatEntersIt) {
  const int rag = object("apple_1"), bin = object("trash_bin_1");
  ObjectAbilities cloth;
  cloth.soakable = true;
  ObjectAbilities bucket;
  bucket.holds_liquid = true;
  world_.states().configure(rag, cloth);
  world_.states().configure(bin, bucket);
  put(rag, 1.5, -1.5, 0.03);  // in the (dry) bin
  run(1);
  EXPECT_FALSE(soaked(world_, rag));
  sample_state(world_, "filled", bin, true);
  EXPECT_TRUE(filled(world_, bin));
  run(0.3);
  EXPECT_TRUE(soaked(world_, rag));
  EXPECT_FALSE(saturated(world_, rag));
  run(0.5);
  EXPECT_TRUE(saturated(world_, rag));
  // Levels are kept per liquid: a bin of oil soaks in oil, not water.
  world_.reset(scene_->robot_start());
  sample_state(world_, "filled", bin, true, "oil");
  EXPECT_TRUE(filled(world_, bin, "oil"));
  EXPECT_TRUE(contains(world_, bin, "oil"));
  EXPECT_FALSE(filled(world_, bin, "water"));
  // contains asks for any of it, filled for a fifth of the height (OmniGibson's).
  sample_state(world_, "contains", bin, true, "oil");
  EXPECT_TRUE(contains(world_, bin, "oil"));
  EXPECT_FALSE(filled(world_, bin, "oil"));
  sample_state(world_, "contains", bin, false, "water");  // holds no water: the oil stays
  EXPECT_TRUE(contains(world_, bin, "oil"));
  sample_state(world_, "filled", bin, true, "oil");
  put(rag, 1.5, -1.5, 0.03);
  run(1);
  EXPECT_TRUE(soaked(world_, rag, "oil"));
  EXPECT_FALSE(soaked(world_, rag, "water"));
}

TEST_F(ObjectStatesTest, ASoakedCleaningToolWipesStainsOffAndADryOneDoesNot) {
  const int tool = object("cup_1"), table = object("table_1");
  ObjectAbilities cleaner;
  cleaner.cleaning_tool = true;
  cleaner.soakable = true;
  ObjectAbilities surface;
  surface.covered = true;
  world_.states().configure(tool, cleaner);
  world_.states().configure(table, surface);
  world_.states().add_substance({"stain", true});
  Rng rng(1);
  ASSERT_TRUE(sample_covered(world_, table, "stain", true, rng));
  EXPECT_TRUE(covered(world_, table, "stain"));
  // Sweep the tool over the whole top, dry, then soaked.
  auto sweep = [&] {
    for (double x = 1.0; x <= 2.0; x += 0.05) {
      for (double y = 1.2; y <= 1.8; y += 0.05) put(tool, x, y, 0.75, 1);
    }
  };
  sweep();
  EXPECT_EQ(world_.states().state(table).dirt["stain"].size(), 20u);
  sample_state(world_, "soaked", tool, true);
  sweep();
  EXPECT_FALSE(covered(world_, table, "stain"));
}

// OmniGibson's texture change, albedo = tint * (albedo + add): a soaked rag
// turns blue, a cooked apple brown, a burnt one dark, a frozen one white, in
// that order of precedence; untouched objects keep their colour.
TEST_F(ObjectStatesTest, SoakedCookedBurntAndFrozenObjectsChangeColourAsInOmniGibson) {
  const int rag = object("rag_1"), apple = object("apple_1"), cup = object("cup_1");
  ObjectAbilities cloth;
  cloth.soakable = true;
  ObjectAbilities food;
  food.temperature = true;
  world_.states().configure(rag, cloth);
  world_.states().configure(apple, food);
  world_.states().configure(cup, food);
  const mjModel* m = world_.model();
  mjvScene scene;
  mjv_defaultScene(&scene);
  mjv_makeScene(m, &scene, 4000);
  mjvOption option;
  mjv_defaultOption(&option);
  mjvCamera camera;
  mjv_defaultCamera(&camera);
  // Each geom of `object` in a drawn scene: its colour, and the model's.
  auto drawn = [&](int object) {
    mjv_updateScene(m, world_.data(), &option, nullptr, &camera, mjCAT_ALL, &scene);
    draw_states(world_, &scene);
    std::vector<std::pair<std::array<float, 3>, std::array<float, 3>>> colours;
    for (int i = 0; i < scene.ngeom; ++i) {
      const mjvGeom& g = scene.geoms[i];
      if (g.objtype != mjOBJ_GEOM || scene_->object_of_geom(g.objid) != object) continue;
      const float* own = m->geom_rgba + 4 * g.objid;
      colours.push_back({{g.rgba[0], g.rgba[1], g.rgba[2]}, {own[0], own[1], own[2]}});
    }
    return colours;
  };
  auto expect_change = [&](int object, float add, std::array<float, 3> tint, const char* what) {
    const auto colours = drawn(object);
    ASSERT_FALSE(colours.empty()) << what;
    for (const auto& [seen, own] : colours) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_FLOAT_EQ(seen[c], std::clamp(tint[c] * (own[c] + add), 0.0f, 1.0f)) << what << " channel " << c;
      }
    }
  };
  expect_change(rag, 0, {1, 1, 1}, "dry rag");
  expect_change(apple, 0, {1, 1, 1}, "apple at room temperature");
  sample_state(world_, "soaked", rag, true);
  expect_change(rag, 0.1f, {0.5f, 0.5f, 1.5f}, "soaked rag");  // water has no colour: blue
  world_.states().state(apple).max_temperature = 100;
  expect_change(apple, 0.1f, {1.5f, 0.75f, 0.25f}, "cooked apple");
  world_.states().state(cup).max_temperature = 250;
  expect_change(cup, -0.3f, {1, 1, 1}, "burnt cup");
  world_.states().state(apple).temperature = -5;
  expect_change(apple, 0.3f, {1, 1, 1}, "frozen (and cooked) apple");
  mjv_freeScene(&scene);

  // And the picture shows it: the rag from above, dry and soaked.
  const int size = 512;
  Renderer renderer(m, size, size, 1);
  std::vector<std::uint8_t> rgb(size * size * 3);
  std::vector<std::int32_t> segment(size * size);
  auto rag_colour = [&](const char* png) {
    const CameraView view{m,       world_.data(), scene_->overview_camera(), rgb.data(), nullptr, 0, false,
                          &world_, segment.data()};
    renderer.render({&view, 1});
    cv::Mat bgr;
    cv::cvtColor(cv::Mat(size, size, CV_8UC3, rgb.data()), bgr, cv::COLOR_RGB2BGR);
    cv::imwrite((test::output_dir() / png).string(), bgr);
    std::array<double, 3> sum{};
    int pixels = 0;
    for (int i = 0; i < size * size; ++i) {
      if (segment[i] < 0 || scene_->object_of_body(m->geom_bodyid[segment[i]]) != rag) continue;
      for (int c = 0; c < 3; ++c) sum[c] += rgb[3 * i + c];
      ++pixels;
    }
    EXPECT_GT(pixels, 10) << png;
    for (double& c : sum) c /= std::max(pixels, 1);
    return sum;
  };
  const auto soaked_rag = rag_colour("soaked_rag_from_above.png");
  sample_state(world_, "soaked", rag, false);
  const auto dry_rag = rag_colour("dry_rag_from_above.png");
  // Light blue (0.45, 0.65, 0.85) to (0.275, 0.375, 1): red and green fall by
  // about 0.6, blue rises.
  EXPECT_NEAR(soaked_rag[0] / dry_rag[0], 0.61, 0.1);
  EXPECT_NEAR(soaked_rag[1] / dry_rag[1], 0.58, 0.1);
  EXPECT_GT(soaked_rag[2], dry_rag[2]);
}

// iGibson's stained/dusty: dirty while more than half of the particles sampled
// remain; OmniGibson's covered: while at least five do.
TEST_F(ObjectStatesTest, StainedClearsAtHalfTheParticlesCoveredAtFewerThanFive) {
  const int table = object("table_1");
  ObjectAbilities surface;
  surface.covered = true;
  world_.states().configure(table, surface);
  Rng rng(2);
  ASSERT_TRUE(sample_covered(world_, table, "stain", true, rng));
  std::vector<Eigen::Vector3d>& dirt = world_.states().state(table).dirt["stain"];
  ASSERT_EQ(dirt.size(), 20u);
  dirt.resize(11);
  EXPECT_TRUE(dirty(world_, table, "stain"));
  dirt.resize(10);
  EXPECT_FALSE(dirty(world_, table, "stain"));
  EXPECT_TRUE(covered(world_, table, "stain"));
  dirt.resize(4);
  EXPECT_FALSE(covered(world_, table, "stain"));
  // Sampling clean leaves nothing dirty, whatever was sampled before.
  sample_covered(world_, table, "stain", false, rng);
  EXPECT_FALSE(dirty(world_, table, "stain"));
}

TEST_F(ObjectStatesTest, HardImpactsBreakAndAPressedSlicerSlices) {
  const int apple = object("apple_1"), cup = object("cup_1");
  ObjectAbilities fragile;
  fragile.breakable = true;
  fragile.break_force = 40;
  fragile.sliceable = true;
  fragile.slice_force = 0.5;
  ObjectAbilities knife;
  knife.slicer = true;
  world_.states().configure(apple, fragile);
  put(apple, 1.0, -0.2, 0.0);  // set down gently
  EXPECT_FALSE(broken(world_, apple));
  put(apple, 1.0, -0.2, 2.0, 0);  // dropped from 2 m
  run(1);
  EXPECT_TRUE(broken(world_, apple));
  put(cup, 1.0, -0.2, 0.09);  // resting on the apple, not a slicer
  EXPECT_FALSE(sliced(world_, apple));
  world_.states().configure(cup, knife);
  put(cup, 1.0, -0.2, 0.09);
  EXPECT_TRUE(sliced(world_, apple));
}

// The apple as a switch that floats where it is put, near the hand without
// touching it: no gravity, no contacts.
int ObjectStatesTest::floating_switch() {
  const int apple = object("apple_1");
  ObjectAbilities lamp;
  lamp.toggleable = true;
  world_.states().configure(apple, lamp);
  world_.model()->opt.gravity[2] = 0;
  for (int g : scene_->objects()[apple].geoms) {
    world_.model()->geom_contype[g] = world_.model()->geom_conaffinity[g] = 0;
  }
  return apple;
}

TEST_F(ObjectStatesTest, TheHandAtTheTogglePointForFiveStepsToggles) {
  const int apple = floating_switch();
  const double* hand = world_.data()->site_xpos + 3 * world_.robot()->gripper_site;
  put(apple, hand[0], hand[1], hand[2] - 0.12, 0);  // top 4 cm below the hand
  for (int i = 0; i < 4; ++i) world_.step(4);
  EXPECT_FALSE(toggled_on(world_, apple));
  world_.step(4);
  EXPECT_TRUE(toggled_on(world_, apple));
  for (int i = 0; i < 10; ++i) world_.step(4);  // staying does not toggle it back
  EXPECT_TRUE(toggled_on(world_, apple));
}

// The fingers press, not the hand's centre (OmniGibson's ToggledOn counts a
// robot's finger links near the toggle marker): the toggle point 13 cm ahead
// of the hand's centre along its fingers (9 cm from the fingertips) toggles
// the object; as far behind the hand it does not.
TEST_F(ObjectStatesTest, TheFingersNotTheHandsCentreReachTheTogglePoint) {
  const int apple = floating_switch();
  const int site = world_.robot()->gripper_site;
  const Eigen::Vector3d hand(world_.data()->site_xpos + 3 * site);
  const double* frame = world_.data()->site_xmat + 9 * site;
  const Eigen::Vector3d fingers(frame[0], frame[3], frame[6]);
  put(apple, hand.x(), hand.y(), hand.z() - 1.0, 0);
  const Eigen::Vector3d origin(hand.x(), hand.y(), hand.z() - 1.0);
  const Eigen::Vector3d top = toggle_point(world_, apple) - origin;
  for (const double side : {-1.0, 1.0}) {
    SCOPED_TRACE(side > 0 ? "ahead" : "behind");
    const Eigen::Vector3d at = hand + side * 0.13 * fingers - top;
    put(apple, at.x(), at.y(), at.z(), 0);
    ASSERT_NEAR((toggle_point(world_, apple) - hand).norm(), 0.13, 1e-6);
    for (int i = 0; i < 8; ++i) world_.step(4);
    EXPECT_EQ(toggled_on(world_, apple), side > 0);
  }
}

TEST_F(ObjectStatesTest, StateSamplersAgreeWithTheCheckers) {
  const int apple = object("apple_1"), bin = object("trash_bin_1");
  ObjectAbilities all;
  all.temperature = true;
  all.ignition_temperature = 300;
  all.soakable = all.toggleable = all.sliceable = all.breakable = true;
  ObjectAbilities bucket;
  bucket.holds_liquid = true;
  world_.states().configure(apple, all);
  world_.states().configure(bin, bucket);
  const std::vector<std::pair<std::string, bool (*)(const World&, int)>> checks = {
      {"cooked", cooked},
      {"burnt", burnt},
      {"frozen", frozen},
      {"hot", hot},
      {"on_fire", on_fire},
      {"soaked", [](const World& w, int a) { return soaked(w, a); }},
      {"saturated", [](const World& w, int a) { return saturated(w, a); }},
      {"toggled_on", toggled_on},
      {"sliced", sliced},
      {"broken", broken}};
  // 1,000 seeded samples per predicate, each of a random truth value.
  for (const auto& [name, check] : checks) {
    int agree = 0;
    for (int seed = 0; seed < 1000; ++seed) {
      Rng rng(seed);
      const bool value = uniform(rng, 0, 1) < 0.5;
      sample_state(world_, name, apple, value);
      agree += check(world_, apple) == value;
    }
    EXPECT_EQ(agree, 1000) << name;
  }
  sample_state(world_, "filled", bin, true);
  EXPECT_TRUE(filled(world_, bin));
  sample_state(world_, "filled", bin, false);
  EXPECT_FALSE(filled(world_, bin));
  EXPECT_THROW(sample_state(world_, "cooked", object("cup_1"), true), Error);  // keeps no temperature
  EXPECT_THROW(sample_state(world_, "levitating", apple, true), Error);
}

TEST_F(ObjectStatesTest, CoveredSamplesAreCovered) {
  const int table = object("table_1");
  ObjectAbilities surface;
  surface.covered = true;
  world_.states().configure(table, surface);
  int agree = 0;
  for (int seed = 0; seed < 1000; ++seed) {
    Rng rng(seed);
    agree += sample_covered(world_, table, "dust", true, rng) && covered(world_, table, "dust");
  }
  EXPECT_GE(agree, 990);
  Rng rng(0);
  sample_covered(world_, table, "dust", false, rng);
  EXPECT_FALSE(covered(world_, table, "dust"));
}

}  // namespace
}  // namespace chore

namespace chore {
namespace {

TEST(Cloth, ARagIsOneObjectOfManyBodiesThatDrapesOverAnEdge) {
  auto scene = Scene::load(test::data_path("scenes/predicate_room.json"));
  const SceneObject* rag = scene->find_object("rag_1");
  ASSERT_NE(rag, nullptr);
  const mjModel* m = scene->model();
  int bodies = 0;
  for (int b = 0; b < m->nbody; ++b)
    bodies += scene->object_of_body(b) == static_cast<int>(rag - scene->objects().data());
  EXPECT_EQ(bodies, 9);  // a 3 x 3 composite, rooted at its centre
  // One column of tiles past the table's edge (the top is 0.75 m high, its +x
  // edge at x = 2.1; tiles are 7 cm apart).
  World world(scene);
  const int joint = m->body_jntadr[rag->body];
  double* q = world.data()->qpos + m->jnt_qposadr[joint];
  q[0] = 2.06;
  q[1] = 1.5;
  q[2] = 0.77;
  mj_forward(world.model(), world.data());
  for (int i = 0; i < 60; ++i) world.step(4);
  double lowest = 1e9, highest = -1e9;
  for (int b = 0; b < m->nbody; ++b) {
    if (m->body_rootid[b] != rag->body) continue;
    lowest = std::min(lowest, world.data()->xpos[3 * b + 2]);
    highest = std::max(highest, world.data()->xpos[3 * b + 2]);
  }
  // The part on the table lies flat on it; the column past the edge bends
  // down (a rigid board with a third over the edge would stay level).
  EXPECT_NEAR(highest, 0.756, 0.005);
  EXPECT_LT(lowest, highest - 0.01);
  // Draped over the table's edge (6 cm down), but covering little of the
  // table: not overlaid.
  const auto index_of = [&](const char* name) {
    return static_cast<int>(scene->find_object(name) - scene->objects().data());
  };
  EXPECT_TRUE(draped(world, index_of("rag_1"), index_of("table_1")));
  EXPECT_FALSE(overlaid(world, index_of("rag_1"), index_of("table_1")));
  EXPECT_FALSE(draped(world, index_of("apple_1"), index_of("table_1"))) << "not a cloth";
  // Keypoints: the draped rag is still spread out; curled up, it is folded.
  const int index = static_cast<int>(rag - scene->objects().data());
  EXPECT_TRUE(unfolded(world, index));
  EXPECT_FALSE(folded(world, index));
  // Fold both side columns up about their hinges to the centre column.
  world.data()->qpos[m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, "rag_1J0_2_1")]] = 1.5;
  world.data()->qpos[m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, "rag_1J0_0_1")]] = -1.5;
  mj_forward(world.model(), world.data());
  EXPECT_TRUE(folded(world, index));
  EXPECT_FALSE(unfolded(world, index));
  // Dropped over a cup, it covers all of the cup's top: overlaid.
  world.reset(scene->robot_start());
  const double* cup = world.data()->xpos + 3 * scene->find_object("cup_1")->body;
  q[0] = cup[0], q[1] = cup[1], q[2] = object_aabb(world, index_of("cup_1")).hi.z() + 0.02;
  mj_forward(world.model(), world.data());
  for (int i = 0; i < 60; ++i) world.step(4);
  EXPECT_TRUE(overlaid(world, index_of("rag_1"), index_of("cup_1")));
  // With cloth off, the same rag is one rigid body.
  SceneOptions rigid;
  rigid.cloth = false;
  auto flat = Scene::load(test::data_path("scenes/predicate_room.json"), rigid);
  EXPECT_EQ(flat->model()->nbody, m->nbody - 8);
}

}  // namespace
}  // namespace chore
