#include "world/scene_file.hpp"

#include <cmath>
#include <filesystem>

#include "base/error.hpp"
#include "base/json_file.hpp"

namespace fs = std::filesystem;

namespace chore {
namespace {

// What scene and object files may say (JsonReader errors past these): a
// house fits in 200 m, its parts in 20 m; BEHAVIOR's largest scenes span ~40 m.
constexpr Bounds kSceneCoordinate{-100, 100};  // m, in the scene's frame
constexpr Bounds kPartCoordinate{-10, 10};     // m, in an object's or link's frame
constexpr Bounds kSize{0, 10};                 // m, half-sizes of geoms
constexpr Bounds kDegrees{-360, 360};
constexpr Bounds kColor{0, 1};
constexpr Bounds kMass{0, 1e4};  // kg
constexpr Bounds kDamping{0, 1e6};
constexpr Bounds kUnitScale{0, 1};  // m, cloth spacing and radius

Eigen::Matrix3d rotation_xyz_degrees(const std::vector<double>& euler) {
  // MuJoCo's default eulerseq "xyz": intrinsic rotations about x, then y, then z.
  const double k = M_PI / 180.0;
  return (Eigen::AngleAxisd(euler[0] * k, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(euler[1] * k, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(euler[2] * k, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

Rgb to_rgb(const std::vector<double>& v) {
  return {v[0], v[1], v[2]};
}

Eigen::Vector3d to_vector(const std::vector<double>& v) {
  return {v[0], v[1], v[2]};
}

GeomSpec read_geom(const JsonReader& j) {
  GeomSpec g;
  g.type = j.string("type");
  const std::map<std::string, size_t> sizes = {{"box", 3}, {"cylinder", 2}, {"sphere", 1}, {"capsule", 2}};
  const auto it = sizes.find(g.type);
  if (it == sizes.end()) j.fail("type '" + g.type + "' is not one of box, cylinder, sphere, capsule");
  g.size = j.numbers("size", it->second, kSize);
  for (double s : g.size) {
    if (!(s > 0)) j.fail("size must be positive");
  }
  g.pose.translation() = to_vector(j.numbers("pos", 3, {0, 0, 0}, kPartCoordinate));
  g.pose.linear() = rotation_xyz_degrees(j.numbers("euler", 3, {0, 0, 0}, kDegrees));
  g.rgb = to_rgb(j.numbers("rgb", 3, {0.7, 0.7, 0.7}, kColor));
  return g;
}

LinkSpec read_link(const JsonReader& j, bool root) {
  LinkSpec link;
  if (!root) {
    link.name = j.string("name");
    link.pos = to_vector(j.numbers("pos", 3, kPartCoordinate));
    const JsonReader joint = j.at("joint");
    link.joint_type = joint.string("type");
    if (link.joint_type != "slide" && link.joint_type != "hinge") {
      joint.fail("type '" + link.joint_type + "' is not slide or hinge");
    }
    link.axis = to_vector(joint.numbers("axis", 3, Bounds{-1, 1}));
    if (link.axis.norm() < 1e-9) joint.fail("axis is zero");
    const auto range = joint.numbers("range", 2, link.joint_type == "hinge" ? kDegrees : kPartCoordinate);
    const double scale = link.joint_type == "hinge" ? M_PI / 180.0 : 1.0;
    link.range[0] = range[0] * scale;
    link.range[1] = range[1] * scale;
    if (!(link.range[0] < link.range[1])) joint.fail("range must be [low, high] with low < high");
    link.damping = joint.number("damping", 1.0, kDamping);
  }
  link.mass = j.number("mass", kMass);
  if (!(link.mass > 0)) j.fail("mass must be positive");
  const JsonReader geoms = j.at("geoms");
  for (size_t i = 0; i < geoms.size(); ++i) link.geoms.push_back(read_geom(geoms.at(i)));
  if (link.geoms.empty()) j.fail("a link needs at least one geom");
  if (j.has("links")) {
    const JsonReader links = j.at("links");
    for (size_t i = 0; i < links.size(); ++i) link.links.push_back(read_link(links.at(i), false));
  }
  return link;
}

ObjectModel read_object_model(const JsonReader& j) {
  ObjectModel m;
  m.category = j.string("category");
  m.synset = j.string("synset");
  if (j.has("cloth")) {
    const JsonReader c = j.at("cloth");
    ClothSpec cloth;
    cloth.count = static_cast<int>(c.number("count", 5, Bounds{3, 15}));
    cloth.spacing = c.number("spacing", 0.06, kUnitScale);
    cloth.radius = c.number("radius", 0.006, kUnitScale);
    cloth.rgb = to_rgb(c.numbers("rgb", 3, {0.45, 0.65, 0.85}, kColor));
    if (cloth.count < 3 || cloth.count > 15 || cloth.count % 2 == 0) c.fail("count must be odd, 3..15");
    if (!(cloth.spacing > 2 * cloth.radius) || !(cloth.radius > 0)) c.fail("need spacing > 2 x radius > 0");
    m.cloth = cloth;
    m.root.mass = j.number("mass", kMass);
    if (!(m.root.mass > 0)) j.fail("mass must be positive");
    return m;
  }
  m.root = read_link(j, true);
  if (j.has("light")) {
    const JsonReader light = j.at("light");
    m.light = LightSpec{to_vector(light.numbers("pos", 3, kPartCoordinate)),
                        to_rgb(light.numbers("rgb", 3, {1, 0.9, 0.75}, kColor))};
  }
  return m;
}

}  // namespace

ObjectModel parse_object_model(const std::string& json_text, const std::string& path) {
  return read_object_model(JsonReader(parse_json(json_text, path), path));
}

ObjectModel read_object_model(const std::string& path) {
  return parse_object_model(read_text_file(path, kMaxJsonBytes, "a JSON file"), path);
}

SceneFile parse_scene_file(const std::string& json_text, const std::string& path, const std::string& assets) {
  const nlohmann::json json = parse_json(json_text, path);
  const JsonReader j(json, path);
  SceneFile scene;
  scene.name = j.string("name", fs::path(path).stem().string());
  scene.path = path;
  scene.wall_height = j.number("wall_height", 2.6, Bounds{0.5, 20});
  scene.wall_thickness = j.number("wall_thickness", 0.1, Bounds{0.01, 2});

  const JsonReader rooms = j.at("rooms");
  for (size_t i = 0; i < rooms.size(); ++i) {
    const JsonReader r = rooms.at(i);
    Room room{r.string("name"), r.string("type"), {}, to_rgb(r.numbers("floor_rgb", 3, {0.6, 0.6, 0.6}, kColor))};
    for (const Room& other : scene.rooms) {
      if (other.name == room.name) r.fail("duplicate room name '" + room.name + "'");
    }
    const JsonReader rects = r.at("rects");
    for (size_t k = 0; k < rects.size(); ++k) {
      const auto v = rects.at(k).as_numbers(4, kSceneCoordinate);
      if (!(v[0] < v[2] && v[1] < v[3])) rects.at(k).fail("expected [xmin, ymin, xmax, ymax]");
      room.rects.push_back({v[0], v[1], v[2], v[3]});
    }
    if (room.rects.empty()) r.fail("a room needs at least one rect");
    scene.rooms.push_back(std::move(room));
  }

  const JsonReader walls = j.at("walls");
  for (size_t i = 0; i < walls.size(); ++i) {
    const auto w = walls.at(i).as_numbers(4, kSceneCoordinate);
    if (std::hypot(w[2] - w[0], w[3] - w[1]) < 1e-6) walls.at(i).fail("wall has zero length");
    scene.walls.push_back({w[0], w[1], w[2], w[3]});
  }

  if (j.has("ceiling_lights")) {
    const JsonReader lights = j.at("ceiling_lights");
    for (size_t i = 0; i < lights.size(); ++i) {
      scene.ceiling_lights.push_back({to_vector(lights.at(i).numbers("pos", 3, kSceneCoordinate)),
                                      to_rgb(lights.at(i).numbers("rgb", 3, {0.5, 0.5, 0.5}, kColor))});
    }
  }

  const JsonReader objects = j.at("objects");
  for (size_t i = 0; i < objects.size(); ++i) {
    const JsonReader o = objects.at(i);
    ObjectPlacement object;
    object.name = o.string("name");
    if (object.name.find('/') != std::string::npos) o.fail("object names may not contain '/'");
    for (const ObjectPlacement& other : scene.objects) {
      if (other.name == object.name) o.fail("duplicate object name '" + object.name + "'");
    }
    object.model = o.string("model");
    auto found = scene.models.find(object.model);
    if (found == scene.models.end()) {
      // A model is a name in <assets>/objects, or a .json path relative to the scene file.
      const fs::path model_path = object.model.ends_with(".json")
                                      ? fs::path(path).parent_path() / object.model
                                      : fs::path(assets) / "objects" / (object.model + ".json");
      if (!fs::exists(model_path)) {
        o.fail("unknown object model '" + object.model + "' (no " + model_path.string() + ")");
      }
      found = scene.models.emplace(object.model, read_object_model(model_path.string())).first;
    }
    object.synset = o.string("synset", found->second.synset);
    object.fixed = o.boolean("fixed", false);
    if (found->second.cloth && object.fixed) o.fail("a cloth cannot be fixed");
    object.pos = to_vector(o.numbers("pos", 3, kSceneCoordinate));
    object.yaw = o.number("yaw", 0.0, kDegrees) * M_PI / 180.0;
    scene.objects.push_back(std::move(object));
  }

  const JsonReader robot = j.at("robot");
  const auto start = robot.numbers("pos", 2, kSceneCoordinate);
  scene.robot_start = {start[0], start[1], robot.number("yaw", 0.0, kDegrees) * M_PI / 180.0};
  return scene;
}

SceneFile read_scene_file(const std::string& path, const std::string& assets) {
  return parse_scene_file(read_text_file(path, kMaxJsonBytes, "a JSON file"), path, assets);
}

}  // namespace chore
