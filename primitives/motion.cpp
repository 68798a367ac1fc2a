#include "primitives/motion.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "primitives/arm_planner.hpp"
#include "primitives/base_planner.hpp"
#include "primitives/trajectory.hpp"
#include "world/object_geometry.hpp"
#include "world/state_rules.hpp"

namespace chore {
namespace {

constexpr int kSubsteps = 4;  // physics steps per control step, as the env's
constexpr double kControlDt = kSubsteps / 120.0;
constexpr double kLineSpacing = 0.01;                        // m between IK waypoints of a line
constexpr double kBackOffSpeed = 0.2;                        // m/s of the hand drawn back from where it worked
constexpr double kArmSpeed = 1.5, kArmAcceleration = 4.0;    // rad/s, rad/s^2 (torso: m/s, a tenth)
constexpr double kBaseSpeed = 1.0, kBaseAcceleration = 1.0;  // m/s (the Tiago's top speed), m/s^2 (heading: 2x, rad)
constexpr double kArmTolerance = 0.03;                       // rad: a motion has arrived
constexpr double kBaseTolerance = 0.04;                      // m (and 2x in rad)
constexpr double kLineTolerance = 0.01;                      // rad: a line's last waypoint is reached
constexpr int kSettleSteps = 30;                             // control steps allowed to arrive after a trajectory

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

Eigen::VectorXd to_vector(const ArmConfiguration& q) {
  return Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size()));
}

// The drives feed forward the damping force at the commanded velocity
// (World::command_position), so the speed limit is the robot's, not what a
// servo sustains against the joint's damping (0.67 rad/s for arm_1).
TrajectoryLimits arm_limits(double speed_scale) {
  TrajectoryLimits limits;
  limits.max_velocity = Eigen::VectorXd::Constant(1 + Robot::kArmJoints, kArmSpeed * speed_scale);
  limits.max_acceleration = Eigen::VectorXd::Constant(1 + Robot::kArmJoints, kArmAcceleration);
  limits.max_velocity[0] *= 0.1;  // the torso lifts in metres
  limits.max_acceleration[0] *= 0.1;
  return limits;
}

// Commands the torso and arm to `q`, reached from `previous` in `seconds`.
void command_arm(World& world, const Eigen::VectorXd& q, const Eigen::VectorXd& previous, double seconds) {
  const auto joints = world.robot()->torso_and_arm();
  for (size_t k = 0; k < joints.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    world.command_position(*joints[k], q[i], (q[i] - previous[i]) / seconds);
  }
}

// Holds the torso and arm at `q`, still.
void hold_arm(World& world, const ArmConfiguration& q) {
  const auto joints = world.robot()->torso_and_arm();
  for (size_t k = 0; k < joints.size(); ++k) world.command_position(*joints[k], q[k]);
}

}  // namespace

// Tucked: Robot::kTuckedArm. Untucked: the hand 0.6 m ahead at 0.8 m, pointing
// forward. Carry: the hand up and close in front of the torso, pointing down, so
// a held object stays inside a small footprint while the robot drives.
const ArmConfiguration kTuckedConfiguration = {Robot::kHomeTorso, 0.12, -1.45, -1.06, 2.13, 1.23, -1.26, -1.00};
const ArmConfiguration kUntuckedConfiguration = {0.15, 0.74, -0.61, -0.28, 2.06, -0.63, -1.29, -0.07};
const ArmConfiguration kCarryConfiguration = {0.35, 0.85, 0.20, -0.08, 2.19, 1.69, -1.39, -0.07};
namespace {
ArmConfiguration carry_turned(double shoulder) {
  ArmConfiguration q = kCarryConfiguration;
  q[1] = shoulder;  // arm_1, about the vertical (0.07 to 2.68 rad)
  return q;
}
}  // namespace
const std::array<ArmConfiguration, 5> kCarryConfigurations = {kCarryConfiguration, carry_turned(1.3), carry_turned(0.4),
                                                              carry_turned(1.7), carry_turned(0.1)};
// The low and high starts: solutions for the hand pointing down 0.5 m ahead
// at 0.12 m and 0.7 m ahead at 1.15 m, found from random starts.
const std::array<ArmConfiguration, 3> kReachStarts = {
    kUntuckedConfiguration,
    ArmConfiguration{0.03, 1.63, -0.95, 1.50, -0.28, 0.08, -0.34, -2.07},
    ArmConfiguration{0.35, 1.24, 0.75, -0.71, 1.17, -0.60, 1.39, 0.76},
};

