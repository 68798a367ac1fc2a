// Generated object models (analogs/category_models.hpp): archetypes chosen by
// the knowledge base, sizes from the nearest ancestor's entry scaled by mass,
// and models that compile and stand still on a floor.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "analogs/activity_scenes.hpp"
#include "analogs/category_models.hpp"
#include "analogs/scene_analogs.hpp"
#include "base/error.hpp"
#include "env/env.hpp"
#include "env/env_impl.hpp"
#include "tasks/activity.hpp"
#include "tasks/vocabulary.hpp"
#include "test_util.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"
#include "world/renderer.hpp"
#include "world/scene.hpp"
#include "world/world.hpp"

namespace chore {
namespace {

namespace fs = std::filesystem;

const CategoryModels& shipped() {
  return *CategoryModels::shipped();
}

TEST(CategoryModels, ArchetypesFollowTheKnowledgeBase) {
  const std::pair<const char*, Archetype> expected[] = {
      {"cabinet.n.01", Archetype::cabinet},
      {"sink.n.01", Archetype::basin},
      {"towel.n.01", Archetype::cloth},
      {"apple.n.01", Archetype::ball},
      {"bowl.n.01", Archetype::open_container},
      {"door.n.01", Archetype::door},
      {"sofa.n.01", Archetype::seat},
      {"bed.n.01", Archetype::bed},
      {"shelf.n.01", Archetype::shelf},
      {"breakfast_table.n.01", Archetype::table},
      {"hammer.n.02", Archetype::block},
      // Fillable furniture taller than wide holds things on shelves (it was
      // a basin on a 1.5 m stand); a swimming pool stays a basin.
      {"grocery_shelf.n.01", Archetype::shelf},
      {"wardrobe.n.01", Archetype::shelf},
      {"swimming_pool.n.01", Archetype::basin},
  };
  for (const auto& [synset, archetype] : expected) {
    EXPECT_EQ(to_string(shipped().archetype(synset)), std::string(to_string(archetype))) << synset;
  }
  EXPECT_THROW(shipped().model("water.n.06"), Error);  // a substance
  try {
    shipped().model("cabinet.n.99");
    ADD_FAILURE() << "an unknown synset was given a model";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cabinet.n.01"), std::string::npos) << e.what();  // did you mean
  }
}

// A size table of three entries, with the shipped masses: a synset takes its
// nearest ancestor's entry, scaled by the cube root of its own mass over the
// entry's, clamped to [0.5, 2]; without a mass of its own, the entry as is.
TEST(CategoryModels, SizesComeFromTheNearestAncestorScaledByMass) {
  const fs::path dir = test::scratch_dir("category_sizes");
  std::ofstream(dir / "sizes.json") << R"({"sizes": {
      "entity.n.01": {"size": [0.1, 0.1, 0.1], "mass": 1.0},
      "edible_fruit.n.01": {"size": [0.08, 0.08, 0.09], "mass": 0.2},
      "apple.n.01": {"size": [0.07, 0.07, 0.07], "mass": 0.15}}})";
  const auto kb = KnowledgeBase::load(default_tasks_dir() + "/kb/behavior-1k");
  const auto models = CategoryModels::load(kb, (dir / "sizes.json").string(),
                                           default_tasks_dir() + "/kb/behavior-1k/category_mapping.csv");
  // Its own entry: as written, whatever its mass.
  EXPECT_EQ(models->size_entry("apple.n.01"), "apple.n.01");
  EXPECT_TRUE(models->size("apple.n.01").isApprox(Eigen::Vector3d(0.07, 0.07, 0.07)));
  EXPECT_NEAR(models->mass("apple.n.01"), 0.163, 1e-12);  // BEHAVIOR's annotation
  // A banana is an edible fruit: that entry, scaled by (0.12 / 0.2)^(1/3).
  ASSERT_TRUE(kb->is_a("banana.n.02", "edible_fruit.n.01"));
  EXPECT_EQ(models->size_entry("banana.n.02"), "edible_fruit.n.01");
  const double banana = models->mass("banana.n.02");
  EXPECT_TRUE(models->size("banana.n.02").isApprox(Eigen::Vector3d(0.08, 0.08, 0.09) * std::cbrt(banana / 0.2)))
      << models->size("banana.n.02").transpose() << " for " << banana << " kg";
  // A sofa (~50 kg) under the root's 1 kg entry: scaled by the clamp, 2.
  EXPECT_EQ(models->size_entry("sofa.n.01"), "entity.n.01");
  EXPECT_GT(models->mass("sofa.n.01"), 8.0);
  EXPECT_TRUE(models->size("sofa.n.01").isApprox(Eigen::Vector3d(0.2, 0.2, 0.2)));

  // A table naming a synset the knowledge base lacks, or without the root.
  std::ofstream(dir / "bad.json") << R"({"sizes": {"entity.n.01": {"size": [0.1, 0.1, 0.1], "mass": 1},
      "aple.n.01": {"size": [0.1, 0.1, 0.1], "mass": 1}}})";
  EXPECT_THROW(CategoryModels::load(kb, (dir / "bad.json").string(),
                                    default_tasks_dir() + "/kb/behavior-1k/category_mapping.csv"),
               Error);
  std::ofstream(dir / "rootless.json") << R"({"sizes": {"apple.n.01": {"size": [0.1, 0.1, 0.1], "mass": 1}}})";
  EXPECT_THROW(CategoryModels::load(kb, (dir / "rootless.json").string(),
                                    default_tasks_dir() + "/kb/behavior-1k/category_mapping.csv"),
               Error);
}

