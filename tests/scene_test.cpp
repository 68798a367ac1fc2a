#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>

#include "base/error.hpp"
#include "base/json_file.hpp"
#include "test_util.hpp"
#include "world/model_cache.hpp"
#include "world/scene.hpp"
#include "world/scene_file.hpp"

namespace chore {
namespace {

TEST(Scene, ApartmentHasFiveNamedRoomsAndAboutSixtyObjects) {
  auto scene = Scene::load("apartment");
  std::set<std::string> rooms;
  for (const Room& r : scene->rooms()) rooms.insert(r.name);
  EXPECT_EQ(rooms, (std::set<std::string>{"bathroom_0", "bedroom_0", "entryway_0", "kitchen_0", "living_room_0"}));
  EXPECT_GE(scene->objects().size(), 50u);
  EXPECT_LE(scene->objects().size(), 70u);
  // Every object stands in some room, and the robot starts inside the apartment.
  for (const SceneObject& o : scene->objects()) {
    EXPECT_NE(scene->room_at(o.pos[0], o.pos[1]), nullptr) << o.name;
  }
  EXPECT_NE(scene->room_at(scene->robot_start().x, scene->robot_start().y), nullptr);
}

TEST(Scene, RoomAtAnswersFromTheFloorRectangles) {
  auto scene = Scene::load(test::box_room());
  ASSERT_NE(scene->room_at(0, 0), nullptr);
  EXPECT_EQ(scene->room_at(0, 0)->name, "living_room_0");
  EXPECT_EQ(scene->room_at(2.9, -2.9)->type, "living_room");
  EXPECT_EQ(scene->room_at(3.5, 0), nullptr);
}

TEST(Scene, StaticGeometryIsDrawnAsMergedChunksAndMovingPartsKeepTheirGeoms) {
  auto scene = Scene::load(test::box_room());
  const mjModel* m = scene->model();
  int merged = 0, drawn_static = 0, hidden_static = 0;
  std::set<int> materials;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->body_weldid[m->geom_bodyid[g]] != 0) continue;  // moves
    const int group = m->geom_group[g];
    (group == kMergedGroup ? merged : group == kStaticGroup ? drawn_static : hidden_static)++;
    if (group == kMergedGroup) {
      materials.insert(m->geom_matid[g]);
      // A chunk is a 2 m cell's shapes: far smaller than the 6 x 6 m room
      // (a wall, the largest shape, reaches 3 m out of its cell).
      EXPECT_LT(m->geom_rbound[g], 4.5) << g;
    }
  }
  EXPECT_GE(merged, 4);                 // the merged static meshes, chunked, in a group of their own
  EXPECT_EQ(materials.size(), 1u);      // one palette texture for them all
  EXPECT_EQ(drawn_static, 0);           // nothing static is drawn apart from it
  EXPECT_GE(hidden_static, 1 + 4 + 2);  // floor, 4 walls, 2 fixed objects for collision
  const SceneObject* block = scene->find_object("small_block_1");
  ASSERT_NE(block, nullptr);
  EXPECT_FALSE(block->fixed);
  EXPECT_GE(block->grasp_weld, 0);
  EXPECT_EQ(m->geom_group[m->body_geomadr[block->body]], 0);  // drawn itself
  const SceneObject* panel = scene->find_object("red_panel_1");
  EXPECT_TRUE(panel->fixed);
  EXPECT_EQ(panel->body, -1);  // in the world body
  for (int g : panel->geoms) EXPECT_EQ(m->geom_bodyid[g], 0);
}

