#include "world/state_rules.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "world/object_geometry.hpp"
#include "world/predicates.hpp"
#include "world/transitions.hpp"

namespace chore {
namespace {

constexpr double kSoakSeconds = 0.5;   // in water this long: saturated (a container dipped in: filled)
constexpr double kCoolingRate = 0.01;  // towards room temperature, per second

// A soakable object overlapping the water of a container (`moved` has
// `moved_box` instead of its box in the world).
void soak(World& w, double dt, int moved, const Aabb* moved_box) {
  std::map<int, ObjectState>& state_of = w.states().all_states();
  const std::map<int, ObjectAbilities>& abilities_of = w.states().all_abilities();
  const auto box = [&](int object) { return object == moved ? *moved_box : object_aabb(w, object); };
  // The containers holding a liquid first: most scenes have none or a few, and
  // a scene of hundreds of objects would otherwise pair every two of them.
  std::vector<int> holding;
  for (const auto& [container, ca] : abilities_of) {
    if (ca.holds_liquid && state_of[container].level() > 0) holding.push_back(container);
  }
  for (const int container : holding) {
    const double level = state_of[container].level();
    const std::string liquid = state_of[container].main_substance();
    Aabb water = box(container);
    water.lo.head<2>().array() += 0.01;
    water.hi.head<2>().array() -= 0.01;
    water.hi.z() = water.lo.z() + level * (water.hi.z() - water.lo.z());
    for (const auto& [object, oa] : abilities_of) {
      if (object == container || !(oa.soakable || oa.holds_liquid)) continue;
      if (!box(object).overlaps(water)) continue;
      ObjectState& s = state_of[object];
      if (oa.soakable) s.soaked[liquid] = std::min(1.0, s.soaked[liquid] + dt / kSoakSeconds);
      // The container the robot dips in fills with the liquid (not over
      // another one); containers merely standing in a basin do not.
      if (oa.holds_liquid && object == w.carried_object() && s.level() <= s.contents[liquid]) {
        s.contents[liquid] =
            std::min(ObjectStates::kSourceLevel, s.contents[liquid] + ObjectStates::kSourceLevel * dt / kSoakSeconds);
      }
    }
  }
}

// Whether a contact joins an object whose states are kept.
bool acts_on(const ObjectStates& states, const World& w, const mjContact& con) {
  const int o1 = w.scene().object_of_geom(con.geom[0]);
  const int o2 = w.scene().object_of_geom(con.geom[1]);
  return (o1 >= 0 && states.abilities(o1)) || (o2 >= 0 && states.abilities(o2));
}

// Whether a tool in state `s` removes the substance `name` now: by the
// knowledge base's conditions where the activity bound them (saturated with
// one of the solvents they list, or as it is), else iGibson's rule (stains
// need the tool soaked in water, dust not).
bool removes_now(const ObjectAbilities& tool, const ObjectState& s, const std::string& name, const Substance* sub) {
  const auto absorbed = [&](const std::string& liquid) {
    const auto it = s.soaked.find(liquid);
    return it == s.soaked.end() ? 0.0 : it->second;
  };
  if (!tool.removes.empty()) {
    const auto it = tool.removes.find(name);
    if (it == tool.removes.end()) return false;
    return it->second.empty() || std::any_of(it->second.begin(), it->second.end(), [&](const std::string& solvent) {
             return absorbed(solvent) >= ObjectStates::kSaturatedLevel;
           });
  }
  return !(sub && sub->needs_soaked_tool) || absorbed("water") >= ObjectStates::kSoakedLevel;
}

// Cleaning, breaking, slicing: what one contact does to the objects it joins;
// `normal_force` is the force between those two objects.
void touch(ObjectStates& states, const World& w, const mjContact& con, double normal_force) {
  const int o1 = w.scene().object_of_geom(con.geom[0]);
  const int o2 = w.scene().object_of_geom(con.geom[1]);
  const ObjectAbilities* a1 = o1 >= 0 ? states.abilities(o1) : nullptr;
  const ObjectAbilities* a2 = o2 >= 0 ? states.abilities(o2) : nullptr;
  std::map<int, ObjectState>& state_of = states.all_states();
  for (const auto& [self, mine, other, theirs] : {std::tuple{o1, a1, o2, a2}, std::tuple{o2, a2, o1, a1}}) {
    if (!mine) continue;
    ObjectState& s = state_of[self];
    if (mine->breakable && normal_force > mine->break_force) s.broken = true;
    if (mine->sliceable && theirs && theirs->slicer && normal_force > mine->slice_force) s.sliced = true;
    if ((mine->cleaning_tool || !mine->removes.empty()) && other >= 0 && theirs && theirs->covered) {
      const Eigen::Vector3d p(con.pos[0], con.pos[1], con.pos[2]);
      for (auto& [name, particles] : state_of[other].dirt) {
        if (!removes_now(*mine, s, name, states.substance(name))) continue;
        const Frame frame = object_frame(w, other);
        std::erase_if(particles, [&](const Eigen::Vector3d& local) {
          return (frame.to_world(local) - p).head<2>().norm() < ObjectStates::kCleaningRadius;
        });
      }
    }
  }
}

}  // namespace

void update_states_after_physics_step(World& w, double dt) {
  ObjectStates& states = w.states();
  if (states.all_states().empty()) return;
  soak(w, dt, -1, nullptr);
  const mjModel* m = w.model();
  const mjData* d = w.data();
  // Breaking and slicing read the force between two objects: the sum over the
  // contacts that join them (MuJoCo gives a face resting on a face one contact
  // or several, as its collision functions choose).
  std::map<std::pair<int, int>, double> pair_force;
  const auto pair_of = [&](const mjContact& con) {
    const int o1 = w.scene().object_of_geom(con.geom[0]), o2 = w.scene().object_of_geom(con.geom[1]);
    return std::pair{std::min(o1, o2), std::max(o1, o2)};
  };
  for (int c = 0; c < d->ncon; ++c) {
    if (!acts_on(states, w, d->contact[c])) continue;  // most contacts: the force is not worth computing
    double force[6];
    mj_contactForce(m, d, c, force);
    pair_force[pair_of(d->contact[c])] += std::abs(force[0]);
  }
  for (int c = 0; c < d->ncon; ++c) {
    if (acts_on(states, w, d->contact[c])) touch(states, w, d->contact[c], pair_force[pair_of(d->contact[c])]);
  }
}

void update_states_at_motion_waypoint(World& w, double dt, int moved, const Aabb& moved_box,
                                      const std::vector<mjContact>& moved_contacts) {
  ObjectStates& states = w.states();
  if (states.all_states().empty()) return;
  soak(w, dt, moved, &moved_box);
  for (const mjContact& con : moved_contacts) {
    if (acts_on(states, w, con)) touch(states, w, con, 0.0);
  }
}

bool thermal_source_acts(const World& w, int source, const ThermalSource& t, int object) {
  if (t.requires_toggled_on && !w.states().state(source).toggled) return false;
  if (t.requires_closed && is_open(w, source)) return false;
  return within_thermal_reach(w, source, t, object);
}

bool within_thermal_reach(const World& w, int source, const ThermalSource& t, int object) {
  return t.requires_inside ? inside(w, object, source)
                           : Aabb::gap(object_aabb(w, object), object_aabb(w, source)) <= t.distance;
}

Eigen::Vector3d toggle_point(const World& w, int object) {
  const Aabb box = object_aabb(w, object);
  const SceneObject& o = w.scene().objects()[object];
  if (o.joints.empty() || o.body < 0) return {box.center().x(), box.center().y(), box.hi.z()};
  // What opens (an oven, a washer) is worked from the front its door or
  // drawer opens to (its frame's -y), as an appliance's panel is: the top's
  // front edge, kFrontInset in, of its carcass (the root body's geoms, so
  // that the door, open or shut, does not move it). At the top's centre it
  // stood under the pot on a stove, and moved half a door's swing as the
  // door opened.
  constexpr double kFrontInset = 0.05;
  const mjModel* m = w.model();
  Aabb carcass;
  // (The root body's own geoms: this runs every env step for each toggleable object.)
  for (int g = m->body_geomadr[o.body]; g >= 0 && g < m->body_geomadr[o.body] + m->body_geomnum[o.body]; ++g) {
    carcass.grow(geom_aabb(w, g));
  }
  Eigen::Vector3d front = -object_frame(w, object).rot.col(1);
  front.z() = 0;
  if (carcass.lo.x() > carcass.hi.x() || front.norm() < 1e-9) return {box.center().x(), box.center().y(), box.hi.z()};
  front.normalize();
  const Eigen::Vector3d edge = carcass.center() + front * std::max(0.0, carcass.half_across(front) - kFrontInset);
  return {edge.x(), edge.y(), carcass.hi.z()};
}

void update_states_after_env_step(World& w, double dt) {
  std::map<int, ObjectState>& state_of = w.states().all_states();
  const std::map<int, ObjectAbilities>& abilities_of = w.states().all_abilities();
  if (state_of.empty()) return;
  // Toggling: the fingers held at the toggle point (top centre) for a few
  // steps, as OmniGibson's ToggledOn counts a robot's finger links near its
  // toggle marker; not the hand that holds the object there (a sprayer
  // grasped from above).
  if (const Robot* r = w.robot()) {
    const Eigen::Vector3d hand(w.data()->site_xpos + 3 * r->gripper_site);
    const mjtNum* frame = w.data()->site_xmat + 9 * r->gripper_site;
    const Eigen::Vector3d fingers = Eigen::Vector3d(frame[0], frame[3], frame[6]) * Robot::kFingertips;
    std::optional<Eigen::Vector3d>& last = w.states().last_hand();
    const bool held = !last || (hand - *last).norm() < ObjectStates::kToggleSpeed * dt;
    last = hand;
    for (auto& [object, s] : state_of) {
      if (!abilities_of.at(object).toggleable || object == w.grasped_object()) continue;
      const Eigen::Vector3d point = toggle_point(w, object);
      // The point's distance from the fingers: the segment from the hand's
      // centre to the fingertips.
      const double along = std::clamp((point - hand).dot(fingers) / fingers.squaredNorm(), 0.0, 1.0);
      const bool near = held && (point - (hand + along * fingers)).norm() < ObjectStates::kToggleDistance;
      s.toggle_steps = near ? s.toggle_steps + 1 : 0;
      if (s.toggle_steps == ObjectStates::kToggleSteps) s.toggled = !s.toggled;
    }
  }
  // Particle sources toggled on give their substance: they hold it, filled.
  for (auto& [object, s] : state_of) {
    const ObjectAbilities& ab = abilities_of.at(object);
    if (ab.source.empty() || !ab.holds_liquid || !s.toggled) continue;
    if (s.level() > s.contents[ab.source]) continue;  // holds something else: a tap does not top up a mix
    s.contents[ab.source] = std::max(s.contents[ab.source], ObjectStates::kSourceLevel);
  }
  // Heat: each source in force pulls temperatures towards its own. The
  // sources first: a few in a scene of hundreds of objects.
  std::vector<std::pair<int, const ThermalSource*>> sources;
  for (const auto& [source, sa] : abilities_of) {
    for (const std::optional<ThermalSource>* t : {&sa.heat_source, &sa.cold_source}) {
      if (*t) sources.emplace_back(source, &**t);
    }
  }
  for (auto& [object, s] : state_of) {
    if (!abilities_of.at(object).temperature) continue;
    bool heated = false;
    for (const auto& [source, t] : sources) {
      if (source == object || !thermal_source_acts(w, source, *t, object)) continue;
      s.temperature += (t->temperature - s.temperature) * std::min(1.0, t->rate * dt);
      heated = true;
    }
    if (!heated) s.temperature += (kRoomTemperature - s.temperature) * std::min(1.0, kCoolingRate * dt);
    s.max_temperature = std::max(s.max_temperature, s.temperature);
  }
  make_transitions(w);
}

void draw_states(const World& w, mjvScene* scene) {
  const std::map<int, ObjectState>& state_of = w.states().all_states();
  // OmniGibson's StatefulObject texture change: albedo = tint * (albedo + add),
  // with the parameters of its states' get_texture_change_params (a colourless
  // liquid such as water tints blue) and its priority frozen > burnt > cooked >
  // soaked. Without it a soaked rag would look dry, and an image-based policy
  // could not tell whether it has dipped.
  struct TextureChange {
    float add;
    float tint[3];
  };
  constexpr TextureChange kFrozen{0.3f, {1, 1, 1}}, kBurnt{-0.3f, {1, 1, 1}}, kCooked{0.1f, {1.5f, 0.75f, 0.25f}},
      kSoaked{0.1f, {0.5f, 0.5f, 1.5f}};
  std::map<int, const TextureChange*> changes;
  for (const auto& [object, state] : state_of) {
    const bool wet = std::any_of(state.soaked.begin(), state.soaked.end(),
                                 [&, id = object](const auto& liquid) { return soaked(w, id, liquid.first); });
    const TextureChange* change = frozen(w, object)   ? &kFrozen
                                  : burnt(w, object)  ? &kBurnt
                                  : cooked(w, object) ? &kCooked
                                  : wet               ? &kSoaked
                                                      : nullptr;
    if (change) changes[object] = change;
  }
  if (!changes.empty()) {
    for (int i = 0; i < scene->ngeom; ++i) {
      mjvGeom& g = scene->geoms[i];
      if (g.objtype != mjOBJ_GEOM) continue;
      const auto it = changes.find(w.scene().object_of_geom(g.objid));
      if (it == changes.end()) continue;
      for (int c = 0; c < 3; ++c)
        g.rgba[c] = std::clamp(it->second->tint[c] * (g.rgba[c] + it->second->add), 0.0f, 1.0f);
    }
  }

  constexpr float kRadius = 0.03f, kHalfThickness = 0.001f;
  const float stain[4] = {0.12f, 0.09f, 0.05f, 1.0f}, dust[4] = {0.78f, 0.76f, 0.70f, 1.0f};
  for (const auto& [object, state] : state_of) {
    for (const auto& [name, particles] : state.dirt) {
      const float* rgba = name == "dust" ? dust : stain;
      const Frame frame = object_frame(w, object);
      for (const Eigen::Vector3d& local : particles) {
        if (scene->ngeom >= scene->maxgeom) return;
        const Eigen::Vector3d p = frame.to_world(local) + Eigen::Vector3d(0, 0, kHalfThickness);
        const mjtNum size[3] = {kRadius, kHalfThickness, 0};
        const mjtNum pos[3] = {p.x(), p.y(), p.z()};
        mjvGeom* g = scene->geoms + scene->ngeom++;
        mjv_initGeom(g, mjGEOM_CYLINDER, size, pos, nullptr, rgba);
        g->category = mjCAT_DECOR;
        g->modelrbound = kRadius;  // lets the renderer cull it like a model geom
      }
    }
  }
}

}  // namespace chore