TEST(CategoryModels, CategoriesHaveColoursOfTheirOwn) {
  const KnowledgeBase& kb = shipped().knowledge_base();
  std::vector<Rgb> colours;
  for (const std::string& s : kb.children("fruit.n.01")) {
    if (!kb.is_substance(s)) colours.push_back(shipped().colour(s));
  }
  ASSERT_GT(colours.size(), 5u);
  for (size_t i = 0; i < colours.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      const double d =
          std::hypot(colours[i][0] - colours[j][0], colours[i][1] - colours[j][1], colours[i][2] - colours[j][2]);
      EXPECT_GT(d, 0.02) << i << " and " << j;
    }
  }
  EXPECT_EQ(shipped().colour("apple.n.01"), shipped().colour("apple.n.01"));
}

// One model of each archetype, free on a floor (furniture fixed): compiled
// into a scene, they stand where placed after a second of physics, and the
// openable ones open.
TEST(CategoryModels, ModelsCompileAndStandOnTheFloor) {
  const std::vector<std::string> synsets = {
      "cabinet.n.01", "sink.n.01",       "towel.n.01",  "apple.n.01", "bowl.n.01",
      "door.n.01",    "sofa.n.01",       "bed.n.01",    "shelf.n.01", "breakfast_table.n.01",
      "hammer.n.02",  "dishwasher.n.01", "carton.n.02", "chair.n.01"};
  SceneFile file;
  file.name = "category_models";
  // A grid of 2.5 m cells, four to a row, each lit from above.
  constexpr double kCell = 2.5;
  const int rows = static_cast<int>(synsets.size() + 3) / 4;
  file.rooms.push_back({"living_room_0", "living_room", {{-1, -1, 4 * kCell, rows * kCell}}});
  std::set<Archetype> archetypes;
  for (size_t i = 0; i < synsets.size(); ++i) {
    const std::string& s = synsets[i];
    const ObjectModel model = shipped().model(s);
    archetypes.insert(shipped().archetype(s));
    ObjectPlacement p;
    p.name = model.category + "_1";
    p.model = s;
    p.synset = s;
    p.fixed = shipped().knowledge_base().has_property(s, "sceneObject");
    p.pos = {(i % 4 + 0.5) * kCell, (i / 4 + 0.5) * kCell, 0};
    file.models[s] = model;
    file.objects.push_back(p);
    file.ceiling_lights.push_back({{p.pos.x(), p.pos.y(), 2.5}, {0.4, 0.4, 0.4}});
  }
  EXPECT_EQ(archetypes.size(), 12u);  // every archetype
  file.robot_start = {-0.5, -0.5, 0};
  const auto scene = Scene::build(file);
  World world(scene);
  world.reset(scene->robot_start());
  world.step(120);
  const mjData* d = world.data();
  for (size_t i = 0; i < scene->objects().size(); ++i) {
    const SceneObject& o = scene->objects()[i];
    if (o.body < 0) continue;
    const Eigen::Vector3d at(d->xpos[3 * o.body], d->xpos[3 * o.body + 1], d->xpos[3 * o.body + 2]);
    EXPECT_LT((at.head<2>() - Eigen::Vector2d(o.pos[0], o.pos[1])).norm(), 0.05) << o.name << " slid";
    EXPECT_GT(at.z(), -0.01) << o.name << " fell through the floor";
  }
  // From above (test_output/category_models_overview.png): each model's own
  // colour shows, not a flat or black picture.
  constexpr int kSize = 512;
  Renderer top(scene->model(), kSize, kSize, 1);
  std::vector<std::uint8_t> rgb(kSize * kSize * 3);
  std::vector<CameraView> view = {
      {scene->model(), world.data(), scene->overview_camera(), rgb.data(), nullptr, 0, false}};
  top.render(view);
  cv::Mat bgr;
  cv::cvtColor(cv::Mat(kSize, kSize, CV_8UC3, rgb.data()), bgr, cv::COLOR_RGB2BGR);
  cv::imwrite((test::output_dir() / "category_models_overview.png").string(), bgr);
  std::set<int> colours;
  for (size_t i = 0; i + 2 < rgb.size(); i += 3)
    colours.insert((rgb[i] >> 4) << 8 | (rgb[i + 1] >> 4) << 4 | rgb[i + 2] >> 4);
  EXPECT_GT(colours.size(), 40u);

  for (const char* name : {"cabinet_1", "door_1", "carton_1", "dishwasher_1"}) {
    const SceneObject* o = scene->find_object(name);
    ASSERT_NE(o, nullptr) << name;
    EXPECT_EQ(o->joints.size(), 1u) << name << " has no door, drawer or lid";
    EXPECT_FALSE(is_open(world, static_cast<int>(o - scene->objects().data()))) << name;
  }
}

