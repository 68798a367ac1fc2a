// One simulated world: a private copy of the scene's model (lighting,
// appearance randomisation, grasp welds' poses and the sleeping flag change
// it) and its mjData. Physics runs at 1/120 s; assistive grasping runs after every
// physics step, as OmniGibson's does.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <vector>

#include "world/appearance.hpp"
#include "world/object_states.hpp"
#include "world/robot.hpp"
#include "world/scene.hpp"
#include "world/sleeping.hpp"

struct mjData_;

namespace chore {

class World {
 public:
  // Objects heavier than this (kg) are refused by the assistive grasp (OmniGibson's limit).
  static constexpr double kGraspMassLimit = 10.0;

  explicit World(std::shared_ptr<const Scene> scene);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const Scene& scene() const { return *scene_; }
  const mjModel_* model() const { return model_; }
  mjModel_* model() { return model_; }
  const mjData_* data() const { return data_; }
  mjData_* data() { return data_; }
  // nullptr when the scene was built without a robot.
  const Robot* robot() const { return robot_ ? &*robot_ : nullptr; }

  // Back to the scene's initial state with the robot's base at `base`, arm
  // tucked, gripper open, no grasp, zero velocities.
  void reset(const Pose2& base);
  void set_lighting(Lighting lighting);
  // Domain randomisation (world/appearance.hpp): the scene's lights and
  // colours perturbed by draws from `rng`; all-zero spreads restore them.
  void randomize_appearance(const AppearanceRandomization& r, Rng& rng);
  // Changes whenever the model's textures do (0: the scene's own), so that a
  // renderer knows when to upload them again.
  int texture_version() const { return texture_version_; }

  // Robot commands, held until changed. Base velocity is in the robot frame
  // (m/s, m/s, rad/s) and is re-projected to the world every physics step.
  void command_base_velocity(double forward, double left, double turn);
  // Position target of an actuated joint, clamped to its range, and the
  // velocity it is moving at (torso and arm): the drive feeds forward the
  // force the joint's damping takes at that velocity, as it does gravity, so
  // the servo corrects only the tracking error (a trajectory's speed is not
  // capped at force limit / damping). 0: holding still.
  void command_position(const RobotJoint& joint, double target, double velocity = 0);
  double commanded_position(const RobotJoint& joint) const;

  struct StepReport {
    bool diverged = false;       // MuJoCo found bad accelerations (or failed mid-step) and the state was reset
    bool grasp_refused = false;  // the gripper closed on an object over the mass limit
  };
  // Runs `substeps` physics steps of 1/120 s.
  StepReport step(int substeps);

  // A scratch mjData for what-if queries (the primitives' collision checks),
  // made on first use and kept: mj_makeData of a large scene costs
  // milliseconds. Its contents are whatever the last user left.
  mjData_* scratch() const;

  // Extended object states (temperature, soaked, dirt, toggles, ...).
  ObjectStates& states() { return states_; }
  const ObjectStates& states() const { return states_; }
  // Off: states stay as they are (Table A.10's "- Object State Update" row).
  void set_state_updates(bool enabled) { state_updates_ = enabled; }
  bool state_updates() const { return state_updates_; }

  // Sleeping (MuJoCo's, world/sleeping.hpp), on unless turned off: objects
  // at rest sleep out of physics until something awake touches them. Turning
  // it off wakes them all and recomputes the contacts (mj_forward). reset()
  // keeps the setting.
  void set_sleeping(bool enabled);
  bool sleeping() const;
  // Objects with moving bodies whose every tree sleeps (furniture in static
  // bodies never counts), after the last step.
  int sleepers() const;
  bool asleep(int object) const;
  // The resting contacts of sleepers, which MuJoCo's contact list leaves out
  // (contact predicates read both).
  const RestingContacts& resting_contacts() const { return resting_; }

  // Index into scene().objects() of the object held by the gripper, or -1.
  // A drawer or door held by its handle counts as grasping its object.
  int grasped_object() const { return grasped_; }
  // The body the gripper holds (an object's root or an articulated link), or -1.
  int grasped_body() const;
  // The free object the hand carries (held by its root, not a drawer's handle), or -1.
  int carried_object() const;
  // The equality constraint of the current grasp (its eq_data holds the grip), or -1.
  int grasp_weld() const { return grasped_weld_; }

  // Kinematic move (symbolic primitives): the base, torso and arm jump to the
  // given joint values, their controllers hold them there, velocities are zero,
  // and a held object moves with the gripper. Contacts are recomputed (what
  // the robot now touches wakes).
  void set_robot_configuration(const Pose2& base, const double* torso_and_arm);
  // Kinematic head turn (symbolic primitives), clamped to the joints' ranges:
  // its controllers hold it there. The head touches nothing: only the poses
  // of bodies and cameras are recomputed.
  void set_head(double pan, double tilt);
  // Moves the held free object, in `d` after mj_kinematics, to where the grasp
  // holds it relative to the gripper; true if it moved one (then kinematics
  // must run again).
  bool carry_grasped(mjData_* d) const;
  // Gripper command: open (the assistive grasp releases) or closed.
  void command_gripper(bool open);
  // Symbolic grasping: attaches free object `object` to the hand where it is
  // now, as the assistive grasp would; false (nothing attached) over the mass limit.
  bool hold(int object);
  // Lets go of whatever the hand holds.
  void release();
  // Attaches `object` to `to` where they are now, through their
  // Scene::attachments() weld; false when the scene has none for the pair.
  // reset() detaches all.
  bool attach_objects(int object, int to);

  // Objects that transitions make and use up (world/transitions.hpp). MuJoCo's
  // models are static, so an object that is not real (not yet made, or used
  // up) is a body kept out of the world: far under the floor, colliding with
  // nothing, held still after every step. Only free objects can be hidden.
  // reset() makes every object real again.
  void hide(int object);
  // Makes a hidden object real, at rest, at `pos` in the orientation the scene
  // compiled it in.
  void reveal(int object, const Eigen::Vector3d& pos);
  bool real(int object) const { return !hidden_.at(object); }
  Pose2 base_pose() const;
  double time() const;

 private:
  void update_grasp(StepReport& report);
  // Joint values and controller targets of a kinematic move, the load carried, kinematics.
  void pose_robot(const Pose2& base, const double* torso_and_arm);
  // mj_resetData, keeping the resting contacts of the objects it puts to sleep.
  void reset_data();
  void attach(int object, int weld);
  // Sets `weld` (body1 -> body2) to hold body2 where it is now relative to body1, and turns it on.
  void hold_in_place(int weld);
  // Keeps a hidden object at its place out of the world, at rest.
  void keep_out(int object);
  // Marks a hidden object real, colliding as compiled (where it is is the caller's).
  void make_real(int object);

  std::shared_ptr<const Scene> scene_;
  mjModel_* model_ = nullptr;
  mjData_* data_ = nullptr;
  std::optional<Robot> robot_;
  double base_command_[3] = {0, 0, 0};
  int grasped_ = -1, grasped_weld_ = -1;
  ObjectStates states_;
  bool state_updates_ = true;
  RestingContacts resting_;
  std::vector<std::vector<int>> object_trees_;  // per object, the trees of its moving bodies
  std::vector<char> hidden_;                    // per object: not real (hide())
  int texture_version_ = 0;
  mutable mjData_* scratch_ = nullptr;
  std::vector<double> payload_jacobian_;  // 3 x nv, for the load's gravity compensation
  std::vector<double> velocity_command_;  // per actuator, m/s or rad/s
};

}  // namespace chore
