#include "world/sampling.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "base/error.hpp"
#include "world/object_geometry.hpp"

namespace chore {
namespace {

constexpr double kDropHeight = 0.005;  // placed this far above the support
constexpr double kClearance = 0.005;   // kept from a container's top or a cover's underside
const Eigen::Vector3d kDown(0, 0, -1), kUp(0, 0, 1);

// The pose-independent size of a free object, measured once per sample call.
struct Footprint {
  double radius;  // horizontal radius of its box: fits any yaw
  double height;
  double bottom;           // body origin height above the box bottom
  Eigen::Vector2d half;    // half the box's sides at heading 0
  Eigen::Vector2d centre;  // the box's centre from the body origin at heading 0
};

int free_joint_qpos(const World& w, int a) {
  const SceneObject& o = w.scene().objects()[a];
  const mjModel* m = w.model();
  if (o.fixed || m->body_jntnum[o.body] < 1 || m->jnt_type[m->body_jntadr[o.body]] != mjJNT_FREE) {
    throw Error("sampling: object '" + o.name + "' is not a free object; its pose cannot be sampled");
  }
  return m->jnt_qposadr[m->body_jntadr[o.body]];
}

void place(World& w, int a, double x, double y, double z, double yaw);

// Stands `a` upright where it is first: placements only turn it about the
// vertical, so its size in that pose holds for every one of them (an object
// that fell over, a cloth that lay tilted, would otherwise be placed in the
// floor).
Footprint footprint(World& w, int a) {
  const Eigen::Vector3d origin = object_frame(w, a).pos;
  place(w, a, origin.x(), origin.y(), origin.z(), 0);
  const Aabb box = object_aabb(w, a);
  return {0.5 * box.extent().head<2>().norm(), box.extent().z(), origin.z() - box.lo.z(), 0.5 * box.extent().head<2>(),
          0.5 * (box.lo + box.hi).head<2>() - origin.head<2>()};
}

void place(World& w, int a, double x, double y, double z, double yaw) {
  const int q = free_joint_qpos(w, a);
  const SceneObject& o = w.scene().objects()[a];
  const int dof = w.model()->jnt_dofadr[w.model()->body_jntadr[o.body]];
  double* qpos = w.data()->qpos + q;
  qpos[0] = x;
  qpos[1] = y;
  qpos[2] = z;
  qpos[3] = std::cos(yaw / 2);
  qpos[4] = 0;
  qpos[5] = 0;
  qpos[6] = std::sin(yaw / 2);
  std::fill_n(w.data()->qvel + dof, 6, 0.0);
  mj_forward(w.model(), w.data());
}

// Collision geoms of the world except those of the excluded objects.
std::vector<int> geoms_except(const World& w, int a, int b = -1) {
  const mjModel* m = w.model();
  std::vector<int> out;
  for (int g = 0; g < m->ngeom; ++g) {
    if (!m->geom_contype[g] && !m->geom_conaffinity[g]) continue;
    const int o = w.scene().object_of_geom(g);
    if (o >= 0 && (o == a || o == b)) continue;
    out.push_back(g);
  }
  return out;
}

// In contact with another object than `except`, or the scene (a cloth's
// tiles touching each other do not count).
bool touches_anything(const World& w, int a, int except = -1) {
  const mjData* d = w.data();
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& con = d->contact[c];
    const int o1 = w.scene().object_of_geom(con.geom[0]), o2 = w.scene().object_of_geom(con.geom[1]);
    if ((o1 == a) != (o2 == a) && (except < 0 || (o1 != except && o2 != except))) return true;
  }
  return false;
}

void settle(World& w, const SampleOptions& options) {
  w.step(static_cast<int>(std::lround(options.settle_seconds / w.model()->opt.timestep)));
}

// How far the footprint at (x, y) turned by `yaw` reaches past `within`
// (summed over the four sides).
double overhang(const Footprint& f, double x, double y, double yaw, const Aabb& within) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  const Eigen::Vector2d centre(x + c * f.centre.x() - s * f.centre.y(), y + s * f.centre.x() + c * f.centre.y());
  const Eigen::Vector2d half(std::abs(c) * f.half.x() + std::abs(s) * f.half.y(),
                             std::abs(s) * f.half.x() + std::abs(c) * f.half.y());
  double out = 0;
  for (int i = 0; i < 2; ++i) {
    out += std::max(0.0, centre[i] + half[i] - within.hi[i]) + std::max(0.0, within.lo[i] - (centre[i] - half[i]));
  }
  return out;
}