TEST(Scene, FurnitureWithoutMovingPartsIsTheWorldBodysAndKeepsItsIdentity) {
  auto scene = Scene::load(test::data_path("scenes/predicate_room.json"));
  const mjModel* m = scene->model();
  auto index = [&](const char* name) { return static_cast<int>(scene->find_object(name) - scene->objects().data()); };
  const SceneObject& table = *scene->find_object("table_1");
  const SceneObject& cabinet = *scene->find_object("cabinet_1");  // a drawer: keeps its bodies
  EXPECT_EQ(table.body, -1);
  EXPECT_GE(cabinet.body, 1);
  EXPECT_EQ(scene->object_of_body(cabinet.body), index("cabinet_1"));
  EXPECT_EQ(scene->object_of_body(0), -1);  // the world's: the geom says whose
  // The table's collision geoms are its own: the geom table names it, its
  // geoms are posed where the table stands (x 1.5, y 1.5 in the scene file).
  ASSERT_FALSE(table.geoms.empty());
  for (int g = 0; g < m->ngeom; ++g) {
    const bool mine = std::find(table.geoms.begin(), table.geoms.end(), g) != table.geoms.end();
    EXPECT_EQ(scene->object_of_geom(g) == index("table_1"), mine && (m->geom_contype[g] || m->geom_conaffinity[g]))
        << g;
  }
  for (int g : table.geoms) {
    EXPECT_EQ(m->geom_bodyid[g], 0);
    EXPECT_LT(std::hypot(m->geom_pos[3 * g] - 1.5, m->geom_pos[3 * g + 1] - 1.5), 1.0) << g;
  }
  EXPECT_EQ(table.pos[0], 1.5);
  EXPECT_EQ(table.pos[1], 1.5);
  // What never moves is never paired: the world and the drawer cabinet's root
  // exclude each other.
  std::set<std::pair<int, int>> excluded;
  for (int e = 0; e < m->nexclude; ++e) {
    const int s1 = m->exclude_signature[e] >> 16, s2 = m->exclude_signature[e] & 0xFFFF;
    excluded.insert({s1, s2});  // MuJoCo's signature: body1 << 16 | body2
  }
  EXPECT_TRUE(excluded.count({0, m->body_rootid[cabinet.body]}));
  EXPECT_FALSE(excluded.count({0, scene->find_object("apple_1")->body}));
}

TEST(Scene, UnknownSceneNamesTheKnownOnes) {
  const std::string e = test::error_of([] { Scene::load("no_such_scene"); });
  EXPECT_NE(e.find("unknown scene 'no_such_scene'"), std::string::npos) << e;
  EXPECT_NE(e.find("apartment"), std::string::npos) << e;
}

TEST(Scene, MalformedJsonGivesFileLineAndColumn) {
  const auto dir = test::scratch_dir("malformed_json");
  test::write_file(dir / "bad.json", "{\n  \"name\": \"bad\",\n  \"rooms\": [ oops ]\n}\n");
  const std::string e = test::error_of([&] { Scene::load((dir / "bad.json").string()); });
  EXPECT_NE(e.find("bad.json:3:"), std::string::npos) << e;
}

TEST(Scene, JsonNestingSizeAndNumbersAreBounded) {
  const auto dir = test::scratch_dir("bounded_json");
  // 50,000 nested links: refused where the nesting passes the limit, before any reader recurses.
  std::string deep = "{\"links\": ";
  for (int i = 0; i < 50000; ++i) deep += "[{\"links\": ";
  test::write_file(dir / "deep.json", deep);
  std::string e = test::error_of([&] { read_json_file((dir / "deep.json").string()); });
  EXPECT_EQ(e, (dir / "deep.json").string() + ":1:353: nested deeper than 64 levels, the limit");
  // A number past double's range, located.
  test::write_file(dir / "huge.json", "{\n  \"mass\": 1e400\n}\n");
  e = test::error_of([&] { read_json_file((dir / "huge.json").string()); });
  EXPECT_EQ(e, (dir / "huge.json").string() + ":2:11: the number 1e400 is out of range");
  // A file past the size limit (sparse: nothing is written).
  test::write_file(dir / "big.json", "{}");
  std::filesystem::resize_file(dir / "big.json", kMaxJsonBytes + 1);
  e = test::error_of([&] { read_json_file((dir / "big.json").string()); });
  EXPECT_EQ(e, (dir / "big.json").string() + ": larger than 256 MB, the limit for a JSON file");
}

TEST(Scene, PositionsAndRoomsOutsideAHouseAreErrors) {
  const auto dir = test::scratch_dir("bounded_scene");
  const std::string tail = R"("walls": [], "robot": {"pos": [1, 1]}, "objects": [)";
  const std::string room = R"({"rooms": [{"name": "r_0", "type": "r", "rects": [[0, 0, 2, 2]]}], )";
  test::write_file(dir / "far.json", room + tail + R"({"name": "x", "model": "apple", "pos": [1, 1e308, 0]}]})");
  std::string e = test::error_of([&] { Scene::load((dir / "far.json").string()); });
  EXPECT_NE(e.find("objects[0].pos: [1] = 1e+308 is outside [-100, 100]"), std::string::npos) << e;
  test::write_file(dir / "vast.json",
                   R"({"rooms": [{"name": "r_0", "type": "r", "rects": [[-1e6, -1e6, 1e6, 1e6]]}], )" + tail + "]}");
  e = test::error_of([&] { Scene::load((dir / "vast.json").string()); });
  EXPECT_NE(e.find("rooms[0].rects[0]: [0] = -1e+06 is outside [-100, 100]"), std::string::npos) << e;
}