// A sink's basin and a cabinet's drawer stand on solid stands, 0.3 m deep
// (the hand pointing down reaches into them): a basin the sink's full height
// and a drawer the cabinet's kept what lay in them 2-4 cm above the floor, out
// of every reach. Deeper where an activity puts something taller in (a sack
// of sugar 0.8 m tall in a kitchen drawer).
TEST(CategoryModels, WhatASinkADrawerOrAnOvenHoldsLiesWithinReach) {
  SceneFile file;
  file.name = "basins";
  file.rooms.push_back({"kitchen_0", "kitchen", {{-1, -1, 5, 3}}});
  // A kitchen's base cabinet, wider than tall: a drawer; the same with a sack
  // inside; an oven (a door before one space: its bottom halfway up).
  const std::vector<std::string> synsets = {"sink.n.01", "cabinet.n.01", "cabinet.n.01", "oven.n.01"};
  const std::vector<Eigen::Vector3d> sizes = {
      shipped().size("sink.n.01"), {1.1, 0.6, 0.9}, {1.1, 0.6, 0.9}, shipped().size("oven.n.01")};
  const std::vector<double> inner = {0, 0, 0.85, 0};
  for (size_t i = 0; i < synsets.size(); ++i) {
    const ObjectModel model = shipped().model(synsets[i], sizes[i], inner[i]);
    ObjectPlacement p;
    p.name = model.category + "_" + std::to_string(i);
    p.model = p.synset = synsets[i];
    p.fixed = true;
    p.pos = {1.0 + 2.5 * i, 1.0, 0};
    p.model = p.name;
    file.models[p.name] = model;
    file.objects.push_back(p);
  }
  file.robot_start = {-0.5, -0.5, 0};
  const auto scene = Scene::build(file);
  World world(scene);
  world.reset(scene->robot_start());
  ASSERT_EQ(scene->objects()[1].joints.size(), 1u);
  std::vector<double> floors;
  for (size_t i = 0; i < synsets.size(); ++i) {
    const Aabb box = object_aabb(world, static_cast<int>(i));
    ASSERT_GT(box.hi.z(), 0.6) << synsets[i];
    // Down from under the top (a drawer's carcass has one) at the centre.
    const mjtNum from[3] = {box.center().x(), box.center().y(), box.hi.z() - 0.03}, down[3] = {0, 0, -1};
    int geom = -1;
    mjtByte colliding[mjNGROUP] = {};  // not the visual geoms
    colliding[kStaticGroup] = colliding[kCollisionGroup] = 1;
    const double depth = mj_ray(world.model(), world.data(), from, down, colliding, 1, -1, &geom, nullptr);
    ASSERT_GE(depth, 0) << synsets[i];
    EXPECT_EQ(scene->object_of_geom(geom), static_cast<int>(i)) << synsets[i];
    floors.push_back(box.hi.z() - 0.03 - depth);
  }
  EXPECT_GT(floors[0], shipped().size("sink.n.01").z() - 0.33);
  EXPECT_GT(floors[1], 0.9 - 0.37);
  EXPECT_LT(floors[2], 0.9 - 0.85);
  EXPECT_GT(floors[3], shipped().size("oven.n.01").z() / 2 - 0.01);
}

TEST(SceneAnalogs, InventoriesGiveRoomsAndSynsetCounts) {
  const SceneInventory& rs = find_scene_inventory("Rs_int");
  std::map<std::string, const RoomInventory*> rooms;
  for (const RoomInventory& r : rs.rooms) rooms[r.name] = &r;
  ASSERT_EQ(rooms.size(), 5u);
  ASSERT_TRUE(rooms.contains("kitchen_0"));
  EXPECT_EQ(rooms["kitchen_0"]->type, "kitchen");
  const auto& kitchen = rooms["kitchen_0"]->objects;
  const auto count = [&](const std::string& synset) {
    for (const auto& [s, n] : kitchen)
      if (s == synset) return n;
    return 0;
  };
  EXPECT_EQ(count("cabinet.n.01"), 7);  // bottom and top cabinets, one synset
  EXPECT_EQ(count("electric_refrigerator.n.01"), 1);
  EXPECT_EQ(rs.object_count(), 76);
  EXPECT_GE(shipped_scene_inventories().size(), 50u);
  EXPECT_THROW(find_scene_inventory("Rs"), Error);
}