Motion::Motion(World& world, const PrimitiveOptions& options, uint64_t seed, int look_at, PrimitiveResult& result)
    : world_(world), options_(options), seeds_(seed), result_(result), ik_(world), look_at_(look_at) {}

bool Motion::fail(PrimitiveStatus status, const std::string& reason) {
  result_.status = status;
  result_.reason = reason;
  return false;
}

void Motion::step_physics(int env_steps) {
  const Clock::time_point start = Clock::now();
  for (int i = 0; i < env_steps && !result_.diverged; ++i) {
    look_at_object();
    const World::StepReport report = world_.step(kSubsteps);
    result_.physics_steps += kSubsteps;
    result_.diverged |= report.diverged;
    result_.grasp_refused |= report.grasp_refused;
  }
  result_.execution_seconds += since(start);
}

void Motion::look_at_object() {
  if (!world_.real(look_at_)) return;  // used up by a transition (a cut apple): the head stays
  const Robot& r = *world_.robot();
  const mjModel* m = world_.model();
  const mjData* d = world_.data();
  const Eigen::Vector3d target = object_aabb(world_, look_at_).center();
  const double* pan_axis = d->xpos + 3 * m->jnt_bodyid[r.head_pan.joint];
  const double* tilt_axis = d->xpos + 3 * m->jnt_bodyid[r.head_tilt.joint];
  const double yaw = world_.base_pose().yaw, dx = target.x() - pan_axis[0], dy = target.y() - pan_axis[1];
  const double forward = std::cos(yaw) * dx + std::sin(yaw) * dy, left = std::cos(yaw) * dy - std::sin(yaw) * dx;
  const double pan = std::atan2(left, forward);
  const double tilt = std::atan2(target.z() - tilt_axis[2], std::hypot(forward, left));  // up is positive
  if (physical()) {
    world_.command_position(r.head_pan, pan);
    world_.command_position(r.head_tilt, tilt);
  } else {
    world_.set_head(pan, tilt);
  }
}

Eigen::Vector3d Motion::hand_position() const {
  const double* p = world_.data()->site_xpos + 3 * world_.robot()->gripper_site;
  return {p[0], p[1], p[2]};
}

Eigen::Vector3d Motion::hand_axis(int column) const {
  const double* r = world_.data()->site_xmat + 9 * world_.robot()->gripper_site;
  return {r[column], r[3 + column], r[6 + column]};
}

bool Motion::hand_in_contact() const {
  const mjModel* m = world_.model();
  const mjData* d = world_.data();
  const Robot& r = *world_.robot();
  const int held = world_.grasped_body();
  const int robot = m->body_rootid[r.gripper_body];
  const auto hand = [&](int body) {
    return body == r.gripper_body || body == r.left_finger_body || body == r.right_finger_body ||
           (held >= 0 && (body == held || m->body_rootid[body] == m->body_rootid[held]));
  };
  for (int c = 0; c < d->ncon; ++c) {
    const int b1 = m->geom_bodyid[d->contact[c].geom[0]], b2 = m->geom_bodyid[d->contact[c].geom[1]];
    const bool robot1 = m->body_rootid[b1] == robot || hand(b1), robot2 = m->body_rootid[b2] == robot || hand(b2);
    if ((hand(b1) && !robot2) || (hand(b2) && !robot1)) return true;
  }
  return false;
}

size_t Motion::settle_arm(const ArmConfiguration& goal, double tolerance) {
  size_t worst = 0;
  for (int i = 0; i <= kSettleSteps; ++i) {
    const ArmConfiguration now = arm_configuration(world_);
    double error = 0;
    for (size_t k = 0; k < goal.size(); ++k) {
      if (std::abs(now[k] - goal[k]) > error) error = std::abs(now[k] - goal[k]), worst = k;
    }
    if (error < tolerance) return goal.size();
    if (i < kSettleSteps) step_physics(1);
  }
  return worst;
}

