// Sleeping is MuJoCo's own (3.4 on; every scene sets <flag sleep="enable"/>):
// a tree of bodies whose velocities stay under mjOption.sleep_tolerance for
// mjMINAWAKE steps sleeps with the rest of its constraint island. MuJoCo then
// skips its dynamics and its collisions with static and sleeping geoms, and
// wakes it on contact with anything awake, on an active equality to an awake
// tree (a grasp weld), on a force applied to it, and when its joints are
// moved from outside physics (samplers, symbolic primitives: MuJoCo compares
// qpos with where it slept). The scene's objects start asleep (Scene:
// mjSLEEP_INIT); the robot, actuated, never sleeps.
//
// What MuJoCo leaves out and chore's contact predicates read: a sleeper's
// resting contacts (onfloor, ontop, touching). RestingContacts keeps those a
// tree had in the step it fell asleep, until it wakes; a kept contact counts
// only while every tree it joins is still asleep (contacts()).
#pragma once

#include <mujoco/mjdata.h>

#include <vector>

struct mjModel_;

namespace chore {

class RestingContacts {
 public:
  // Before a physics step (or a reset that puts trees to sleep): which trees
  // are awake.
  void before_step(const mjModel_* m, const mjData* d);
  // After it: keeps the contacts of the trees that fell asleep in it, and
  // forgets those of trees awake now.
  void after_step(const mjModel_* m, const mjData* d);
  // After a reset: every tree counts as awake before it, nothing is kept.
  void before_reset(const mjModel_* m);
  void clear() { kept_.clear(); }

  // Calls visit(contact) for each kept contact whose trees all still sleep.
  template <class Visit>
  void for_each(const mjModel_* m, const mjData* d, Visit visit) const {
    for (const mjContact& c : kept_) {
      if (asleep(m, d, c)) visit(c);
    }
  }
  int size() const { return static_cast<int>(kept_.size()); }

 private:
  static bool asleep(const mjModel_* m, const mjData* d, const mjContact& c);
  std::vector<char> awake_before_;  // per tree
  std::vector<mjContact> kept_;
};

}  // namespace chore