// Rasterises the walls at 5 cm and floods the floor from the robot's start:
// every room must be reached through the doorways.
std::set<std::string> rooms_reached(const SceneFile& f) {
  constexpr double kCell = 0.05;
  double x1 = 0, y1 = 0;
  for (const Room& r : f.rooms) x1 = std::max(x1, r.rects[0][2]), y1 = std::max(y1, r.rects[0][3]);
  const int nx = static_cast<int>(x1 / kCell) + 1, ny = static_cast<int>(y1 / kCell) + 1;
  std::vector<char> blocked(nx * ny, 0);
  for (const auto& w : f.walls) {
    const int steps = static_cast<int>(std::hypot(w[2] - w[0], w[3] - w[1]) / (kCell / 2)) + 1;
    for (int i = 0; i <= steps; ++i) {
      const double x = w[0] + (w[2] - w[0]) * i / steps, y = w[1] + (w[3] - w[1]) * i / steps;
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy) {
          const int cx = static_cast<int>(x / kCell) + dx, cy = static_cast<int>(y / kCell) + dy;
          if (cx >= 0 && cy >= 0 && cx < nx && cy < ny) blocked[cy * nx + cx] = 1;
        }
    }
  }
  std::vector<char> seen(nx * ny, 0);
  std::vector<int> stack = {static_cast<int>(f.robot_start.y / kCell) * nx + static_cast<int>(f.robot_start.x / kCell)};
  std::set<std::string> reached;
  while (!stack.empty()) {
    const int c = stack.back();
    stack.pop_back();
    if (seen[c] || blocked[c]) continue;
    seen[c] = 1;
    const int cx = c % nx, cy = c / nx;
    for (const Room& r : f.rooms) {
      const auto& b = r.rects[0];
      if ((cx + 0.5) * kCell > b[0] && (cx + 0.5) * kCell < b[2] && (cy + 0.5) * kCell > b[1] &&
          (cy + 0.5) * kCell < b[3])
        reached.insert(r.name);
    }
    if (cx > 0) stack.push_back(c - 1);
    if (cx + 1 < nx) stack.push_back(c + 1);
    if (cy > 0) stack.push_back(c - nx);
    if (cy + 1 < ny) stack.push_back(c + nx);
  }
  return reached;
}

TEST(SceneAnalogs, AreSeededConnectedAndCollisionFree) {
  const CategoryModels& models = shipped();
  const SceneInventory& inventory = find_scene_inventory("Rs_int");
  const SceneAnalog a = generate_scene_analog(inventory, models, 0), b = generate_scene_analog(inventory, models, 0),
                    c = generate_scene_analog(inventory, models, 1);
  ASSERT_EQ(a.file.objects.size(), b.file.objects.size());
  bool same_as_seed_1 = a.file.objects.size() == c.file.objects.size();
  for (size_t i = 0; i < a.file.objects.size(); ++i) {
    EXPECT_EQ(a.file.objects[i].name, b.file.objects[i].name);
    EXPECT_EQ(a.file.objects[i].pos, b.file.objects[i].pos) << a.file.objects[i].name;
    same_as_seed_1 = same_as_seed_1 && a.file.objects[i].pos == c.file.objects[i].pos;
  }
  EXPECT_FALSE(same_as_seed_1);
  // Every inventory object but the floors and ceilings is placed or counted.
  int structure = 0;
  for (const RoomInventory& r : inventory.rooms)
    for (const auto& [synset, n] : r.objects) structure += synset == "floor.n.01" || synset == "ceiling.n.01" ? n : 0;
  EXPECT_EQ(a.placed + a.left_out + structure, inventory.object_count());
  EXPECT_EQ(a.left_out, 0);

  // Rooms tile one rectangle without overlap; each is reached from the robot's start.
  double area = 0, x1 = 0, y1 = 0;
  for (const Room& r : a.file.rooms) {
    const auto& q = r.rects[0];
    area += (q[2] - q[0]) * (q[3] - q[1]);
    x1 = std::max(x1, q[2]), y1 = std::max(y1, q[3]);
  }
  EXPECT_NEAR(area, x1 * y1, 1e-6);
  EXPECT_EQ(rooms_reached(a.file).size(), a.file.rooms.size());

  // Fixed furniture on the floor: footprints apart, inside its room's walls.
  struct Box {
    std::string name;
    double x0, y0, x1, y1;
  };
  std::vector<Box> boxes;
  for (const ObjectPlacement& o : a.file.objects) {
    if (!o.fixed || o.pos.z() > 0.01) continue;
    const Eigen::Vector3d s = models.size(o.synset);
    const bool turned = std::abs(std::sin(o.yaw)) > 0.5;
    const double hx = (turned ? s.y() : s.x()) / 2, hy = (turned ? s.x() : s.y()) / 2;
    boxes.push_back({o.name, o.pos.x() - hx, o.pos.y() - hy, o.pos.x() + hx, o.pos.y() + hy});
  }
  ASSERT_GT(boxes.size(), 10u);
  for (size_t i = 0; i < boxes.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      const Box &p = boxes[i], &q = boxes[j];
      EXPECT_FALSE(p.x0 < q.x1 - 1e-9 && q.x0 < p.x1 - 1e-9 && p.y0 < q.y1 - 1e-9 && q.y0 < p.y1 - 1e-9)
          << p.name << " overlaps " << q.name;
    }
  }

  // Compiled, the free objects stay where they were put (on surfaces or the floor).
  const auto scene = Scene::build(a.file);
  World world(scene);
  world.reset(scene->robot_start());
  world.step(120);
  int free_objects = 0;
  for (const SceneObject& o : scene->objects()) {
    if (o.fixed || o.body < 0) continue;
    ++free_objects;
    const double* p = world.data()->xpos + 3 * o.body;
    EXPECT_LT(std::hypot(p[0] - o.pos[0], p[1] - o.pos[1]), 0.1) << o.name;
    EXPECT_GT(p[2], -0.01) << o.name;
  }
  EXPECT_GT(free_objects, 5);
}