bool Motion::track_arm(const std::vector<ArmConfiguration>& path, double speed_scale) {
  const Clock::time_point start = Clock::now();
  std::vector<Eigen::VectorXd> points;
  for (const ArmConfiguration& q : path) points.push_back(to_vector(q));
  ArmCollisionChecker checker(world_);
  const Trajectory trajectory =
      make_trajectory(points, arm_limits(speed_scale), kControlDt, 0.05,
                      [&checker](const Eigen::VectorXd& q) { return !checker.collides(q.data()); });
  result_.planning_seconds += since(start);
  for (size_t i = 0; i < trajectory.samples.size(); ++i) {
    command_arm(world_, trajectory.samples[i], trajectory.samples[i > 0 ? i - 1 : 0], kControlDt);
    step_physics(1);
    if (result_.diverged) return fail(PrimitiveStatus::motion_planning_failure, "physics diverged");
  }
  const ArmConfiguration& goal = path.back();
  hold_arm(world_, goal);
  const size_t worst = settle_arm(goal, kArmTolerance);
  if (worst == goal.size()) return true;
  // Which joint lagged, and by how much, tells a blocked arm from a weak one.
  const char* name = mj_id2name(world_.model(), mjOBJ_JOINT, world_.robot()->torso_and_arm()[worst]->joint);
  return fail(PrimitiveStatus::motion_planning_failure,
              "the arm did not reach its goal (blocked): " + std::string(name ? name : "?") + " " +
                  std::to_string(goal[worst] - arm_configuration(world_)[worst]) + " rad short");
}

bool Motion::arm_to(const ArmConfiguration& goal) {
  if (!physical()) {
    // Symbolic: the end state, when it is collision-free (no path search, as
    // OmniGibson's symbolic primitives teleport).
    const Clock::time_point t = Clock::now();
    const bool blocked = arm_in_collision(world_, goal);
    result_.planning_seconds += since(t);
    if (blocked) return fail(PrimitiveStatus::motion_planning_failure, "the arm's goal configuration is in collision");
    const Clock::time_point e = Clock::now();
    world_.set_robot_configuration(world_.base_pose(), goal.data());
    result_.execution_seconds += since(e);
    return true;
  }
  // Touching something (after a grasp or a stroke): back off along the approach first.
  if (arm_in_collision(world_, arm_configuration(world_))) line(-hand_axis(0) * 0.05, false, kBackOffSpeed, 0.0);
  const Clock::time_point start = Clock::now();
  const ArmPath path = plan_arm_path(world_, goal, next_seed(), options_.arm_iterations);
  result_.planning_seconds += since(start);
  if (!path.success) return fail(PrimitiveStatus::motion_planning_failure, path.reason);
  return track_arm(path.waypoints, 1.0);
}