// Places `a` with its bottom on height `support` at (x, y), random heading;
// false if it would overlap anything. With `within` (what it is put on), a
// heading at which it reaches past that is squared to within's sides,
// whichever way reaches past least: a chopping board longer than the
// counter is deep lies along it, not across it into the wall behind. The
// draw is the same either way.
bool try_place(World& w, int a, const Footprint& f, double x, double y, double support, Rng& rng,
               const Aabb* within = nullptr) {
  double yaw = uniform(rng, -M_PI, M_PI);
  double least = within ? overhang(f, x, y, yaw, *within) : 0.0;
  if (least > 0) {
    const double square = std::round(yaw / (M_PI / 2)) * (M_PI / 2);
    for (const double turned : {square, square + M_PI / 2}) {
      const double reach_past = overhang(f, x, y, turned, *within);
      if (reach_past < least) {
        yaw = turned;
        least = reach_past;
      }
    }
  }
  place(w, a, x, y, support + kDropHeight + f.bottom, yaw);
  return !touches_anything(w, a);
}

// A uniform point of the box's footprint shrunk by r (its centre if too small).
Eigen::Vector2d point_in(const Aabb& box, double r, Rng& rng) {
  Eigen::Vector2d p;
  for (int i = 0; i < 2; ++i) {
    const double lo = box.lo[i] + r, hi = box.hi[i] - r;
    p[i] = lo < hi ? uniform(rng, lo, hi) : (box.lo[i] + box.hi[i]) / 2;
  }
  return p;
}

// Whether b's walls, along both horizontal axes, stand clear of an object of
// horizontal radius r at `centre` by the fingers' width: what a hand takes
// from above or the side closes its fingers round it.
bool hand_room(const World& w, int b, const Eigen::Vector3d& centre, double r) {
  constexpr double kHandRoom = 0.06;
  // Not a door's leaf: it swings open before the hand comes in (a closed
  // fridge door counted as a wall kept bowls off all but a 6 cm band of a
  // shelf within reach). A drawer's walls stay as they are.
  const mjModel* m = w.model();
  std::vector<int> walls;
  for (const int g : w.scene().objects()[b].geoms) {
    const int joint = m->body_jntadr[m->geom_bodyid[g]];
    if (joint < 0 || m->jnt_type[joint] != mjJNT_HINGE) walls.push_back(g);
  }
  for (const Eigen::Vector3d dir : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)}) {
    for (const double sign : {1.0, -1.0}) {
      const double to_wall = ray_to_geoms(w, walls, centre, sign * dir, r + kHandRoom);
      if (to_wall >= 0) return false;
    }
  }
  return true;
}

// Candidates until one is placed; `candidate(strict)` with strict in the
// first half of the attempts when a preference is set.
template <class Candidate>
bool search(World& w, const SampleOptions& options, Candidate candidate) {
  for (int attempt = 0; attempt < options.attempts; ++attempt) {
    if (candidate(options.prefer && attempt < options.attempts / 2)) {
      settle(w, options);
      return true;
    }
  }
  return false;
}

}  // namespace