// A BEHAVIOR-1K activity written for a test: DIR/NAME/problem0.bddl in the
// scratch folder SCRATCH, as BEHAVIOR-1K keeps its activities.
fs::path write_activity(const std::string& scratch, const std::string& name, const std::string& bddl) {
  const fs::path file = test::scratch_dir(scratch) / name / "problem0.bddl";
  fs::create_directories(file.parent_path());
  std::ofstream(file) << bddl;
  return file;
}

// An env of it without pictures, its instance whether in reach or not.
EnvConfig unpictured(const fs::path& activity) {
  EnvConfig config;
  config.activity = activity.string();
  config.observations = {"proprio"};
  config.reachable_instances = false;
  return config;
}

// A BEHAVIOR-1K activity no scene file has: it gets the smallest inventory
// with a kitchen, a countertop there, and its apple, plate and bowl as added
// free objects, which its sampler puts on the countertop, the plate first
// though the file names the apple's placement first (support first, as
// BEHAVIOR samples: else the apple stays behind when the plate moves).
TEST(SceneAnalogs, AnActivityIsInstantiatedInTheAnalogOfAScene) {
  const fs::path file = write_activity("analog_activity", "apple_on_counter", R"((define (problem apple_on_counter-0)
    (:domain omnigibson)
    (:objects
        countertop.n.01_1 - countertop.n.01
        apple.n.01_1 - apple.n.01
        plate.n.04_1 - plate.n.04
        bowl.n.01_1 - bowl.n.01
        floor.n.01_1 - floor.n.01
        agent.n.01_1 - agent.n.01)
    (:init
        (ontop apple.n.01_1 plate.n.04_1)
        (ontop plate.n.04_1 countertop.n.01_1)
        (ontop bowl.n.01_1 countertop.n.01_1)
        (inroom countertop.n.01_1 kitchen)
        (inroom floor.n.01_1 kitchen)
        (ontop agent.n.01_1 floor.n.01_1))
    (:goal (and (inside ?apple.n.01_1 ?bowl.n.01_1))))
)");
  const Problem problem = load_bddl(file.string());
  const SceneInventory& inventory = activity_inventory(problem);
  int smallest = 1 << 30;
  for (const SceneInventory& s : shipped_scene_inventories()) {
    const bool kitchen = std::any_of(s.rooms.begin(), s.rooms.end(), [](const auto& r) { return r.type == "kitchen"; });
    if (kitchen) smallest = std::min(smallest, s.object_count());
  }
  EXPECT_EQ(inventory.object_count(), smallest) << inventory.name;
  EXPECT_THROW(activity_inventory(problem, "gates_bedroom"), Error);  // one bedroom, no kitchen

  EnvConfig config;
  config.activity = file.string();
  config.observations = {"rgb"};
  config.width = config.height = 64;
  Env env(config);
  const auto reset = env.reset(0);
  EXPECT_EQ(env.world().scene().name(), inventory.name);
  EXPECT_EQ(reset.info.total, 1);
  // Sampled: both on the countertop, in the kitchen.
  const World& world = env.world();
  const Scene& scene = world.scene();
  const SceneObject* apple = scene.find_object("apple_1");
  ASSERT_NE(apple, nullptr);
  const double* p = world.data()->xpos + 3 * apple->body;
  const Room* room = scene.room_at(p[0], p[1]);
  ASSERT_NE(room, nullptr);
  EXPECT_EQ(room->type, "kitchen");
  EXPECT_GT(p[2], 0.5) << "on the countertop, not the floor";
  const SceneObject* plate = scene.find_object("plate_1");
  ASSERT_NE(plate, nullptr);
  const double* q = world.data()->xpos + 3 * plate->body;
  EXPECT_GT(p[2], q[2]) << "on the plate";
  EXPECT_LT(std::hypot(p[0] - q[0], p[1] - q[1]), 0.2) << "on the plate";
}

// BEHAVIOR-1K's garden activities: the lawn is an object of the garden the
// agent starts on, a small container grows to hold what :init puts in it,
// and a goal may ask what a container contains.
TEST(SceneAnalogs, AGardenHasItsLawnAndContainersHoldTheirContents) {
  const fs::path file = write_activity("analog_garden", "chorizo_on_lawn", R"((define (problem chorizo_on_lawn-0)
    (:domain omnigibson)
    (:objects
        lawn.n.01_1 - lawn.n.01
        tupperware.n.01_1 - tupperware.n.01
        chorizo.n.01_1 - chorizo.n.01
        bucket.n.01_1 - bucket.n.01
        water.n.06_1 - water.n.06
        floor.n.01_1 - floor.n.01
        agent.n.01_1 - agent.n.01)
    (:init
        (inside chorizo.n.01_1 tupperware.n.01_1)
        (ontop tupperware.n.01_1 lawn.n.01_1)
        (ontop bucket.n.01_1 lawn.n.01_1)
        (inroom lawn.n.01_1 garden)
        (inroom floor.n.01_1 garden)
        (ontop agent.n.01_1 lawn.n.01_1))
    (:goal (and (contains ?bucket.n.01_1 ?water.n.06_1))))
)");
  const CategoryModels& models = *CategoryModels::shipped();
  const Eigen::Vector3d chorizo = models.size("chorizo.n.01"), tupperware = models.size("tupperware.n.01");
  ASSERT_GT(chorizo.head<2>().norm(), tupperware.x()) << "the test needs a container too small of its own";

  Env env(unpictured(file));
  const auto reset = env.reset(0);
  EXPECT_EQ(reset.info.total, 1);
  EXPECT_EQ(reset.info.satisfied, 0) << "the bucket holds no water yet";
  const World& world = env.world();
  const Scene& scene = world.scene();
  const SceneObject* lawn = scene.find_object("lawn_1");
  ASSERT_NE(lawn, nullptr);
  EXPECT_TRUE(lawn->fixed);
  const Room* garden = scene.room_at(world.base_pose().x, world.base_pose().y);
  ASSERT_NE(garden, nullptr);
  EXPECT_EQ(garden->type, "garden") << "the agent starts in the lawn's room";
  const SceneObject* box = scene.find_object("tupperware_1");
  ASSERT_NE(box, nullptr);
  EXPECT_GT(object_aabb(world, static_cast<int>(box - scene.objects().data())).extent().x(), chorizo.head<2>().norm());
}