bool Motion::base_to(const Pose2& goal, const Footprint& footprint) {
  const Clock::time_point start = Clock::now();
  const BasePath path = plan_base_path(world_, footprint, goal, next_seed(), options_.base_iterations);
  result_.planning_seconds += since(start);
  if (!path.success) return fail(PrimitiveStatus::motion_planning_failure, path.reason);
  if (!physical()) {
    const Clock::time_point t = Clock::now();
    world_.set_robot_configuration(goal, arm_configuration(world_).data());
    result_.execution_seconds += since(t);
    return true;
  }
  // Headings unwrapped along the path, so the trajectory turns the short way.
  std::vector<Eigen::VectorXd> points;
  double yaw = world_.base_pose().yaw;
  for (const Pose2& p : path.waypoints) {
    yaw += std::remainder(p.yaw - yaw, 2 * M_PI);
    points.push_back(Eigen::Vector3d(p.x, p.y, yaw));
  }
  points.front() = Eigen::Vector3d(world_.base_pose().x, world_.base_pose().y, world_.base_pose().yaw);
  TrajectoryLimits limits;
  limits.max_velocity = Eigen::Vector3d(kBaseSpeed, kBaseSpeed, 2 * kBaseSpeed);
  limits.max_acceleration = Eigen::Vector3d(kBaseAcceleration, kBaseAcceleration, 2 * kBaseAcceleration);
  const Clock::time_point t = Clock::now();
  const Trajectory trajectory =
      make_trajectory(points, limits, kControlDt, OccupancyMap::kResolution, [&footprint](const Eigen::VectorXd& p) {
        return footprint.free({p[0], p[1], p[2]});
      });
  result_.planning_seconds += since(t);
  // Velocity commands towards the next sample, from where the base is now:
  // feed-forward and feedback in one.
  auto drive_towards = [&](const Eigen::Vector3d& target) {
    const Pose2 now = world_.base_pose();
    const double vx = (target[0] - now.x) / kControlDt, vy = (target[1] - now.y) / kControlDt;
    const double turn = std::remainder(target[2] - now.yaw, 2 * M_PI) / kControlDt;
    const double c = std::cos(now.yaw), s = std::sin(now.yaw);
    world_.command_base_velocity(c * vx + s * vy, -s * vx + c * vy, turn);
    step_physics(1);
  };
  for (size_t k = 1; k < trajectory.samples.size() && !result_.diverged; ++k) {
    drive_towards(trajectory.samples[k]);
  }
  const Eigen::Vector3d end = trajectory.samples.back();
  for (int i = 0; i < kSettleSteps && !result_.diverged; ++i) {
    const Pose2 now = world_.base_pose();
    if (std::hypot(end[0] - now.x, end[1] - now.y) < kBaseTolerance &&
        std::abs(std::remainder(end[2] - now.yaw, 2 * M_PI)) < 2 * kBaseTolerance) {
      break;
    }
    // Gentler gains while settling: a tenth of the distance per step.
    const Eigen::Vector3d p(now.x, now.y, now.yaw);
    Eigen::Vector3d towards = p + 0.3 * (end - p);
    towards[2] = now.yaw + 0.3 * std::remainder(end[2] - now.yaw, 2 * M_PI);
    drive_towards(towards);
  }
  world_.command_base_velocity(0, 0, 0);
  step_physics(2);  // come to rest
  if (result_.diverged) return fail(PrimitiveStatus::motion_planning_failure, "physics diverged");
  const Pose2 now = world_.base_pose();
  if (std::hypot(end[0] - now.x, end[1] - now.y) > 3 * kBaseTolerance) {
    return fail(PrimitiveStatus::motion_planning_failure, "the base did not reach its goal (blocked)");
  }
  return true;
}

bool Motion::line(const Eigen::Vector3d& delta, bool until_contact, double speed, double min_fraction) {
  const Eigen::Vector3d from = hand_position(), approach = hand_axis(0);
  // The approach axis is held; the roll about it may drift (the IK steps from
  // the last solution, so it barely does), which keeps long lines feasible.
  return follow(
      [&](double f) {
        return IkTarget{from + delta * f, approach, std::nullopt};
      },
      delta.norm(), "a line", until_contact, speed, min_fraction);
}

bool Motion::arc(const Eigen::Vector3d& pivot, const Eigen::Vector3d& axis, double angle, bool until_contact,
                 double speed, double min_fraction, bool turn_hand) {
  const Eigen::Vector3d from = hand_position(), approach = hand_axis(0), unit = axis.normalized();
  const Eigen::Vector3d radial = from - pivot - unit * unit.dot(from - pivot);
  const auto turned = [&](double f) {
    const Eigen::Matrix3d r = Eigen::AngleAxisd(angle * f, unit).toRotationMatrix();
    return IkTarget{pivot + r * (from - pivot), turn_hand ? std::optional<Eigen::Vector3d>(r * approach) : std::nullopt,
                    std::nullopt};
  };
  return follow(turned, std::abs(angle) * radial.norm(), "an arc", until_contact, speed, min_fraction);
}

