// A scene compiled once into an immutable mjModel: rooms, walls, furniture,
// objects, lights and (optionally) the robot. Environments copy the model; the
// Scene itself is shared read-only between them (MuJoCo's Model/Data split).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "world/scene_file.hpp"

struct mjModel_;

namespace chore {

// Root of the asset library: $CHORE_ASSETS if set, else the source tree's assets/.
std::string default_assets_dir();

// Geom groups: what cameras draw (group 0: robot and objects, which also
// collide; group 2: the merged static scene, drawn only), ceilings (group 1,
// drawn by egocentric views only) and collision-only geoms (group 3, never
// drawn). Ray casts test groups 0 and 3: the merged mesh would cost them a
// test of every static triangle.
constexpr int kStaticGroup = 0;
constexpr int kCeilingGroup = 1;
constexpr int kMergedGroup = 2;
constexpr int kCollisionGroup = 3;

struct SceneObject {
  std::string name;   // instance name, unique in the scene
  std::string model;  // object model file (assets/objects/<model>.json)
  std::string category;
  std::string synset;
  bool fixed = false;  // welded to the world (furniture) or a free body
  // Root body id; -1 for fixed furniture without moving parts, whose geoms
  // are compiled into the world body: a body costs every physics step, a
  // geom of the world body only where MuJoCo's midphase finds something near.
  int body = -1;
  // Where the object stands as compiled (row-major rotation, as mjData's
  // xmat): for ever for furniture in the world body, the initial pose otherwise.
  std::array<double, 3> pos{};
  std::array<double, 9> mat{};
  int grasp_weld = -1;          // equality id of the gripper weld (free objects only)
  std::vector<int> joints;      // articulated joints (drawers, doors)
  std::vector<int> link_welds;  // per joint: the gripper weld of the link it moves
  std::vector<int> geoms;       // collision geoms of the object and its links
  // Cloth only: its four corner bodies (keypoints) and their diagonal when flat.
  std::vector<int> keypoints;
  double flat_diagonal = 0;
};

struct SceneOptions {
  bool robot = true;        // false: no robot, a fixed camera stands in (Table A.10 "- Robot")
  bool cloth = true;        // false: cloths become rigid flat boxes (Table A.10 "- Fluid and Cloth")
  std::string assets_dir;   // empty: default_assets_dir()
  std::string model_cache;  // a folder compiled models are kept in (world/model_cache.hpp); "": none
};

class Scene {
 public:
  // `name` is a scene in <assets>/scenes/<name>.json, or a path to a .json file.
  static std::shared_ptr<const Scene> load(const std::string& name, const SceneOptions& options = {});
  // A scene read or made in memory (the robot comes from options.assets_dir).
  static std::shared_ptr<const Scene> build(const SceneFile& file, const SceneOptions& options = {});
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  const mjModel_* model() const { return model_; }
  const std::string& name() const { return name_; }
  const std::string& path() const { return path_; }
  const std::vector<Room>& rooms() const { return rooms_; }
  const std::vector<SceneObject>& objects() const { return objects_; }
  const SceneObject* find_object(std::string_view name) const;
  // Index into objects() of the object a body belongs to, or -1 (robot, world).
  int object_of_body(int body) const { return body_object_[body]; }
  // Index into objects() of the object a geom belongs to, or -1 (robot, rooms).
  // The identity of furniture in the world body lives only here.
  int object_of_geom(int geom) const { return geom_object_[geom]; }
  // Collision geoms of each room's floor, in rooms() order.
  const std::vector<int>& floor_geoms(int room) const { return floor_geoms_[room]; }
  // The room whose floor contains (x, y), or nullptr outside every room.
  const Room* room_at(double x, double y) const;
  const Pose2& robot_start() const { return robot_start_; }
  bool has_robot() const { return has_robot_; }
  int camera() const { return camera_; }                    // the egocentric camera
  int overview_camera() const { return overview_camera_; }  // third-person, top-down
  const std::vector<int>& ceiling_lights() const { return ceiling_lights_; }
  // SceneFile::attachments, resolved: objects() indices and the weld's equality id.
  struct Attachment {
    int object, to, weld;
  };
  const std::vector<Attachment>& attachments() const { return attachments_; }
  const std::string& mjcf() const { return mjcf_; }  // the generated MJCF text
  bool from_cache() const { return from_cache_; }    // loaded from SceneOptions::model_cache, not compiled

 private:
  Scene() = default;
  mjModel_* model_ = nullptr;
  std::string name_, path_, mjcf_;
  std::vector<Room> rooms_;
  std::vector<SceneObject> objects_;
  std::vector<int> body_object_, geom_object_;
  std::vector<std::vector<int>> floor_geoms_;
  Pose2 robot_start_;
  bool has_robot_ = true;
  int camera_ = -1, overview_camera_ = -1;
  std::vector<int> ceiling_lights_;
  std::vector<Attachment> attachments_;
  bool from_cache_ = false;
};

}  // namespace chore