// clean_snap_peas: five pea pods on a mixing bowl on a counter. On a bowl
// is in it: the bowl grows both ways for them, as for what goes inside.
// Grown along its width alone it was 0.94 x 0.76 m, and the counter under it
// 1.05 m deep, the pods at its middle out of the arm's reach.
TEST(SceneAnalogs, ABowlGrowsBothWaysForWhatLiesOnIt) {
  const fs::path file = write_activity("analog_bowl", "pea_pods_on_a_bowl", R"((define (problem pea_pods_on_a_bowl-0)
    (:domain omnigibson)
    (:objects
        pea_pod.n.01_1 pea_pod.n.01_2 pea_pod.n.01_3 pea_pod.n.01_4 pea_pod.n.01_5 - pea_pod.n.01
        mixing_bowl.n.01_1 - mixing_bowl.n.01
        countertop.n.01_1 - countertop.n.01
        floor.n.01_1 - floor.n.01
        agent.n.01_1 - agent.n.01)
    (:init
        (ontop pea_pod.n.01_1 mixing_bowl.n.01_1)
        (ontop pea_pod.n.01_2 mixing_bowl.n.01_1)
        (ontop pea_pod.n.01_3 mixing_bowl.n.01_1)
        (ontop pea_pod.n.01_4 mixing_bowl.n.01_1)
        (ontop pea_pod.n.01_5 mixing_bowl.n.01_1)
        (ontop mixing_bowl.n.01_1 countertop.n.01_1)
        (inroom countertop.n.01_1 kitchen)
        (inroom floor.n.01_1 kitchen)
        (ontop agent.n.01_1 floor.n.01_1))
    (:goal (and (ontop ?pea_pod.n.01_1 ?countertop.n.01_1))))
)");
  Env env(unpictured(file));
  env.reset(0);
  const World& world = env.world();
  const Eigen::Vector3d bowl = object_aabb(world, env.activity()->object("mixing_bowl.n.01_1")).extent();
  EXPECT_LT(std::max(bowl.x(), bowl.y()), 1.05 * std::min(bowl.x(), bowl.y())) << bowl.transpose();
  EXPECT_LT(std::max(bowl.x(), bowl.y()), 0.85) << bowl.transpose();
}

// clearing_table_after_breakfast: french toast on french toast on a plate on
// a table. Sizes are the synset's: grown for what lies on it, french toast
// grew for its own kind at every pass, 3 m long, and with it the plate
// (2.5 m across) and the table (8.5 m), the banana on it beyond every base
// pose. A like thing on its like is no load.
TEST(SceneAnalogs, ALikeThingOnItsLikeGrowsNeither) {
  const fs::path file = write_activity("analog_stack", "toast_on_toast", R"((define (problem toast_on_toast-0)
    (:domain omnigibson)
    (:objects
        french_toast.n.01_1 french_toast.n.01_2 - french_toast.n.01
        plate.n.04_1 - plate.n.04
        breakfast_table.n.01_1 - breakfast_table.n.01
        floor.n.01_1 - floor.n.01
        agent.n.01_1 - agent.n.01)
    (:init
        (ontop french_toast.n.01_2 french_toast.n.01_1)
        (ontop french_toast.n.01_1 plate.n.04_1)
        (ontop plate.n.04_1 breakfast_table.n.01_1)
        (inroom breakfast_table.n.01_1 dining_room)
        (inroom floor.n.01_1 dining_room)
        (ontop agent.n.01_1 floor.n.01_1))
    (:goal (and (ontop ?french_toast.n.01_1 ?breakfast_table.n.01_1))))
)");
  Env env(unpictured(file));
  env.reset(0);
  const World& world = env.world();
  const Activity& activity = *env.activity();
  const Eigen::Vector3d toast = object_aabb(world, activity.object("french_toast.n.01_2")).extent();
  const Eigen::Vector3d own = shipped().size("french_toast.n.01");
  EXPECT_LT(toast.head<2>().maxCoeff(), 1.01 * own.head<2>().norm()) << toast.transpose();
  const Eigen::Vector3d plate = object_aabb(world, activity.object("plate.n.04_1")).extent();
  EXPECT_LT(plate.head<2>().maxCoeff(), 0.6) << plate.transpose();
  const Eigen::Vector3d table = object_aabb(world, activity.object("breakfast_table.n.01_1")).extent();
  EXPECT_LT(table.head<2>().maxCoeff(), 2.5) << table.transpose();
  EXPECT_TRUE(ontop(world, activity.object("french_toast.n.01_2"), activity.object("french_toast.n.01_1")));
  EXPECT_TRUE(ontop(world, activity.object("french_toast.n.01_1"), activity.object("plate.n.04_1")));
}