TEST(Scene, MissingFieldAndUnknownModelAreNamed) {
  const auto dir = test::scratch_dir("bad_fields");
  const std::string head =
      R"({"rooms": [{"name": "r_0", "type": "r", "rects": [[0, 0, 2, 2]]}], "walls": [], "robot": {"pos": [1, 1]}, )";
  test::write_file(dir / "a.json", head + R"("objects": [{"name": "x", "pos": [1, 1, 0]}]})");
  std::string e = test::error_of([&] { Scene::load((dir / "a.json").string()); });
  EXPECT_NE(e.find("objects[0]: missing field 'model'"), std::string::npos) << e;
  test::write_file(dir / "b.json", head + R"("objects": [{"name": "x", "model": "teapot_9000", "pos": [1, 1, 0]}]})");
  e = test::error_of([&] { Scene::load((dir / "b.json").string()); });
  EXPECT_NE(e.find("unknown object model 'teapot_9000'"), std::string::npos) << e;
  test::write_file(dir / "c.json", head + R"("objects": [{"name": "x", "model": "apple", "pos": [1, 1]}]})");
  e = test::error_of([&] { Scene::load((dir / "c.json").string()); });
  EXPECT_NE(e.find("objects[0].pos: expected an array of 3 numbers"), std::string::npos) << e;
}

TEST(Scene, MalformedRobotMjcfNamesTheFile) {
  const auto dir = test::scratch_dir("bad_robot");
  std::filesystem::create_directories(dir / "robots");
  std::filesystem::create_directory_symlink(default_assets_dir() + "/objects", dir / "objects");
  test::write_file(dir / "robots" / "tiago.xml", "<mujoco>\n<worldbody>\n<body name=\"robot\">\n</mujoco>\n");
  SceneOptions options;
  options.assets_dir = dir.string();
  const std::string e = test::error_of([&] { Scene::load(test::box_room(), options); });
  EXPECT_NE(e.find("tiago.xml: invalid robot MJCF"), std::string::npos) << e;
}

// MuJoCo's XML reader (tinyxml2) bounds the nesting itself: a clear error, no
// stack overflow.
TEST(Scene, DeeplyNestedRobotMjcfIsALocatedError) {
  const auto dir = test::scratch_dir("deep_robot");
  std::filesystem::create_directories(dir / "robots");
  std::filesystem::create_directory_symlink(default_assets_dir() + "/objects", dir / "objects");
  std::string xml = "<mujoco>\n<!-- a comment -->\n<worldbody>\n";
  for (int i = 0; i < 100000; ++i) xml += "<body><geom size=\"0.1\"/>";
  test::write_file(dir / "robots" / "tiago.xml", xml);
  SceneOptions options;
  options.assets_dir = dir.string();
  const std::string e = test::error_of([&] { Scene::load(test::box_room(), options); });
  EXPECT_NE(e.find("tiago.xml: invalid robot MJCF: XML parse error"), std::string::npos) << e;
  EXPECT_NE(e.find("Line number=4: Element nesting is too deep"), std::string::npos) << e;
}

TEST(Scene, MissingRobotFileNamesThePath) {
  const auto dir = test::scratch_dir("no_robot_file");
  std::filesystem::create_directory_symlink(default_assets_dir() + "/objects", dir / "objects");
  SceneOptions options;
  options.assets_dir = dir.string();
  const std::string e = test::error_of([&] { Scene::load(test::box_room(), options); });
  EXPECT_NE(e.find("robots/tiago.xml: no such file; expected a robot file"), std::string::npos) << e;
}

// A robot MuJoCo accepts but chore cannot drive is refused before the scene is
// compiled, naming the file and what it lacks.
TEST(Scene, RobotWithoutTheJointsChoreDrivesNamesWhatIsMissing) {
  const auto dir = test::scratch_dir("robot_without_joints");
  std::filesystem::create_directories(dir / "robots");
  std::filesystem::create_directory_symlink(default_assets_dir() + "/objects", dir / "objects");
  test::write_file(
      dir / "robots" / "tiago.xml",
      "<mujoco>\n<worldbody>\n<body name=\"robot\"><geom size=\"0.1\"/></body>\n</worldbody>\n</mujoco>\n");
  SceneOptions options;
  options.assets_dir = dir.string();
  const std::string e = test::error_of([&] { Scene::load(test::box_room(), options); });
  EXPECT_NE(e.find("robots/tiago.xml: robot model: missing joint 'base_x'"), std::string::npos) << e;
}