bool Motion::follow(const std::function<IkTarget(double)>& target_at, double length, const char* what,
                    bool until_contact, double speed, double min_fraction) {
  touched_ = false;
  const Clock::time_point start = Clock::now();
  const int n = std::max(1, static_cast<int>(std::ceil(length / kLineSpacing)));
  IkOptions options;
  options.start = arm_configuration(world_);
  options.iterations = 100;
  std::vector<ArmConfiguration> path = {*options.start};
  bool cut_short = false;
  int reached = n;
  for (int i = 1; i <= n; ++i) {
    const IkResult r = ik_.solve(target_at(static_cast<double>(i) / n), options);
    if (!r.success) {
      // As far as the arm reaches; with until_contact, contact decides below.
      cut_short = true;
      reached = i - 1;
      if (until_contact || i > min_fraction * n) break;
      result_.planning_seconds += since(start);
      return fail(PrimitiveStatus::motion_planning_failure, std::string("the hand cannot follow ") + what + " beyond " +
                                                                std::to_string(100 * (i - 1) / n) + "% of its " +
                                                                std::to_string(length) + " m (" + r.reason + ")");
    }
    path.push_back(r.joints);
    options.start = r.joints;
  }
  result_.planning_seconds += since(start);
  if (!physical()) {
    // Waypoint by waypoint: the hand stops at the first contact. The state
    // rules run at every waypoint while the hand holds something they act on
    // (a tool soaking or wiping), on the load's contacts and box from the
    // collision checker (the world is posed once, at the end); otherwise
    // once, over the motion's time.
    const Clock::time_point t = Clock::now();
    const double dt = kLineSpacing / speed;
    const int held = world_.carried_object();
    const ObjectAbilities* load = held >= 0 ? world_.states().abilities(held) : nullptr;
    const bool rules_along =
        world_.state_updates() && load && (load->soakable || load->cleaning_tool || !load->removes.empty());
    std::optional<ArmCollisionChecker> checker;
    if (until_contact || rules_along) checker.emplace(world_);
    std::vector<mjContact> contacts;
    size_t last = 0;
    for (size_t i = 1; i < path.size(); ++i) {
      last = i;
      if (until_contact && checker->hand_touches(path[i])) touched_ = true;
      if (rules_along) {
        const Aabb box = checker->load_contacts(path[i], contacts);
        update_states_at_motion_waypoint(world_, dt, held, box, contacts);
      }
      if (touched_) break;
    }
    world_.set_robot_configuration(world_.base_pose(), path[last].data());
    if (!rules_along && world_.state_updates())
      update_states_after_physics_step(world_, dt * static_cast<double>(last));
    result_.execution_seconds += since(t);
    return touched_ || !cut_short || !until_contact || reached >= min_fraction * n - 1e-9 ||
           fail(PrimitiveStatus::motion_planning_failure, "the hand cannot reach the contact: IK stops after " +
                                                              std::to_string(reached) + " of " + std::to_string(n) +
                                                              " cm");
  }
  // Each waypoint is kLineSpacing apart: reached in kLineSpacing / speed seconds.
  const double waypoint_time = kLineSpacing / speed;
  const int per_waypoint = std::max(1, static_cast<int>(std::round(waypoint_time / kControlDt)));
  for (size_t i = 1; i < path.size() && !touched_; ++i) {
    // Several waypoints per control step when fast, several steps per waypoint when slow.
    for (int s = 0; s < per_waypoint; ++s) {
      command_arm(world_, to_vector(path[i]), to_vector(path[i - 1]), per_waypoint * kControlDt);
      step_physics(1);
      if (result_.diverged) return fail(PrimitiveStatus::motion_planning_failure, "physics diverged");
      if (until_contact && hand_in_contact()) {
        touched_ = true;
        break;
      }
    }
  }
  if (touched_) {
    // Stop pressing: hold where the arm is.
    hold_arm(world_, arm_configuration(world_));
  } else if (!result_.diverged) {
    // The controllers lag the waypoints: let the arm arrive where the line
    // ends (a grasp closed short of it closes on nothing).
    hold_arm(world_, path.back());
    settle_arm(path.back(), kLineTolerance);
  }
  return touched_ || !cut_short || !until_contact || reached >= min_fraction * n - 1e-9 ||
         fail(PrimitiveStatus::motion_planning_failure, "the hand cannot reach the contact: IK stops after " +
                                                            std::to_string(reached) + " of " + std::to_string(n) +
                                                            " cm");
}

bool Motion::base_line(const Eigen::Vector3d& delta, double speed) {
  const Pose2 from = world_.base_pose();
  return base_path(
      [&](double f) {
        return Pose2{from.x + f * delta.x(), from.y + f * delta.y(), from.yaw};
      },
      delta.norm(), speed, 1.0, "no room to back the base out");
}

bool Motion::base_arc(const Eigen::Vector3d& pivot, double angle, int moving, double speed, double min_fraction) {
  const Pose2 from = world_.base_pose();
  const double dx = from.x - pivot.x(), dy = from.y - pivot.y();
  const auto turned = [&](double f) {
    const double c = std::cos(angle * f), s = std::sin(angle * f);
    return Pose2{pivot.x() + c * dx - s * dy, pivot.y() + s * dx + c * dy, from.yaw + angle * f};
  };
  return base_path(turned, std::abs(angle) * std::hypot(dx, dy), speed, min_fraction, "no room to swing the base round",
                   moving);
}