// make_a_steak: two steaks on a chopping board on a counter. The board grows
// for them; the counter under it keeps its depth (grown as deep as the board
// was long, 1.4 m, its back was beyond the arm) and grows along its width.
TEST(SceneAnalogs, FurnitureKeepsItsDepthForWhatLiesOnIt) {
  const fs::path file = write_activity("analog_counter", "steaks_on_a_board", R"((define (problem steaks_on_a_board-0)
    (:domain omnigibson)
    (:objects
        steak.n.01_1 steak.n.01_2 - steak.n.01
        chopping_board.n.01_1 - chopping_board.n.01
        countertop.n.01_1 - countertop.n.01
        floor.n.01_1 - floor.n.01
        agent.n.01_1 - agent.n.01)
    (:init
        (ontop steak.n.01_1 chopping_board.n.01_1)
        (ontop steak.n.01_2 chopping_board.n.01_1)
        (ontop chopping_board.n.01_1 countertop.n.01_1)
        (inroom countertop.n.01_1 kitchen)
        (inroom floor.n.01_1 kitchen)
        (ontop agent.n.01_1 floor.n.01_1))
    (:goal (and (ontop ?steak.n.01_1 ?countertop.n.01_1))))
)");
  Env env(unpictured(file));
  env.reset(0);
  const World& world = env.world();
  const Activity& activity = *env.activity();
  const Eigen::Vector3d board = object_aabb(world, activity.object("chopping_board.n.01_1")).extent();
  const Eigen::Vector3d own_board = shipped().size("chopping_board.n.01");
  EXPECT_GT(board.head<2>().maxCoeff(), own_board.head<2>().maxCoeff() + 0.1) << "grown for the steaks";
  const Eigen::Vector3d counter = object_aabb(world, activity.object("countertop.n.01_1")).extent();
  const Eigen::Vector3d own_counter = shipped().size("countertop.n.01");
  EXPECT_NEAR(counter.head<2>().minCoeff(), own_counter.head<2>().minCoeff(), 0.01) << counter.transpose();
  EXPECT_GE(counter.head<2>().maxCoeff(), board.head<2>().maxCoeff()) << counter.transpose();
  for (const char* steak : {"steak.n.01_1", "steak.n.01_2"}) {
    EXPECT_TRUE(ontop(world, activity.object(steak), activity.object("chopping_board.n.01_1"))) << steak;
  }
}

// BDDL's attached: a rod attached to a wall nail is welded where it was
// sampled, stays there as the world steps, and is let go at the next reset.
TEST(SceneAnalogs, AttachedObjectsAreWeldedWhereSampled) {
  const fs::path file = write_activity("analog_attached", "rod_on_nail", R"((define (problem rod_on_nail-0)
    (:domain omnigibson)
    (:objects
        wall_nail.n.01_1 - wall_nail.n.01
        curtain_rod.n.01_1 - curtain_rod.n.01
        floor.n.01_1 - floor.n.01
        agent.n.01_1 - agent.n.01)
    (:init
        (attached curtain_rod.n.01_1 wall_nail.n.01_1)
        (inroom wall_nail.n.01_1 living_room)
        (inroom floor.n.01_1 living_room)
        (ontop agent.n.01_1 floor.n.01_1))
    (:goal (and (not (attached ?curtain_rod.n.01_1 ?wall_nail.n.01_1)))))
)");
  Env env(unpictured(file));
  const auto reset = env.reset(0);
  EXPECT_EQ(reset.info.satisfied, 0) << "attached at the start";
  World& world = env.impl().world();
  const Scene& scene = world.scene();
  const int rod = static_cast<int>(scene.find_object("curtain_rod_1") - scene.objects().data());
  const int nail = static_cast<int>(scene.find_object("wall_nail_1") - scene.objects().data());
  ASSERT_TRUE(attached(world, rod, nail));
  EXPECT_GT(object_aabb(world, rod).lo.z(), 0.5) << "up on the nail, not on the floor";
  const Eigen::Vector3d before = object_aabb(world, rod).center();
  world.step(120);
  EXPECT_LT((object_aabb(world, rod).center() - before).norm(), 0.03) << "held (a soft weld sags), not fallen";
  world.reset(scene.robot_start());
  EXPECT_FALSE(attached(world, rod, nail));
}

