// wipe(object): with a tool in hand, down onto the object's densest dirt,
// then strokes left-right, row by row towards the robot, pressing 1 cm in;
// the cleaning rules remove the dirt the tool passes over.
#include <algorithm>
#include <cmath>

#include "primitives/primitive_def.hpp"
#include "world/object_geometry.hpp"

namespace chore {
namespace {

// Strokes: kRows rows kRowSpacing apart, the first kFarRow beyond the approach
// point, each kHalfWidth to either side of it; on an object smaller than that,
// as far as its box reaches (an egg: the tool's contact cleans round it).
constexpr int kRows = 4;
constexpr double kRowSpacing = 0.08, kFarRow = 1.5 * kRowSpacing, kHalfWidth = 0.22;
// rad: a base pose drawn to wipe from faces the dirt within +-0.3, and the
// dirt is wiped from a base facing it within +-0.6 (PrimitiveDef::yaw_spread):
// side-on, 62 degrees off, the strokes swept past a table's corner, one
// particle in 25 wipes (clean_table, seed 1).
constexpr double kYawSpread = 0.6;

struct Strokes {
  Eigen::Vector3d forward, left;  // from the base facing its yaw
  double far_row, row_spacing, half_width;
};
Strokes strokes(const World& w, int object, double yaw) {
  const Aabb box = object_aabb(w, object);
  const Eigen::Vector3d forward(std::cos(yaw), std::sin(yaw), 0), left(-std::sin(yaw), std::cos(yaw), 0);
  const double far_row = std::min(kFarRow, box.half_across(forward));
  return {forward, left, far_row, far_row * kRowSpacing / kFarRow, std::min(kHalfWidth, box.half_across(left))};
}

bool applies(const World& w, int object) {
  const ObjectAbilities* ab = w.states().abilities(object);
  return ab && ab->covered;
}

std::string unmet_precondition(const World& w, int object) {
  if (w.carried_object() < 0) return "the hand holds nothing";
  return applies(w, object) ? "" : "'" + w.scene().objects().at(object).name + "' has nothing to wipe";
}

// Where to wipe, densest dirt first: particles ordered by how many lie
// within kPatchRadius of them (the strokes sweep about that far), each kept
// unless within kPatchSpacing of one kept before; then the particles passed
// over, so that a last reachable one beside an unreachable patch is still
// aimed at. Particles themselves, not the means of their neighbourhoods: a
// mean can lie beyond reach where every particle does not. The top centre
// when clean.
std::vector<Eigen::Vector3d> dirt_patches(const World& w, int object) {
  constexpr double kPatchRadius = 0.25, kPatchSpacing = 0.15;
  const std::vector<Eigen::Vector3d> particles = dirt_particles(w, object);
  if (particles.empty()) return {top_centre(w, object, w.base_pose())};
  std::vector<std::pair<int, size_t>> density;  // (-neighbours, particle): sorted densest first
  for (size_t i = 0; i < particles.size(); ++i) {
    int n = 0;
    for (const Eigen::Vector3d& q : particles) n += (q - particles[i]).head<2>().norm() < kPatchRadius;
    density.push_back({-n, i});
  }
  std::sort(density.begin(), density.end());
  std::vector<Eigen::Vector3d> patches, passed;
  for (const auto& [count, i] : density) {
    const bool near_kept = std::any_of(patches.begin(), patches.end(), [&, i = i](const Eigen::Vector3d& kept) {
      return (kept - particles[i]).head<2>().norm() < kPatchSpacing;
    });
    (near_kept ? passed : patches).push_back(particles[i]);
  }
  patches.insert(patches.end(), passed.begin(), passed.end());
  return patches;
}

// Down onto the patch; else, where it lies beyond that reach (the back of a
// deep counter), down nearer the base, so that the strokes' far row passes
// within half the cleaning radius of it, where that spot is still on the
// object. Last (Approach::last_resort), onto the patch tilted 45 degrees
// towards it where the hand pointing down does not get: higher than
// kHighestDown, or farther than kFarthestDown from the base's centre;
// tilted, the hand gets to 1.4 m and 0.9 m (a monitor's top, a shell at the
// back of a counter against a wall). Not elsewhere: physically the rag
// hanging from a tilted hand cleans little, and where coming down failed for
// other reasons the robot had better stand elsewhere. Only from a base
// facing the spot, as the strokes across the robot's front need (turned
// away, the arm bends back and the descent stops).
std::vector<Approach> onto_patch(const World& w, int object, const Eigen::Vector3d& patch, const Pose2& base) {
  constexpr double kInside = 0.02;  // m the nearer spot keeps inside the object's box
  std::vector<Approach> out = {{patch, kDown, std::nullopt}};
  Eigen::Vector3d towards(patch.x() - base.x, patch.y() - base.y, 0);
  if (towards.norm() < 1e-6) return out;
  const Eigen::Vector3d nearer =
      patch - towards.normalized() * (strokes(w, object, base.yaw).far_row + ObjectStates::kCleaningRadius / 2);
  const Aabb box = object_aabb(w, object);
  if (nearer.x() > box.lo.x() + kInside && nearer.x() < box.hi.x() - kInside && nearer.y() > box.lo.y() + kInside &&
      nearer.y() < box.hi.y() - kInside) {
    out.push_back({nearer, kDown, std::nullopt});
  }
  constexpr double kFarthestDown = 0.75;  // m from the base's centre, at a counter's height
  const double off_facing = std::remainder(std::atan2(towards.y(), towards.x()) - base.yaw, 2 * M_PI);
  const bool beyond_down = towards.norm() > kFarthestDown || patch.z() + kClearance + load_below_hand(w) > kHighestDown;
  if (!beyond_down || std::abs(off_facing) > kYawSpread / 2) return out;
  out.push_back({patch, tilted_towards(towards), std::nullopt, true});
  return out;
}

// From above onto every patch before tilted onto any: tilted, the tool
// meets the surface with its edge and the strokes clean less.
std::vector<Approach> approaches(const World& w, int object, const Pose2& base) {
  std::vector<Approach> out, tilted;
  for (const Eigen::Vector3d& patch : dirt_patches(w, object)) {
    for (const Approach& a : onto_patch(w, object, patch, base)) (a.last_resort ? tilted : out).push_back(a);
  }
  out.insert(out.end(), tilted.begin(), tilted.end());
  return out;
}

// How far the approach runs through the object's box from its point.
double depth_through(const Aabb& box, const Approach& a) {
  double depth = 1e9;
  for (int i = 0; i < 3; ++i) {
    const double d = a.direction[i];
    if (std::abs(d) > 1e-9) depth = std::min(depth, std::max(0.0, ((d > 0 ? box.hi[i] : box.lo[i]) - a.point[i]) / d));
  }
  return depth;
}

// At contact where the strokes begin: their farthest row. The tool hangs
// `load` below the hand: where the object is thinner than that, the hand
// stops short by what would be past the object, and 1 cm, the tool on what
// the object lies on (a sponge 6 cm below the fingers, down onto a bracelet
// 2 cm thick, was into the counter under it, and no pose reached:
// clean_gold). On a table the tool stays inside the object, which the reach
// check ignores, and the hand comes down to the top.
Eigen::Vector3d line_end(const World& w, int object, const Approach& a, const Pose2& base, double load) {
  constexpr double kAbove = 0.01;  // m the tool stays above what the object lies on
  const Strokes st = strokes(w, object, base.yaw);
  const Eigen::Vector3d contact = contact_point(w, object, a);
  const double past = (contact - a.point).dot(a.direction) + load - depth_through(object_aabb(w, object), a);
  return contact + st.forward * st.far_row - a.direction * (past > 0 ? past + kAbove : 0.0);
}

// Enough of the dirt within reach that wiping all of that leaves the object
// clean. The tool coming down onto a particle cleans what lies within
// kCleaningRadius of its contact (world/state_rules.cpp), before any stroke:
// a particle within half that of one reached is reached too. Searched one by
// one, 5 of the 20 on a clam 7 cm across were beyond every pose while 10
// others on it were within reach (clean_clams).
std::string out_of_reach(ReachSearch& s) {
  constexpr double kCleanedBeside = ObjectStates::kCleaningRadius / 2;
  std::vector<Eigen::Vector3d> reached, missed;
  const auto beside = [](const std::vector<Eigen::Vector3d>& spots, const Eigen::Vector3d& p) {
    return std::any_of(spots.begin(), spots.end(),
                       [&](const Eigen::Vector3d& q) { return (q - p).head<2>().norm() < kCleanedBeside; });
  };
  for (const Eigen::Vector3d& particle : dirt_particles(s.w, s.object)) {
    if (beside(reached, particle)) continue;
    const auto at = [&](const Pose2& base) { return onto_patch(s.w, s.object, particle, base); };
    if (s.kept_reaches(at) || s.sample({{particle, kDown, std::nullopt}}, at, s.seed++)) {
      reached.push_back(particle);
      std::erase_if(missed, [&](const Eigen::Vector3d& m) { return beside(reached, m); });
    } else {
      missed.push_back(particle);
    }
    if (static_cast<int>(missed.size()) == ObjectStates::kCoveredParticles) {
      return std::to_string(missed.size()) + " dirt particles on '" + s.w.scene().objects().at(s.object).name +
             "' lie out of reach of every base pose the robot can drive to (" + s.tally.to_string() + ")";
    }
  }
  return "";
}

bool act(Executor& e) {
  World& w = e.world();
  Motion& m = e.motion();
  if (!e.go_to_pre_pose()) return false;
  // Down until the tool touches. Physically the rag hanging below the hand
  // drapes onto the surface within kClearance + 6 cm; symbolically only the
  // part of a cloth in the hand touches (the rest gives way: arm_planner.hpp),
  // and tilted the tool lies along the hand's axis: the line covers the
  // pre-pose's standoff for the tool as well.
  const Approach& a = e.approach();
  const double descent =
      kClearance + 0.06 + (a.last_resort || !m.physical() ? std::max(kFingerReach, load_below_hand(w)) : 0.0);
  if (!m.line(a.direction * descent, true, kApproachSpeed)) return false;
  if (!m.touched()) return e.fail(PrimitiveStatus::motion_planning_failure, "the tool did not reach the surface");
  // Strokes left-right, row by row towards the robot, pressing 1 cm in.
  const Strokes st = strokes(w, e.object(), w.base_pose().yaw);
  // Pressed 1 cm in along the first stroke. Symbolic: before it, as a line of
  // its own: a rigid tool held kinematically presses only as far as the arm
  // follows that stroke, and a stroke cut short left it above the table.
  // (Physical: the rag drapes onto the table, and a press of its own would
  // wait out the settling of an arm the table stops.) Each stroke goes as far
  // as the arm reaches along it.
  const Eigen::Vector3d press = kDown * 0.01;
  if (!m.physical()) m.line(press, false, 0.25, 0.0);
  m.line(st.forward * st.far_row - st.left * st.half_width + (m.physical() ? press : Eigen::Vector3d::Zero()), false,
         0.25, 0.0);
  for (int row = 0; row < kRows; ++row) {
    const double side = row % 2 == 0 ? 1.0 : -1.0;
    m.line(st.left * (2 * st.half_width * side), false, 0.3, 0.0);
    if (row + 1 < kRows) m.line(-st.forward * st.row_spacing, false, 0.25, 0.0);
  }
  m.line(kUp * kLift, false, kRetreatSpeed, 0.0);
  if (!e.tuck_where_possible()) return false;
  if (w.grasped_object() < 0) return e.fail(PrimitiveStatus::grasp_failure, "dropped the tool");
  return true;
}

// Symbolically: the substance leaves the object, if what the hand holds
// removes it (the knowledge base's particleRemover conditions), saturated
// with one of the solvents the substance needs where it needs one.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const int agent = agent_index(objects);
  if (agent < 0 || a.held < 0 || a.substance < 0) return {};
  const auto removes = objects[a.held].removes.find(objects[a.substance].synset);
  if (removes == objects[a.held].removes.end()) return {};
  SymbolicStep base;
  base.needs = {literal("grasped", {agent, a.held}), literal(kWithinReach, {a.target}),
                literal("covered", {a.target, a.substance})};
  base.deletes = {literal("covered", {a.target, a.substance})};
  if (removes->second.empty()) return {base};
  std::vector<SymbolicStep> out;
  for (const std::string& solvent : removes->second) {
    for (int o = 0; o < static_cast<int>(objects.size()); ++o) {
      if (objects[o].synset != solvent) continue;
      out.push_back(base);
      out.back().needs.push_back(literal("saturated", {a.held, o}));
    }
  }
  return out;
}

}  // namespace

const PrimitiveDef& wipe_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .approaches = approaches,
                                .line_end = line_end,
                                .out_of_reach = out_of_reach,
                                .about_substance = true,
                                .with_tool = true,
                                .yaw_spread = kYawSpread};
  return def;
}

}  // namespace chore