bool Motion::base_path(const std::function<Pose2(double)>& pose_at, double length, double speed, double min_fraction,
                       const char* blocked, int moving) {
  // As far along as the body's map is free.
  double reached = 1.0;
  {
    const Clock::time_point t = Clock::now();
    const Footprint footprint(world_, moving);
    const int n = std::max(1, static_cast<int>(std::ceil(length / OccupancyMap::kResolution)));
    for (int i = 1; i <= n; ++i) {
      const double f = static_cast<double>(i) / n;
      const Pose2 p = pose_at(f);
      if (!footprint.body_map().free(p.x, p.y)) {
        reached = static_cast<double>(i - 1) / n;
        break;
      }
    }
    result_.planning_seconds += since(t);
    if (reached < min_fraction) return fail(PrimitiveStatus::motion_planning_failure, blocked);
    if (reached <= 0) return true;  // (min_fraction 0: as far as it goes, here nowhere)
  }
  const auto along = [&](double f) { return reached < 1.0 ? pose_at(f * reached) : pose_at(f); };
  if (!physical()) {
    const Clock::time_point t = Clock::now();
    world_.set_robot_configuration(along(1.0), arm_configuration(world_).data());
    result_.execution_seconds += since(t);
    return true;
  }
  const int steps = std::max(1, static_cast<int>(std::ceil(length * reached / speed / kControlDt)));
  for (int i = 1; i <= steps && !result_.diverged; ++i) {
    const Pose2 to = along(static_cast<double>(i) / steps);
    const Pose2 now = world_.base_pose();
    const double vx = (to.x - now.x) / kControlDt, vy = (to.y - now.y) / kControlDt;
    const double c = std::cos(now.yaw), s = std::sin(now.yaw);
    world_.command_base_velocity(c * vx + s * vy, -s * vx + c * vy,
                                 std::remainder(to.yaw - now.yaw, 2 * M_PI) / kControlDt);
    step_physics(1);
  }
  world_.command_base_velocity(0, 0, 0);
  step_physics(2);
  if (result_.diverged) return fail(PrimitiveStatus::motion_planning_failure, "physics diverged");
  return true;
}

void Motion::gripper(bool open) {
  world_.command_gripper(open);
  if (physical()) {
    step_physics(8);
  } else if (open) {
    world_.release();  // symbolic grasps are made by the primitive (World::hold)
  }
}

void Motion::wait(double seconds) {
  if (physical()) {
    step_physics(static_cast<int>(std::ceil(seconds / kControlDt)));
    return;
  }
  // Symbolically the time passes in one go: the rules of a physics step and
  // of an env step (a source toggled on fills itself, heat flows).
  if (world_.state_updates()) {
    update_states_after_physics_step(world_, seconds);
    update_states_after_env_step(world_, seconds);
  }
}

bool Motion::tuck() {
  if (world_.carried_object() < 0) return arm_to(kTuckedConfiguration);
  // One checker for the five (what it checks against stands still while the
  // arm alone moves): tuck ends every manipulation.
  const auto free_carry = [&]() -> const ArmConfiguration* {
    ArmCollisionChecker checker(world_);
    for (const ArmConfiguration& q : kCarryConfigurations) {
      if (!checker.collides(q.data())) return &q;
    }
    return nullptr;
  };
  const ArmConfiguration* carry = free_carry();
  if (!carry) {
    // The hand still inside what it took the load from (a fridge's shelf, a
    // cabinet): drawn back level towards the base, as far as the carry pose's
    // reach or the first touch, first.
    constexpr double kCarryReach = 0.45;  // m from the base's centre
    const Pose2 base = world_.base_pose();
    const Eigen::Vector3d hand = hand_position();
    const Eigen::Vector3d back(base.x - hand.x(), base.y - hand.y(), 0.0);
    if (back.norm() > kCarryReach + kLineSpacing) {
      line(back.normalized() * (back.norm() - kCarryReach), false, kBackOffSpeed, 0.0);
      if (result_.diverged) return false;
      result_.status = PrimitiveStatus::success;
      result_.reason.clear();
      carry = free_carry();
    }
  }
  return arm_to(carry ? *carry : kCarryConfiguration);  // failing, it says why
}

}  // namespace chore
