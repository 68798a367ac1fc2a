#include "primitives/ik.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>

#include "env/world/error.hpp"

namespace chore {

IkResult solve_ik(const World& world, const IkTarget& target, const IkOptions& options) {
  const Robot* robot = world.robot();
  if (!robot) throw Error("ik: the scene has no robot");
  const mjModel* m = world.model();
  std::unique_ptr<mjData, void (*)(mjData*)> scratch(mj_makeData(m), mj_deleteData);
  mj_copyData(scratch.get(), m, world.data());
  mjData* d = scratch.get();

  std::vector<const RobotJoint*> joints;
  if (options.use_torso) joints.push_back(&robot->torso);
  for (const RobotJoint& j : robot->arm) joints.push_back(&j);
  const int n = static_cast<int>(joints.size());
  const int site = robot->gripper_site;
  const int rows = target.approach ? 6 : 3;

  Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor> jacp(3, m->nv), jacr(3, m->nv);
  IkResult result;
  for (int it = 0; it <= options.iterations; ++it) {
    mj_kinematics(m, d);
    mj_comPos(m, d);
    const Eigen::Vector3d p(d->site_xpos[3 * site], d->site_xpos[3 * site + 1], d->site_xpos[3 * site + 2]);
    // The site's x axis is the gripper's approach direction (tiago.xml).
    const Eigen::Vector3d x(d->site_xmat[9 * site], d->site_xmat[9 * site + 3], d->site_xmat[9 * site + 6]);
    Eigen::VectorXd error(rows);
    error.head<3>() = target.position - p;
    result.position_error = error.head<3>().norm();
    result.angle_error = 0;
    if (target.approach) {
      const Eigen::Vector3d want = target.approach->normalized();
      error.tail<3>() = x.cross(want);  // rotation taking x towards want
      result.angle_error = std::acos(std::clamp(x.dot(want), -1.0, 1.0));
    }
    if (result.position_error < options.position_tolerance && result.angle_error < options.angle_tolerance) {
      result.success = true;
      break;
    }
    if (it == options.iterations) break;
    mj_jacSite(m, d, jacp.data(), jacr.data(), site);
    Eigen::MatrixXd jac(rows, n);
    for (int k = 0; k < n; ++k) {
      jac.block(0, k, 3, 1) = jacp.col(joints[k]->dof);
      if (target.approach) jac.block(3, k, 3, 1) = jacr.col(joints[k]->dof);
    }
    // dq = J^T (J J^T + lambda^2 I)^-1 e
    const Eigen::MatrixXd jjt = jac * jac.transpose() +
                                options.damping * options.damping * Eigen::MatrixXd::Identity(rows, rows);
    const Eigen::VectorXd dq = jac.transpose() * jjt.ldlt().solve(error);
    for (int k = 0; k < n; ++k) {
      double& q = d->qpos[joints[k]->qpos];
      q = std::clamp(q + dq[k], joints[k]->low, joints[k]->high);
    }
  }
  for (const RobotJoint* j : joints) result.joints.push_back(d->qpos[j->qpos]);
  if (!result.success) {
    result.reason = "no arm configuration reaches the target: " +
                    std::to_string(result.position_error) + " m and " +
                    std::to_string(result.angle_error) + " rad off after " +
                    std::to_string(options.iterations) + " iterations";
  }
  return result;
}

}  // namespace chore