TEST(Scene, WithoutRobotAFixedCameraStandsIn) {
  SceneOptions options;
  options.robot = false;
  auto scene = Scene::load(test::box_room(), options);
  EXPECT_FALSE(scene->has_robot());
  EXPECT_EQ(mj_name2id(scene->model(), mjOBJ_BODY, "robot"), -1);
  ASSERT_GE(scene->camera(), 0);
  EXPECT_STREQ(mj_id2name(scene->model(), mjOBJ_CAMERA, scene->camera()), "scene_camera");
}

// MuJoCo's binary form of a model, to compare two models byte for byte.
std::string model_bytes(const mjModel* m) {
  std::string bytes(static_cast<size_t>(mj_sizeModel(m)), '\0');
  mj_saveModel(m, nullptr, bytes.data(), static_cast<int>(bytes.size()));
  return bytes;
}

std::vector<std::filesystem::path> cached_files(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& f : std::filesystem::directory_iterator(dir)) files.push_back(f.path());
  return files;
}

// A scene compiled once loads from the model cache after, the same model byte
// for byte; a cache file cut short or altered is compiled afresh and replaced,
// a folder that cannot be written leaves it uncached, and the folder keeps the
// most recently used files.
TEST(Scene, CompiledModelsAreCachedByTheirMjcf) {
  const auto dir = test::scratch_dir("model_cache");
  SceneOptions options;
  options.robot = false;
  options.model_cache = (dir / "models").string();
  const SceneFile file = read_scene_file(test::box_room(), default_assets_dir());
  const auto compiled = Scene::build(file, options);
  EXPECT_FALSE(compiled->from_cache());
  const auto loaded = Scene::build(file, options);
  EXPECT_TRUE(loaded->from_cache());
  EXPECT_EQ(model_bytes(loaded->model()), model_bytes(compiled->model()));
  EXPECT_EQ(loaded->objects().size(), compiled->objects().size());

  const std::vector<std::filesystem::path> files = cached_files(dir / "models");
  ASSERT_EQ(files.size(), 1u);
  const std::filesystem::path cached = files[0];
  const std::string whole = read_text_file(cached.string(), 1 << 28, "the cached model");
  for (const std::string& bad : {whole.substr(0, whole.size() / 2), [&] {
                                   std::string altered = whole;
                                   altered[altered.size() - 100] ^= 1;
                                   return altered;
                                 }()}) {
    std::ofstream(cached, std::ios::binary | std::ios::trunc) << bad;
    const auto again = Scene::build(file, options);
    EXPECT_FALSE(again->from_cache()) << "a damaged file is not loaded";
    EXPECT_EQ(model_bytes(again->model()), model_bytes(compiled->model()));
    EXPECT_EQ(read_text_file(cached.string(), 1 << 28, "the cached model"), whole) << "and is replaced";
  }

  options.model_cache = (dir / "models" / cached.filename() / "x").string();  // below a file
  EXPECT_FALSE(Scene::build(file, options)->from_cache());

  // Other documents (the room a little wider each) fill the folder to its bound.
  options.model_cache = (dir / "models").string();
  SceneFile wider = file;
  for (int i = 0; i < kModelCacheFiles + 3; ++i) {
    wider.rooms[0].rects[0][2] += 0.01;
    EXPECT_FALSE(Scene::build(wider, options)->from_cache());
  }
  EXPECT_EQ(cached_files(dir / "models").size(), static_cast<size_t>(kModelCacheFiles));
  EXPECT_TRUE(Scene::build(wider, options)->from_cache()) << "the most recent stays";

  // Files the cache did not write stay whatever their name (a user's own
  // model, a file named as the cache's but not in its format); a temporary
  // file of a writer that died goes.
  const auto models = dir / "models";
  std::ofstream(models / "mine.mjb") << "a user's own model";
  std::ofstream(models / "123.mjb") << "not chore's format";
  std::ofstream(models / "456.mjb.tmp.999999999.0") << "half a file";
  for (int i = 0; i < 3; ++i) {
    wider.rooms[0].rects[0][2] += 0.01;
    Scene::build(wider, options);
  }
  EXPECT_TRUE(std::filesystem::exists(models / "mine.mjb"));
  EXPECT_TRUE(std::filesystem::exists(models / "123.mjb"));
  EXPECT_FALSE(std::filesystem::exists(models / "456.mjb.tmp.999999999.0"));
  EXPECT_EQ(cached_files(models).size(), static_cast<size_t>(kModelCacheFiles) + 2);
}

}  // namespace
}  // namespace chore