// A BEHAVIOR-100 activity with a dusty floor in a room no inventory has (a
// home office, added to the analog): the floor is an object of its room that
// keeps the dust, laid where the floor lies exposed, and a floor nothing is
// asked of stays the room's. A window of the inventory's, whose synset
// (openable_window.n.01) BEHAVIOR-100 lacks, is its window.n.01 by
// BEHAVIOR-1K's hierarchy.
TEST(SceneAnalogs, AFloorKeepsDustAndSceneObjectsAreKnownByBehavior1kSynsets) {
  const fs::path file = write_activity("analog_floor", "dusty_office", R"((define (problem dusty_office_0)
    (:domain igibson)
    (:objects
        floor.n.01_1 floor.n.01_2 - floor.n.01
        window.n.01_1 - window.n.01
        agent.n.01_1 - agent.n.01)
    (:init
        (dusty floor.n.01_1)
        (not (open window.n.01_1))
        (inroom floor.n.01_1 home_office)
        (inroom floor.n.01_2 bedroom)
        (inroom window.n.01_1 bedroom)
        (onfloor agent.n.01_1 floor.n.01_2))
    (:goal (and (not (dusty ?floor.n.01_1)) (open ?window.n.01_1))))
)");
  Env env(unpictured(file));
  const auto reset = env.reset(0);
  EXPECT_EQ(reset.info.total, 2);
  EXPECT_EQ(reset.info.satisfied, 0) << "the floor is dusty and the window closed";
  const World& world = env.world();
  const Scene& scene = world.scene();
  const Activity& activity = *env.activity();
  const Binding& office = activity.binding("floor.n.01_1");
  ASSERT_EQ(office.kind, Binding::Kind::floor);
  EXPECT_EQ(scene.rooms()[office.index].type, "home_office");
  ASSERT_GE(office.object, 0);
  const SceneObject& slab = scene.objects()[office.object];
  EXPECT_EQ(slab.synset, "floor.n.01");
  EXPECT_TRUE(slab.fixed);
  const Aabb box = object_aabb(world, office.object);
  EXPECT_NEAR(box.hi.z(), 0, 1e-9) << "its top is the floor's";
  const std::vector<Eigen::Vector3d>& dust = world.states().state(office.object).dirt.at("dust");
  EXPECT_FALSE(dust.empty());
  const Room& room = scene.rooms()[office.index];
  for (const Eigen::Vector3d& local : dust) {
    const Eigen::Vector3d p = object_frame(world, office.object).to_world(local);
    EXPECT_NEAR(p.z(), 0, 1e-6);
    EXPECT_EQ(scene.room_at(p.x(), p.y()), &room);
  }
  EXPECT_TRUE(dirty(world, office.object, "dust"));
  EXPECT_EQ(activity.binding("floor.n.01_2").object, -1) << "nothing is asked of the bedroom's floor";

  const std::string& window = scene.objects()[activity.object("window.n.01_1")].synset;
  EXPECT_FALSE(dialect_knowledge_base(Domain::igibson)->contains(window))
      << window << ": the inventory's window, not one added in BEHAVIOR-100's synset";
  EXPECT_TRUE(dialect_knowledge_base(Domain::omnigibson)->is_a(window, "window.n.01"));
}

// States :init sets go to objects that keep them (issue 54): an abstract
// synset (fiber.n.01, whose own properties are its kinds' intersection and
// soak nothing) is made as the first of its kinds that soaks (cotton.n.01),
// and a flammable object is set on fire past its knowledge base's ignition
// temperature (OmniGibson's 250 C), so both goal literals hold at the start.
TEST(SceneAnalogs, StatesTheInitSetsGoToObjectsThatKeepThem) {
  const fs::path file = write_activity("analog_states", "soaked_fibre_on_fire", R"((define (problem fire-0)
    (:domain omnigibson)
    (:objects
        newspaper.n.03_1 - newspaper.n.03
        fiber.n.01_1 - fiber.n.01
        water.n.06_1 - water.n.06
        table.n.02_1 - table.n.02
        floor.n.01_1 - floor.n.01
        agent.n.01_1 - agent.n.01)
    (:init
        (ontop newspaper.n.03_1 table.n.02_1)
        (on_fire newspaper.n.03_1)
        (ontop fiber.n.01_1 table.n.02_1)
        (saturated fiber.n.01_1 water.n.06_1)
        (inroom table.n.02_1 kitchen)
        (inroom floor.n.01_1 kitchen)
        (ontop agent.n.01_1 floor.n.01_1))
    (:goal (and (on_fire ?newspaper.n.03_1) (saturated ?fiber.n.01_1 ?water.n.06_1))))
)");
  Env env(unpictured(file));
  const auto reset = env.reset(0);
  EXPECT_EQ(reset.info.total, 2);
  EXPECT_EQ(reset.info.satisfied, 2);
  const World& world = env.world();
  const Activity& activity = *env.activity();
  EXPECT_EQ(world.scene().objects()[activity.object("fiber.n.01_1")].synset, "cotton.n.01");
  const int paper = activity.object("newspaper.n.03_1");
  EXPECT_DOUBLE_EQ(world.states().abilities(paper)->ignition_temperature, 250);
  EXPECT_GE(world.states().state(paper).temperature, 250);
}

}  // namespace
}  // namespace chore