bool sample_ontop(World& w, int a, int b, Rng& rng, const SampleOptions& options) {
  const Footprint f = footprint(w, a);
  const Aabb box = object_aabb(w, b);
  const std::vector<int> others = geoms_except(w, a);
  // A cloth is laid over all of b from above it and settles onto b (a towel
  // over a sink's rim), as BEHAVIOR drops cloth onto rigid objects.
  const bool cloth = !w.scene().objects()[a].keypoints.empty();
  SampleOptions search_options = options;
  if (cloth) search_options.settle_seconds *= 4;
  return search(w, search_options, [&](bool strict) {
    const Eigen::Vector2d p = point_in(box, cloth ? 0 : f.radius, rng);
    const Eigen::Vector3d start(p.x(), p.y(), box.hi.z() + 0.01);
    // The first surface below must be b's: nothing else lies there.
    const double to_b = ray_to_object(w, b, start, kDown, 10);
    if (to_b < 0 || ray_to_geoms(w, others, start, kDown, 10) < to_b - 1e-9) return false;
    if (strict && !options.prefer({p.x(), p.y(), start.z() - to_b}, f.height, false)) return false;
    // Where a rim stands above the surface (a plate onto a plate of its
    // size), on top of b's box: it settles onto the rim.
    return (!cloth && try_place(w, a, f, p.x(), p.y(), start.z() - to_b, rng, &box)) ||
           try_place(w, a, f, p.x(), p.y(), box.hi.z(), rng, cloth ? nullptr : &box);
  });
}

bool sample_inside(World& w, int a, int b, Rng& rng, const SampleOptions& options) {
  const Footprint f = footprint(w, a);
  const Aabb box = object_aabb(w, b);
  const std::vector<int> others = geoms_except(w, a);
  return search(w, options, [&](bool strict) {
    const Eigen::Vector2d p = point_in(box, f.radius + 0.01, rng);
    // A height inside b's box from which a support of b lies below.
    const double top = box.hi.z() - kClearance - f.height;
    if (top <= box.lo.z()) return false;
    const Eigen::Vector3d start(p.x(), p.y(), uniform(rng, box.lo.z(), top) + f.height);
    const double to_b = ray_to_object(w, b, start, kDown, 10);
    if (to_b < 0 || ray_to_geoms(w, others, start, kDown, 10) < to_b - 1e-9) return false;
    const double support = start.z() - to_b;
    if (support + kDropHeight + f.height > box.hi.z() - kClearance) return false;
    if (strict && (!options.prefer({p.x(), p.y(), support}, f.height, true) ||
                   !hand_room(w, b, {p.x(), p.y(), support + f.height / 2}, f.radius))) {
      return false;
    }
    return try_place(w, a, f, p.x(), p.y(), support, rng);
  });
}

bool sample_under(World& w, int a, int b, Rng& rng, const SampleOptions& options) {
  const Footprint f = footprint(w, a);
  const Aabb box = object_aabb(w, b);
  const std::vector<int> others = geoms_except(w, a, b);
  return search(w, options, [&](bool strict) {
    const Eigen::Vector2d p = point_in(box, 0, rng);
    // The underside of b above this point, then the support below it.
    const Eigen::Vector3d low(p.x(), p.y(), 0.001);
    const double to_cover = ray_to_object(w, b, low, kUp, 10);
    if (to_cover < 0) return false;
    const Eigen::Vector3d start(p.x(), p.y(), low.z() + to_cover - 0.001);
    const double to_support = ray_to_geoms(w, others, start, kDown, 10);
    if (to_support < 0) return false;
    const double support = start.z() - to_support;
    if (support + kDropHeight + f.height > start.z() - kClearance) return false;
    if (strict && !options.prefer({p.x(), p.y(), support}, f.height, true)) return false;
    return try_place(w, a, f, p.x(), p.y(), support, rng);
  });
}

