// What a scene file and its object model files say, read and validated, before
// anything is compiled: every bound and name is checked here, so that
// Scene::build only turns valid data into MJCF (MuJoCo's parse/compile split).
// A reader error is a chore::Error naming the file and the field.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace chore {

using Rgb = std::array<double, 3>;

// An object model (assets/objects/<model>.json): a tree of links, each with
// its primitive geoms; a child link moves on one joint (drawers, doors).
struct GeomSpec {
  std::string type;  // box, cylinder, sphere or capsule
  std::vector<double> size;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // in the link frame
  Rgb rgb = {0.7, 0.7, 0.7};
};

struct LinkSpec {
  std::string name;
  Eigen::Vector3d pos = Eigen::Vector3d::Zero();
  std::string joint_type;  // "" for the root, else slide or hinge
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double range[2] = {0, 0};  // m or rad
  double damping = 1.0;
  double mass = 1.0;
  std::vector<GeomSpec> geoms;
  std::vector<LinkSpec> links;
};

struct LightSpec {
  Eigen::Vector3d pos;
  Rgb rgb;
};

// A cloth: MuJoCo's composite grid of small bodies joined by hinges, rooted at
// its centre body (which carries the free joint).
struct ClothSpec {
  int count = 5;          // bodies per side (odd: a centre body)
  double spacing = 0.06;  // m between neighbours
  double radius = 0.006;  // of the capsules that collide
  Rgb rgb = {0.45, 0.65, 0.85};
};

struct ObjectModel {
  std::string category, synset;
  LinkSpec root;  // a cloth's: its mass only
  std::optional<LightSpec> light;
  std::optional<ClothSpec> cloth;
};

ObjectModel parse_object_model(const std::string& json_text, const std::string& path);
ObjectModel read_object_model(const std::string& path);

struct Room {
  std::string name;  // "<type>_<index>", the name BDDL's (inroom obj room) uses
  std::string type;
  std::vector<std::array<double, 4>> rects;  // xmin, ymin, xmax, ymax
  Rgb floor_rgb = {0.6, 0.6, 0.6};
};

struct Pose2 {
  double x = 0, y = 0, yaw = 0;
};

struct ObjectPlacement {
  std::string name;   // instance name, unique in the scene, without '/'
  std::string model;  // key into SceneFile::models
  std::string synset;
  bool fixed = false;
  Eigen::Vector3d pos = Eigen::Vector3d::Zero();
  double yaw = 0;  // rad
};

struct CeilingLight {
  Eigen::Vector3d pos;
  Rgb rgb;
};

// Two objects an activity may attach (BDDL's attached: a hanger in a
// wardrobe, a rod on a wall nail): a weld between them, off at the start.
struct Attachment {
  std::string object, to;  // object names
};

struct SceneFile {
  std::string name, path;
  double wall_height = 2.6, wall_thickness = 0.1;
  std::vector<Room> rooms;
  std::vector<std::array<double, 4>> walls;  // x0, y0, x1, y1
  std::vector<CeilingLight> ceiling_lights;
  std::vector<ObjectPlacement> objects;
  std::map<std::string, ObjectModel> models;  // by ObjectPlacement::model
  Pose2 robot_start;
  std::vector<Attachment> attachments;  // made by analogs; scene files have none
};

// `path` names the file in messages and anchors object models given as .json
// paths; other models are read from <assets>/objects.
SceneFile parse_scene_file(const std::string& json_text, const std::string& path, const std::string& assets);
SceneFile read_scene_file(const std::string& path, const std::string& assets);

}  // namespace chore
