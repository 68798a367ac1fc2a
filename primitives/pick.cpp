// pick(object): to the object's pre-pose, along the approach until the
// fingers touch it, close (the assistive grasp holds what lies between
// them), lift and tuck into the carry pose.
#include <algorithm>
#include <cmath>
#include <limits>

#include "primitives/primitive_def.hpp"
#include "world/object_geometry.hpp"

namespace chore {
namespace {

constexpr double kSlim = 0.08;           // m: objects this narrow fit between the open fingers
constexpr double kUpright = 0.08;        // m: objects this tall are taken from the side too
constexpr double kNearSideInset = 0.05;  // m in from a wide object's edge its near side is taken at
constexpr double kFlat = 0.1;            // m: objects this low are taken by their near side too

bool applies(const World& w, int object) {
  const SceneObject& o = w.scene().objects().at(object);
  return !o.fixed && o.grasp_weld >= 0 && w.model()->body_subtreemass[o.body] <= World::kGraspMassLimit;
}

std::string unmet_precondition(const World& w, int object) {
  if (w.grasped_object() >= 0) return "the hand is not empty";
  // Fixed objects cannot be picked; a heavy one is refused by the grasp itself.
  return w.scene().objects()[object].fixed ? "'" + w.scene().objects()[object].name + "' cannot be picked up" : "";
}

// From above, or for upright objects from the side, the fingers closing
// horizontally: the arm reaches 0.3-1.0 m out from the side at counter
// height, 0.3-0.75 m pointing down (Ik.SideReachesFartherThanFromAbove): a
// pot at the back of a counter. A slim one sits between the fingers; on a
// wider one both fingertips touch its side, which the assistive grasp holds
// as it holds a wide object touched from above.
std::vector<Approach> approaches(const World& w, int object, const Pose2& base) {
  std::vector<Approach> out = {{top_centre(w, object, base), kDown, std::nullopt}};
  const Aabb box = object_aabb(w, object);
  const Eigen::Vector3d size = box.hi - box.lo;
  Eigen::Vector3d towards(box.center().x() - base.x, box.center().y() - base.y, 0);
  // (A wider one only where nothing from above reaches: a container held
  // by its side dips and pours lower. Not a cloth: the assistive grasp holds
  // it by its centre, which is reached from above.)
  const bool slim = std::max(size.x(), size.y()) <= kSlim;
  const bool cloth = !w.scene().objects()[object].keypoints.empty();
  if (cloth || towards.norm() < 1e-6) return out;
  towards.normalize();
  if (size.z() >= kUpright) {
    const Eigen::Vector3d point(box.center().x(), box.center().y(), box.lo.z() + 0.6 * size.z());
    out.push_back({point - towards * std::max(size.x(), size.y()) / 2, towards, kUp.cross(towards), !slim});
  }
  // Tilted 45 degrees towards it where no pose has room above to point
  // down (a shelf over it, a cabinet's top): the fingers close across.
  out.push_back({out.front().point, tilted_towards(towards), kUp.cross(towards), true});
  // A wide flat one also by its near side, from above, on its surface there
  // (a sheet of paper or a hammer on the floor: pointing down at the floor
  // the hand reaches 0.4 m from the base's centre, 0.1 m past its edge, not
  // the middle). Along the line from its centre to the base: a box's corner
  // may hold nothing of a bottle lying there. (Not a pumpkin: taken by its
  // near side from above, the paper's StoreDecoration failed at seed 5.)
  const double half_across = box.half_across(towards);
  if (size.z() <= kFlat && half_across > kNearSideInset + kSlim / 2) {
    const Eigen::Vector3d above =
        box.center() - towards * (half_across - kNearSideInset) + Eigen::Vector3d(0, 0, size.z() / 2 + kClearance);
    const double down = ray_to_object(w, object, above, kDown, size.z() + kClearance);
    if (down >= 0) out.push_back({above + kDown * down, kDown, std::nullopt, true});
  }
  return out;
}

bool act(Executor& e) {
  World& w = e.world();
  Motion& m = e.motion();
  const int object = e.object();
  if (!e.go_to_pre_pose()) return false;
  // Towards the object until contact: through its height from above, its width from the side.
  const Aabb box = object_aabb(w, object);
  // Within a waypoint (1 cm) of the contact point reach() checked, the line
  // may end without a touch: a slim object taken from the side sits between
  // the open fingers.
  const Approach& a = e.approach();
  const double extent = std::abs(a.direction.dot(box.hi - box.lo));
  const double length = kClearance + extent + 0.02;
  const double needed = kClearance + contact_depth(w, object, a) - 0.01;
  if (!m.line(a.direction * length, true, kApproachSpeed, needed / length)) return false;
  m.gripper(false);
  if (!m.physical()) {
    // The assistive grasp's condition, kinematically: the object between the
    // fingers, within 5 cm of them from the hand's centre to their tips. (Of
    // the centre alone, an upright broom taken from the side at a slant was
    // 5.2 cm off when the fingertips touched its face.)
    const Eigen::Vector3d hand = m.hand_position(), tips = hand + m.hand_axis(0) * kFingerReach;
    double gap = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 4; ++i) {
      const Eigen::Vector3d p = hand + (tips - hand) * (i / 4.0);
      gap = std::min(gap, (p.cwiseMax(box.lo).cwiseMin(box.hi) - p).norm());
    }
    if (gap < 0.05 && !w.hold(object)) e.result().grasp_refused = true;
  }
  if (w.grasped_object() != object) {
    m.gripper(true);
    m.line(kUp * kLift, false, kRetreatSpeed, 0.0);
    return e.fail(PrimitiveStatus::grasp_failure,
                  e.result().grasp_refused ? "'" + e.name() + "' is too heavy to hold" : "the hand closed on nothing");
  }
  m.line(kUp * kLift, false, kRetreatSpeed, 0.0);  // lift as far as the arm goes; tuck plans the rest
  if (!e.tuck_where_possible()) return false;
  if (w.grasped_object() != object) return e.fail(PrimitiveStatus::grasp_failure, "'" + e.name() + "' slipped out");
  return true;
}

// Symbolically: into the empty hand, from wherever it was.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const int agent = agent_index(objects);
  if (agent < 0 || !objects[a.target].movable()) return {};
  SymbolicStep s;
  s.needs = {literal(kHandEmpty, {}), literal(kWithinReach, {a.target}), literal("real", {a.target})};
  s.deletes = {literal(kHandEmpty, {})};
  end_placements(objects, a.target, s);
  s.adds = {literal("grasped", {agent, a.target})};
  return only_while_open(objects, a.target, s);
}

}  // namespace

const PrimitiveDef& pick_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .approaches = approaches};
  return def;
}

}  // namespace chore