bool sample_onfloor(World& w, int a, int room, Rng& rng, const SampleOptions& options) {
  const Footprint f = footprint(w, a);
  const Room& r = w.scene().rooms()[room];
  const std::vector<int>& floors = w.scene().floor_geoms(room);
  const std::vector<int> others = geoms_except(w, a);
  return search(w, options, [&](bool strict) {
    const auto& rect = r.rects[uniform_index(rng, static_cast<int>(r.rects.size()))];
    Aabb area;
    area.lo = Eigen::Vector3d(rect[0], rect[1], 0);
    area.hi = Eigen::Vector3d(rect[2], rect[3], 0);
    const Eigen::Vector2d p = point_in(area, f.radius, rng);
    // Open floor: the first surface below head height is this room's floor.
    const Eigen::Vector3d start(p.x(), p.y(), 2.0);
    const double to_floor = ray_to_geoms(w, floors, start, kDown, 10);
    if (to_floor < 0 || ray_to_geoms(w, others, start, kDown, 10) < to_floor - 1e-9) return false;
    if (strict && !options.prefer({p.x(), p.y(), start.z() - to_floor}, f.height, false)) return false;
    return try_place(w, a, f, p.x(), p.y(), start.z() - to_floor, rng);
  });
}

bool sample_attached(World& w, int a, int b, Rng& rng, const SampleOptions& options) {
  const Footprint f = footprint(w, a);
  const Aabb box = object_aabb(w, b);
  for (int attempt = 0; attempt < options.attempts; ++attempt) {
    const Eigen::Vector2d p = point_in(box, 0, rng);
    place(w, a, p.x(), p.y(), box.hi.z() + kDropHeight + f.bottom, uniform_index(rng, 4) * M_PI / 2);
    // Clear of everything but b (a rod along the wall its nail is on, not into
    // it: a weld against a contact throws the object across the room).
    if (!touches_anything(w, a, b)) return w.attach_objects(a, b);
  }
  return false;
}

void sample_open(World& w, int a, bool open, Rng& rng) {
  const SceneObject& o = w.scene().objects()[a];
  const mjModel* m = w.model();
  if (o.joints.empty() && !open) return;  // closed already: nothing opens
  if (o.joints.empty()) throw Error("sampling: object '" + o.name + "' has no joints to open");
  for (int j : o.joints) w.data()->qpos[m->jnt_qposadr[j]] = m->jnt_range[2 * j];
  if (open) {
    const int j = o.joints[uniform_index(rng, static_cast<int>(o.joints.size()))];
    const double lo = m->jnt_range[2 * j], hi = m->jnt_range[2 * j + 1];
    w.data()->qpos[m->jnt_qposadr[j]] = lo + uniform(rng, 0.3, 1.0) * (hi - lo);
  }
  for (int j : o.joints) w.data()->qvel[m->jnt_dofadr[j]] = 0;
  mj_forward(m, w.data());
}

void sample_state(World& w, const std::string& predicate, int a, bool value, const std::string& liquid) {
  const std::string& name = w.scene().objects()[a].name;
  const ObjectAbilities* ab = w.states().abilities(a);
  // A state the object does not keep reads false: its negation holds as it is.
  const std::string missing = ab ? missing_for_state(predicate, *ab) : "any state";
  if (!missing.empty() && !value) return;
  if (!missing.empty()) {
    throw Error("sampling: object '" + name + "' does not keep " + missing + " (needed by '" + predicate + "')");
  }
  ObjectState* s = &w.states().state(a);
  // Past a threshold by this much when true, back to room conditions when false.
  constexpr double kMargin = 10;
  if (predicate == "cooked" || predicate == "burnt") {
    const double threshold = predicate == "cooked" ? ab->cook_temperature : ab->burn_temperature;
    s->max_temperature =
        value ? std::max(s->max_temperature, threshold + kMargin) : std::min(s->max_temperature, threshold - kMargin);
    s->temperature = std::min(s->temperature, s->max_temperature);
  } else if (predicate == "frozen" || predicate == "hot" || predicate == "on_fire") {
    double target = kRoomTemperature;
    if (value && predicate == "frozen") target = ab->freeze_temperature - kMargin;
    if (value && predicate == "hot") target = ab->hot_temperature + kMargin;
    if (value && predicate == "on_fire") target = ab->ignition_temperature + kMargin;
    s->temperature = target;
    s->max_temperature = std::max(s->max_temperature, target);
  } else if (predicate == "soaked" || predicate == "saturated") {
    s->soaked[liquid] = value ? 1.0 : 0.0;
  } else if (predicate == "filled" || predicate == "contains") {
    // filled: four fifths up; contains: a little, below filled's level.
    if (value) {
      s->contents[liquid] = predicate == "filled" ? 0.8 : ObjectStates::kFilledLevel / 2;
    } else {
      s->contents.erase(liquid);
    }
  } else if (predicate == "toggled_on") {
    s->toggled = value;
  } else if (predicate == "sliced") {
    s->sliced = value;
  } else if (predicate == "broken") {
    s->broken = value;
  } else {
    throw Error("sampling: no state sampler for predicate '" + predicate + "'");
  }
}

