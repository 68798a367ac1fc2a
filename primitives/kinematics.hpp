// Forward kinematics of the robot alone, and of the object it carries, on the
// scene's compiled model: the ~30 bodies of the robot instead of the whole
// scene's (90 in the apartment, 837 in the restaurant), so IK and collision
// queries cost the same in every scene. Same arithmetic as mj_kinematics.
// Internal to primitives/.
#pragma once

#include <Eigen/Core>

#include <array>
#include <vector>

#include "world/world.hpp"

namespace chore {

// torso, arm_1 .. arm_7
using ArmConfiguration = std::array<double, 1 + Robot::kArmJoints>;
// The world's current torso and arm joint values.
ArmConfiguration arm_configuration(const World& world);

class RobotKinematics {
 public:
  // Joints other than base, torso and arm (fingers, head), and the carried
  // object's grip, as the world has them now.
  explicit RobotKinematics(const World& world);

  // Base pose and torso/arm configuration; recomputes every pose below.
  void set(const Pose2& base, const ArmConfiguration& q);

  // The gripper site (its x axis is the approach direction, y the closing one).
  Eigen::Vector3d site_position() const;
  Eigen::Matrix3d site_rotation() const;
  // d(site position; site rotation)/d(torso, arm 1..7): 6 x 8.
  Eigen::Matrix<double, 6, 1 + Robot::kArmJoints> site_jacobian() const;

  // Colliding geoms of the robot and of the carried object, and their poses
  // (MuJoCo layout: position 3, row-major rotation 9).
  const std::vector<int>& robot_geoms() const { return robot_geoms_; }
  const std::vector<int>& load_geoms() const { return load_geoms_; }
  void geom_pose(int geom, double* xpos, double* xmat) const;

 private:
  struct BodyPose {
    double pos[3], quat[4];
  };
  void forward(int body, const double* qpos);

  const World& world_;
  std::vector<double> qpos_;                    // the world's positions, robot joints overwritten by set()
  std::vector<int> bodies_;                     // robot bodies, parents first
  std::vector<int> load_bodies_;                // the carried object's bodies, root first
  std::vector<BodyPose> pose_;                  // by body id (only ours are kept up to date)
  std::vector<Eigen::Vector3d> axis_, anchor_;  // world axis/anchor per joint id
  std::vector<int> robot_geoms_, load_geoms_;
  int load_root_ = -1, weld_ = -1;
};

}  // namespace chore
