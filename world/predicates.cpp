#include "world/predicates.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "world/object_geometry.hpp"

namespace chore {
namespace {

constexpr double kVerticalRange = 5.0;    // m, BEHAVIOR's vertical ray length
constexpr double kHorizontalRange = 1.0;  // m, for inside's horizontal rays
constexpr int kHorizontalAngles = 5;      // directions over [0, pi/2)
constexpr double kOpenFraction = 0.05;
constexpr double kOverlaidShare = 0.5;  // of b's horizontal extent an overlaid cloth covers (OmniGibson's)
constexpr double kDrapeDrop = 0.05;     // m a draped cloth hangs below b's top

const Eigen::Vector3d kUp(0, 0, 1), kDown(0, 0, -1);

bool hits(const World& w, int object, const Eigen::Vector3d& p, const Eigen::Vector3d& dir, double range) {
  return ray_to_object(w, object, p, dir, range) >= 0;
}

}  // namespace

bool touching(const World& w, int a, int b) {
  return in_contact(w, a, b);
}

namespace {
// Where a lies: its box's centre; a cloth's middle tile (a towel hanging
// over a washer's front has its box's centre below the top it lies on).
Eigen::Vector3d lying_point(const World& w, int a) {
  return w.scene().objects()[a].keypoints.empty() ? object_aabb(w, a).center() : object_frame(w, a).pos;
}
}  // namespace

bool ontop(const World& w, int a, int b) {
  const Eigen::Vector3d c = lying_point(w, a);
  return touching(w, a, b) && hits(w, b, c, kDown, kVerticalRange) && !hits(w, b, c, kUp, kVerticalRange);
}

bool inside(const World& w, int a, int b) {
  const Eigen::Vector3d c = object_aabb(w, a).center();
  if (!object_aabb(w, b).contains(c)) return false;
  int axes = hits(w, b, c, kUp, kVerticalRange) && hits(w, b, c, kDown, kVerticalRange);
  bool first = false, second = false;
  for (int k = 0; k < kHorizontalAngles; ++k) {
    const double t = M_PI / 2 * k / kHorizontalAngles;
    const Eigen::Vector3d d(std::cos(t), std::sin(t), 0), e(-std::sin(t), std::cos(t), 0);
    first = first || (hits(w, b, c, d, kHorizontalRange) && hits(w, b, c, -d, kHorizontalRange));
    second = second || (hits(w, b, c, e, kHorizontalRange) && hits(w, b, c, -e, kHorizontalRange));
  }
  return axes + first + second >= 2;
}

bool nextto(const World& w, int a, int b) {
  const Aabb box_a = object_aabb(w, a), box_b = object_aabb(w, b);
  const double threshold = (box_a.extent() + box_b.extent()).mean() / 6.0;
  if (Aabb::gap(box_a, box_b) > threshold) return false;
  const Eigen::Vector3d c = box_a.center();
  const double range = box_a.extent().head<2>().norm() / 2 + threshold + box_b.extent().head<2>().norm();
  for (int k = 0; k < 8; ++k) {
    const double t = M_PI / 4 * k;
    if (hits(w, b, c, Eigen::Vector3d(std::cos(t), std::sin(t), 0), range)) return true;
  }
  return false;
}

bool under(const World& w, int a, int b) {
  const Eigen::Vector3d c = object_aabb(w, a).center();
  return hits(w, b, c, kUp, kVerticalRange) && !hits(w, b, c, kDown, kVerticalRange);
}

bool onfloor(const World& w, int a, int room) {
  const std::vector<int>& floors = w.scene().floor_geoms(room);
  return in_contact_with_geoms(w, a, floors) &&
         ray_to_geoms(w, floors, object_aabb(w, a).center(), kDown, kVerticalRange) >= 0;
}

bool inroom(const World& w, int a, int room) {
  const Eigen::Vector3d c = object_aabb(w, a).center();
  const Room* r = w.scene().room_at(c.x(), c.y());
  return r == &w.scene().rooms()[room];
}

bool is_open(const World& w, int a) {
  const mjModel* m = w.model();
  for (int j : w.scene().objects()[a].joints) {
    const double lo = m->jnt_range[2 * j], hi = m->jnt_range[2 * j + 1];
    if (w.data()->qpos[m->jnt_qposadr[j]] > lo + kOpenFraction * (hi - lo)) return true;
  }
  return false;
}

bool grasped(const World& w, int a) {
  return w.grasped_object() == a;
}

bool infov(const World& w, int a) {
  const Robot* r = w.robot();
  if (!r) return false;
  const mjModel* m = w.model();
  const mjData* d = w.data();
  const int cam = r->camera;
  const Eigen::Vector3d c = object_aabb(w, a).center();
  double rel[3], local[3];
  mju_sub3(rel, c.data(), d->cam_xpos + 3 * cam);
  mju_mulMatTVec3(local, d->cam_xmat + 9 * cam, rel);  // camera frame: looks along -z
  const double depth = -local[2];
  const double half = std::tan(m->cam_fovy[cam] * M_PI / 360.0);
  if (depth <= 0 || std::abs(local[1]) > half * depth || std::abs(local[0]) > half * depth) {
    return false;  // square images: the same half-angle both ways
  }
  // Unoccluded: the first geom along the line of sight belongs to a.
  Eigen::Vector3d dir = c - Eigen::Vector3d(d->cam_xpos[3 * cam], d->cam_xpos[3 * cam + 1], d->cam_xpos[3 * cam + 2]);
  const double distance = dir.norm();
  dir /= distance;
  const mjtByte groups[mjNGROUP] = {1, 0, 0, 1, 0, 0};  // drawn objects and collision geoms
  int geom = -1;
  const double hit = mj_ray(m, d, d->cam_xpos + 3 * cam, dir.data(), groups, 0, m->cam_bodyid[cam], &geom, nullptr);
  return hit >= 0 && geom >= 0 && w.scene().object_of_geom(geom) == a;
}

bool inreach(const World& w, int a) {
  const Robot* r = w.robot();
  if (!r) return false;
  const int shoulder = w.model()->jnt_bodyid[r->arm[0].joint];
  const double* s = w.data()->xpos + 3 * shoulder;
  Aabb point;
  point.lo = point.hi = Eigen::Vector3d(s[0], s[1], s[2]);
  return Aabb::gap(object_aabb(w, a), point) <= 1.0;
}

bool insameroom(const World& w, int a, int b) {
  const Eigen::Vector3d ca = object_aabb(w, a).center(), cb = object_aabb(w, b).center();
  const Room* ra = w.scene().room_at(ca.x(), ca.y());
  return ra && ra == w.scene().room_at(cb.x(), cb.y());
}

namespace {

// The farthest pair of a cloth's corner keypoints over its flat diagonal; -1
// for objects that are not cloths.
double spread(const World& w, int a) {
  const SceneObject& o = w.scene().objects()[a];
  if (o.keypoints.empty()) return -1;
  double widest = 0;
  for (int i : o.keypoints) {
    for (int j : o.keypoints) {
      double d[3];
      mju_sub3(d, w.data()->xpos + 3 * i, w.data()->xpos + 3 * j);
      widest = std::max(widest, mju_norm3(d));
    }
  }
  return widest / o.flat_diagonal;
}

}  // namespace

bool folded(const World& w, int a) {
  const double s = spread(w, a);
  return s >= 0 && s < 0.75;
}

bool unfolded(const World& w, int a) {
  return spread(w, a) > 0.9;
}

bool overlaid(const World& w, int a, int b) {
  if (w.scene().objects()[a].keypoints.empty() || !touching(w, a, b)) return false;
  const Aabb cloth = object_aabb(w, a), under = object_aabb(w, b);
  const Eigen::Vector2d lo = cloth.lo.head<2>().cwiseMax(under.lo.head<2>());
  const Eigen::Vector2d hi = cloth.hi.head<2>().cwiseMin(under.hi.head<2>());
  const double covered = (hi - lo).cwiseMax(0.0).prod(), area = under.extent().head<2>().prod();
  return cloth.center().z() >= under.hi.z() - kDrapeDrop && area > 0 && covered >= kOverlaidShare * area;
}

bool draped(const World& w, int a, int b) {
  if (w.scene().objects()[a].keypoints.empty() || !touching(w, a, b)) return false;
  const Aabb cloth = object_aabb(w, a), over = object_aabb(w, b);
  return cloth.hi.z() >= over.hi.z() && cloth.lo.z() <= over.hi.z() - kDrapeDrop;
}

bool attached(const World& w, int a, int b) {
  const mjModel* m = w.model();
  const mjData* d = w.data();
  const Scene& scene = w.scene();
  const int robot = w.robot() ? m->body_rootid[w.robot()->gripper_body] : -2;
  auto is = [&](int body, int object) {
    return object >= 0 ? scene.object_of_body(body) == object : m->body_rootid[body] == robot;
  };
  for (const Scene::Attachment& at : scene.attachments()) {  // to furniture in the world body too
    if (at.weld >= 0 && d->eq_active[at.weld] && ((at.object == a && at.to == b) || (at.object == b && at.to == a)))
      return true;
  }
  for (int e = 0; e < m->neq; ++e) {
    if (!d->eq_active[e] || (m->eq_type[e] != mjEQ_WELD && m->eq_type[e] != mjEQ_CONNECT)) continue;
    const int b1 = m->eq_obj1id[e], b2 = m->eq_obj2id[e];
    if ((is(b1, a) && is(b2, b)) || (is(b2, a) && is(b1, b))) return true;
  }
  return false;
}

namespace {

// The state and abilities of a tracked object, or nulls.
template <class Test>
bool state_test(const World& w, int a, Test test) {
  const ObjectAbilities* ab = w.states().abilities(a);
  return ab && test(*ab, w.states().state(a));
}

// The particles of `substance` left on a against those sampled, for an object
// that keeps dirt.
template <class Test>
bool dirt_test(const World& w, int a, const std::string& substance, Test test) {
  return state_test(w, a, [&](const auto& ab, const auto& s) {
    const auto left = s.dirt.find(substance);
    const auto sampled = s.dirt_sampled.find(substance);
    return ab.covered && left != s.dirt.end() &&
           test(static_cast<int>(left->second.size()), sampled == s.dirt_sampled.end() ? 0 : sampled->second);
  });
}

}  // namespace

bool cooked(const World& w, int a) {
  return state_test(
      w, a, [](const auto& ab, const auto& s) { return ab.temperature && s.max_temperature >= ab.cook_temperature; });
}
bool burnt(const World& w, int a) {
  return state_test(
      w, a, [](const auto& ab, const auto& s) { return ab.temperature && s.max_temperature >= ab.burn_temperature; });
}
bool frozen(const World& w, int a) {
  return state_test(
      w, a, [](const auto& ab, const auto& s) { return ab.temperature && s.temperature <= ab.freeze_temperature; });
}
bool hot(const World& w, int a) {
  return state_test(
      w, a, [](const auto& ab, const auto& s) { return ab.temperature && s.temperature >= ab.hot_temperature; });
}
bool on_fire(const World& w, int a) {
  return state_test(
      w, a, [](const auto& ab, const auto& s) { return ab.temperature && s.temperature >= ab.ignition_temperature; });
}
// How much of `liquid` a soakable object has absorbed (0 if none or not soakable).
double absorbed(const World& w, int a, const std::string& liquid) {
  double level = 0;
  state_test(w, a, [&](const auto& ab, const auto& s) {
    const auto it = s.soaked.find(liquid);
    level = ab.soakable && it != s.soaked.end() ? it->second : 0;
    return true;
  });
  return level;
}
bool soaked(const World& w, int a, const std::string& liquid) {
  return absorbed(w, a, liquid) >= ObjectStates::kSoakedLevel;
}
bool saturated(const World& w, int a, const std::string& liquid) {
  return absorbed(w, a, liquid) >= ObjectStates::kSaturatedLevel;
}
bool covered(const World& w, int a, const std::string& substance) {
  return dirt_test(w, a, substance, [](int left, int) { return left >= ObjectStates::kCoveredParticles; });
}
bool dirty(const World& w, int a, const std::string& substance) {
  return dirt_test(w, a, substance,
                   [](int left, int sampled) { return left > ObjectStates::kDirtyFraction * sampled; });
}
namespace {
// How high a container holds `substance`, as a fraction of its inner height.
double content_level(const World& w, int a, const std::string& substance) {
  double level = 0;
  state_test(w, a, [&](const auto& ab, const auto& s) {
    const auto it = s.contents.find(substance);
    level = ab.holds_liquid && it != s.contents.end() ? it->second : 0;
    return true;
  });
  return level;
}
}  // namespace
bool filled(const World& w, int a, const std::string& substance) {
  return content_level(w, a, substance) >= ObjectStates::kFilledLevel;
}
bool contains(const World& w, int a, const std::string& substance) {
  return content_level(w, a, substance) > 0;
}
bool substance_exists(const World& w, const std::string& substance) {
  for (const auto& [object, s] : w.states().all_states()) {
    const auto held = s.contents.find(substance);
    const auto dirt = s.dirt.find(substance);
    const auto soaked = s.soaked.find(substance);
    if ((held != s.contents.end() && held->second > 0) || (dirt != s.dirt.end() && !dirt->second.empty()) ||
        (soaked != s.soaked.end() && soaked->second > 0))
      return true;
  }
  return false;
}
bool toggled_on(const World& w, int a) {
  return state_test(w, a, [](const auto& ab, const auto& s) { return ab.toggleable && s.toggled; });
}
bool sliced(const World& w, int a) {
  return state_test(w, a, [](const auto& ab, const auto& s) { return ab.sliceable && s.sliced; });
}
bool broken(const World& w, int a) {
  return state_test(w, a, [](const auto& ab, const auto& s) { return ab.breakable && s.broken; });
}

}  // namespace chore
