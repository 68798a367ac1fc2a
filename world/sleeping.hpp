// Sleeping, as PhysX and Bullet do it: objects at rest, away from the robot
// and from anything moving, are taken out of collision detection and held
// where they came to rest, until something comes near. A resting contact costs
// the same every step whether or not anything happens to it (in the restaurant
// ~3/4 of a physics step is collision detection of ~800 objects nobody
// touches); sleepers cost nothing. It is on in every physics step (World).
//
// The mask lives only inside a physics step: before mj_step the sleepers'
// bodies get no geoms (MuJoCo's broadphase skips them), after it they are
// given back and their joints put back where they slept (gravity moved them
// one step). Static bodies of furniture (Scene::static_bodies()) that no awake
// region meets are masked too: out of the broadphase; one that a region meets
// keeps only the run of its geoms from the first to the last a region meets.
//
// What a sleeper touched when it fell asleep it still touches: those resting
// contacts are kept, and World appends them to mjData's contact list at the
// end of each of its steps and kinematic moves (not between physics substeps:
// ~500 bytes a contact), marked with efc_address kKeptContact (no force:
// mj_contactForce gives zeros), so that contact predicates read the same list
// as if all were awake.
// An object sleeps after kStillSteps steps at rest; one moved or set in
// motion by anything but physics wakes at the next step.
#pragma once

#include <mujoco/mjdata.h>

#include <cstddef>
#include <vector>

#include "world/aabb.hpp"

struct mjModel_;

namespace chore {

class Scene;

class Sleeping {
 public:
  // Awake regions: the robot's box grown by kRobotMargin (m); an object moving
  // faster than kRestSpeed (m/s, or 10x in rad/s) wakes what is within
  // kMovingMargin of it, one at rest what it touches (kTouchMargin).
  static constexpr double kRobotMargin = 0.25, kMovingMargin = 0.25, kTouchMargin = 0.02;
  static constexpr double kRestSpeed = 0.02;
  // Steps an object stays below kRestSpeed before it may sleep (0.1 s; PhysX
  // waits 0.4 s): an object just placed in the air is still, not at rest.
  static constexpr int kStillSteps = 12;
  // efc_address of a kept resting contact (MuJoCo's own are >= 0, or -1 when
  // excluded from the solver).
  static constexpr int kKeptContact = -2;

  // `robot_root`: the robot's root body (-1: no robot).
  Sleeping(const Scene& scene, const mjModel_* model, int robot_root);

  // Decides who sleeps from the positions and velocities in `d`, then masks
  // the sleepers' bodies out of `m`'s collision detection. `held_body` (-1:
  // none) is carried by the robot and always awake.
  void mask(mjModel_* m, const mjData* d, int held_body);
  // Gives the bodies their geoms back and the sleepers their resting state;
  // after a physics step (`physics`), remembers where the awake are, to tell
  // a later move by anything but physics.
  void unmask(mjModel_* m, mjData* d, bool physics);
  // Appends the kept resting contacts to d's contact list (once per list).
  void append_resting_contacts(const mjModel_* m, mjData* d) const;
  // Everyone awake, nothing remembered.
  void wake_all();
  // Everyone as if at rest already: each object sleeps at the next step
  // unless it moves or something awake is near it (objects placed at rest,
  // too many to be awake at once).
  void all_at_rest();

  // After mask(): the degrees of freedom physics must keep (a prefix of the
  // model's); those past it are sleepers' only. The scene's model puts the
  // robot's and cloths' first.
  int awake_dofs() const { return awake_dofs_; }

  int sleepers() const;
  bool asleep(int object) const;

 private:
  struct Object {
    std::vector<int> bodies;      // the object's bodies (its root's subtree)
    std::vector<int> geoms;       // its collision geoms
    std::vector<int> qpos, dofs;  // its joints' coordinates and degrees of freedom
    bool free = false;            // moves on its own (else welded to the world, links aside)
    bool never = false;           // has unbounded geoms (planes, height fields)
    int static_body = -1;         // furniture in a static body: index into static_bodies_
    bool asleep = false;
    int still_steps = 0;            // steps below the rest speed
    std::vector<double> rest_qpos;  // where it fell asleep
    std::vector<double> step_qpos;  // where the last physics step left it (empty: not yet)
  };
  bool moved_while_asleep(const Object& o, const mjData* d) const;
  bool moved_since_step(const Object& o, const mjData* d) const;
  void keep_resting_contacts(const mjData* d);

  std::vector<Object> objects_;
  std::vector<int> moving_;       // objects with bodies of their own (not in a static body), in order
  std::vector<int> geom_object_;  // Scene::object_of_geom, copied
  std::vector<int> robot_geoms_;
  std::vector<char> robot_geom_;                  // per geom
  std::vector<int> body_geomadr_, body_geomnum_;  // the model's own
  std::vector<Aabb> boxes_, regions_;             // mask()'s scratch: objects' boxes, awake regions
  std::vector<char> awake_, fell_asleep_;
  std::vector<int> static_bodies_;
  std::vector<Aabb> static_boxes_;                    // made on the first mask()
  std::vector<std::vector<Aabb>> static_geom_boxes_;  // per static body, its geoms'
  std::vector<Aabb> near_regions_;                    // mask()'s scratch
  std::vector<char> static_asleep_;
  std::vector<mjContact> resting_;  // contacts of sleepers, kept
  int always_dofs_ = 0;             // one past the robot's and tendons' dofs
  std::vector<int> body_dof_end_;   // per body: one past the last dof of its tree
  int awake_dofs_ = 0;
};

}  // namespace chore
