// Semantic and instance segmentation. The renderer's segmentation pass gives
// the model geom seen at each pixel; this maps geoms to instances (objects,
// robot links, floors, walls, ceilings) and instances to semantic classes.
//
// The static scene is drawn as one merged mesh (DESIGN.md): its pixels are
// put back on the floor, wall or fixed object whose collision geometry lies
// nearest the point the pixel sees (from depth).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "world/pinhole.hpp"

struct mjModel_;
struct mjData_;

namespace chore {

class World;

// A semantic class: id 0 is "background" (nothing drawn); then "floors",
// "walls", "ceilings", "agent" (the robot), then the scene's object classes,
// by category name.
struct SemanticClass {
  std::string category, synset;
};

struct Instance {
  enum class Kind { background, object, robot_link, structure };
  std::string name;  // object name, robot body name, floor_<room>, wall_<i>, ceilings
  Kind kind = Kind::background;
  int semantic = 0;  // index into classes()
  int object = -1;   // index into Scene::objects() (objects only)
  int body = -1;     // the robot link's body id (robot links only)
};

class Segmentation {
 public:
  static constexpr int kFloors = 1, kWalls = 2, kCeilings = 3, kAgent = 4;

  // Static geometry is read from the world's current pose (it never moves).
  explicit Segmentation(const World& world);
  ~Segmentation();
  Segmentation(const Segmentation&) = delete;
  Segmentation& operator=(const Segmentation&) = delete;

  // Indexed by semantic id and instance id. Instance ids: 0 background, then
  // 1 + i for Scene::objects()[i], then robot links, then floors (one per
  // room), walls, ceilings.
  const std::vector<SemanticClass>& classes() const { return classes_; }
  const std::vector<Instance>& instances() const { return instances_; }
  int instance_of_object(int object) const { return 1 + object; }

  // Per pixel: `geom` (from the segmentation pass, -1: nothing) and metric
  // `depth` to instance and semantic ids; either output may be nullptr.
  void label(const Pinhole& camera, const CameraPose& pose, const std::int32_t* geom, const float* depth,
             std::int32_t* instance, std::int32_t* semantic) const;

 private:
  struct Part;  // a static collision geom and its instance
  // The instance of the static part nearest a point; `part` (in: a guess, -1
  // for none; out: the part found) carries one pixel's answer to the next.
  int resolve(const double point[3], int& part) const;

  std::vector<SemanticClass> classes_;
  std::vector<Instance> instances_;
  std::vector<int> geom_instance_;  // per model geom; kResolve for the merged mesh
  std::vector<Part> parts_;
  std::vector<std::vector<int>> cells_;  // indices into parts_
  double cell_ = 0.5, x0_ = 0, y0_ = 0;
  int nx_ = 0, ny_ = 0;
};

}  // namespace chore