bool sample_covered(World& w, int a, const std::string& substance, bool value, Rng& rng, int particles) {
  const ObjectAbilities* ab = w.states().abilities(a);
  if (!ab || !missing_for_state("covered", *ab).empty()) {
    if (!value) return true;  // nothing lies on what keeps no dirt
    throw Error("sampling: object '" + w.scene().objects()[a].name + "' does not keep CoveredLevel");
  }
  std::vector<Eigen::Vector3d>& dirt = w.states().state(a).dirt[substance];
  int& sampled = w.states().state(a).dirt_sampled[substance];
  dirt.clear();
  sampled = 0;
  if (!value) return true;
  const Aabb box = object_aabb(w, a);
  const std::vector<int> all = geoms_except(w, -1);
  const Frame frame = object_frame(w, a);
  for (int attempt = 0; attempt < 20 * particles && static_cast<int>(dirt.size()) < particles; ++attempt) {
    const Eigen::Vector2d p = point_in(box, 0, rng);
    const Eigen::Vector3d start(p.x(), p.y(), box.hi.z() + 0.05);
    const double to_a = ray_to_object(w, a, start, kDown, 10);
    if (to_a < 0 || ray_to_geoms(w, all, start, kDown, 10) < to_a - 1e-9) continue;
    dirt.push_back(frame.to_local(start + kDown * to_a));
  }
  sampled = static_cast<int>(dirt.size());
  return static_cast<int>(dirt.size()) == particles;
}

bool sample_robot_in_room(World& w, int room, Rng& rng) {
  const Robot& r = *w.robot();
  const Room& rm = w.scene().rooms()[room];
  const mjModel* m = w.model();
  for (int attempt = 0; attempt < 200; ++attempt) {
    const auto& rect = rm.rects[uniform_index(rng, static_cast<int>(rm.rects.size()))];
    const double margin = 0.4;
    if (rect[2] - rect[0] < 2 * margin || rect[3] - rect[1] < 2 * margin) continue;
    w.data()->qpos[r.base_x.qpos] = uniform(rng, rect[0] + margin, rect[2] - margin);
    w.data()->qpos[r.base_y.qpos] = uniform(rng, rect[1] + margin, rect[3] - margin);
    w.data()->qpos[r.base_yaw.qpos] = uniform(rng, -M_PI, M_PI);
    mj_forward(m, w.data());
    bool clear = true;
    for (int c = 0; c < w.data()->ncon && clear; ++c) {
      const mjContact& con = w.data()->contact[c];
      const int root1 = m->body_rootid[m->geom_bodyid[con.geom[0]]];
      const int root2 = m->body_rootid[m->geom_bodyid[con.geom[1]]];
      const int robot = m->body_rootid[m->jnt_bodyid[r.base_x.joint]];
      clear = root1 != robot && root2 != robot;
    }
    if (clear) return true;
  }
  return false;
}

}  // namespace chore
