// Sleeping, as PhysX and Bullet do it: objects at rest, away from the robot
// and from anything moving, are taken out of collision detection and held
// where they came to rest, until something comes near. A resting contact costs
// the same every step whether or not anything happens to it (in the restaurant
// ~3/4 of a physics step is collision detection of ~800 objects nobody
// touches); sleepers cost nothing.
//
// The mask lives only inside a physics step: before mj_step the sleepers'
// bodies get no geoms (MuJoCo's broadphase skips them), after it they are
// given back and their joints put back where they slept (gravity moved them
// one step). Everything else (planners, predicates, rendering) sees the whole
// model. What mjData's contact list lacks while some sleep are the sleepers'
// resting contacts: wake everyone (and run mj_forward) before reading them.
// While it is on only physics may move objects: a sleeper set elsewhere would
// be put back where it slept.
#pragma once

#include <cstddef>
#include <vector>

#include "env/world/aabb.hpp"

struct mjModel_;
struct mjData_;

namespace chore {

class Scene;

class Sleeping {
 public:
  // Awake regions: the robot's box grown by kRobotMargin (m); an object moving
  // faster than kRestSpeed (m/s, or 10x in rad/s) wakes what is within
  // kMovingMargin of it, one at rest what it touches (kTouchMargin).
  static constexpr double kRobotMargin = 0.25, kMovingMargin = 0.25, kTouchMargin = 0.02;
  static constexpr double kRestSpeed = 0.02;

  // `robot_root`: the robot's root body (-1: no robot).
  Sleeping(const Scene& scene, const mjModel_* model, int robot_root);

  // Decides who sleeps from the positions and velocities in `d`, then masks
  // the sleepers' bodies out of `m`'s collision detection. `held_body` (-1:
  // none) is carried by the robot and always awake.
  void mask(mjModel_* m, const mjData_* d, int held_body);
  // Gives the bodies their geoms back and the sleepers their resting state.
  void unmask(mjModel_* m, mjData_* d) const;
  // Everyone awake, nothing remembered.
  void wake_all();

  int sleepers() const;
  bool asleep(int object) const { return objects_[static_cast<size_t>(object)].asleep; }

 private:
  struct Object {
    std::vector<int> bodies;  // the object's bodies (its root's subtree)
    std::vector<int> geoms;   // its collision geoms
    std::vector<int> qpos, dofs;  // its joints' coordinates and degrees of freedom
    bool free = false;        // moves on its own (else welded to the world, links aside)
    bool never = false;       // has unbounded geoms (planes, height fields)
    bool asleep = false;
    std::vector<double> rest_qpos;  // where it fell asleep
  };
  std::vector<Object> objects_;
  std::vector<int> robot_geoms_;
  std::vector<int> body_geomnum_;  // the model's own counts
  std::vector<Aabb> boxes_, regions_;  // mask()'s scratch: objects' boxes, awake regions
  std::vector<char> awake_;
};

}  // namespace chore
