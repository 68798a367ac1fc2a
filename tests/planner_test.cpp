// The planner's symbolic problem and its relaxed reachability, on hand-built
// activities with known answers.
#include <gtest/gtest.h>

#include <algorithm>

#include "planner/reachability.hpp"
#include "planner/task_planner.hpp"
#include "tasks/goal.hpp"
#include "tasks/intermediates.hpp"
#include "tasks/vocabulary.hpp"

namespace chore {
namespace {

struct Case {
  Problem problem;
  SymbolicProblem symbolic;
  Reachability reach;
  GoalReach goal;
};

const TransitionRules& rules() {
  static const auto r = TransitionRules::load();
  return *r;
}

Case solve(const std::string& objects, const std::string& init, const std::string& goal,
           const std::string& domain = "omnigibson") {
  Case c;
  c.problem = parse_bddl("(define (problem p) (:domain " + domain + ") (:objects " + objects + ") (:init " + init +
                             ") (:goal " + goal + "))",
                         "test.bddl");
  const auto kb = dialect_knowledge_base(c.problem.domain);
  declare_intermediates(c.problem, *kb, rules());  // as the loaders do
  c.symbolic = symbolic_problem(c.problem, *kb, rules());
  c.reach = reachability(c.symbolic);
  c.goal = goal_reach(c.symbolic, c.reach, ground_goal(c.problem), *kb, rules());
  return c;
}

bool achievable(const Case& c, const std::string& predicate, std::vector<std::string> args, bool negated = false) {
  return c.reach.achievable(c.symbolic, Literal{predicate, std::move(args), negated});
}

constexpr const char* kKitchen =
    "apple.n.01_1 - apple.n.01 countertop.n.01_1 - countertop.n.01 agent.n.01_1 - agent.n.01 "
    "floor.n.01_1 - floor.n.01";
constexpr const char* kKitchenInit =
    "(ontop apple.n.01_1 countertop.n.01_1) (inroom countertop.n.01_1 kitchen) (inroom floor.n.01_1 kitchen) "
    "(ontop agent.n.01_1 floor.n.01_1)";

// Placing: navigate, pick, place puts the apple on the floor; nothing the
// six primitives do puts it inside anything or opens a fixed countertop.
TEST(Planner, PlacementsThePrimitivesMake) {
  const Case c = solve(kKitchen, kKitchenInit, "(and (ontop apple.n.01_1 floor.n.01_1))");
  EXPECT_TRUE(achievable(c, "ontop", {"apple.n.01_1", "floor.n.01_1"}));
  EXPECT_EQ(c.reach.achiever.at({"ontop", {0, 3}}), "place(floor.n.01_1)");
  EXPECT_TRUE(achievable(c, "grasped", {"agent.n.01_1", "apple.n.01_1"}));
  EXPECT_FALSE(achievable(c, "ontop", {"countertop.n.01_1", "floor.n.01_1"}));  // fixed: never picked
  EXPECT_FALSE(achievable(c, "inside", {"apple.n.01_1", "countertop.n.01_1"}));
  // Negated goals: the apple can leave the countertop (pick deletes it).
  EXPECT_TRUE(achievable(c, "ontop", {"apple.n.01_1", "countertop.n.01_1"}, true));
  EXPECT_EQ(c.goal.literals, 1u);
  EXPECT_EQ(c.goal.achievable, 1u);
}

// Cooking: a steak on a pan on a stove that is on becomes cooked (the pan is
// heated by the stove, the steak by the pan); with the stove off, toggle_on
// turns it on first; with no heat source at all, nothing cooks it.
TEST(Planner, HeatThroughWhatObjectsLieOn) {
  const std::string objects =
      "steak.n.01_1 - steak.n.01 frying_pan.n.01_1 - frying_pan.n.01 stove.n.01_1 - stove.n.01 "
      "agent.n.01_1 - agent.n.01";
  const std::string on =
      "(ontop steak.n.01_1 frying_pan.n.01_1) (ontop frying_pan.n.01_1 stove.n.01_1) "
      "(inroom stove.n.01_1 kitchen)";
  const Case lit = solve(objects, on + " (toggled_on stove.n.01_1)", "(and (cooked steak.n.01_1))");
  EXPECT_TRUE(achievable(lit, "cooked", {"steak.n.01_1"}));
  EXPECT_TRUE(achievable(lit, "hot", {"steak.n.01_1"}));
  EXPECT_EQ(lit.reach.achiever.at({"cooked", {0}}), "heat(steak.n.01_1)");
  const Case off = solve(objects, on, "(and (cooked steak.n.01_1))");
  EXPECT_TRUE(achievable(off, "cooked", {"steak.n.01_1"}));
  EXPECT_EQ(off.reach.achiever.at({"toggled_on", {2}}), "toggle_on(stove.n.01_1)");
  const Case cold = solve("steak.n.01_1 - steak.n.01 frying_pan.n.01_1 - frying_pan.n.01 agent.n.01_1 - agent.n.01",
                          "(ontop steak.n.01_1 frying_pan.n.01_1)", "(and (cooked steak.n.01_1))");
  EXPECT_FALSE(achievable(cold, "cooked", {"steak.n.01_1"}));
  EXPECT_EQ(cold.goal.unachievable.at("cooked"), std::vector<std::string>{"(cooked steak.n.01_1)"});
}

// Cleaning: a rag removes dust as it is; a stain on the same table needs the
// rag saturated with water (the knowledge base's particleRemover conditions),
// which dip gives where a bucket holds water.
TEST(Planner, CleaningFollowsTheRemoversConditions) {
  const std::string objects =
      "table.n.02_1 - table.n.02 rag.n.01_1 - rag.n.01 dust.n.01_1 - dust.n.01 mud.n.03_1 - mud.n.03 "
      "agent.n.01_1 - agent.n.01";
  const std::string init =
      "(covered table.n.02_1 dust.n.01_1) (covered table.n.02_1 mud.n.03_1) "
      "(ontop rag.n.01_1 table.n.02_1) (inroom table.n.02_1 kitchen)";
  const std::string goal = "(and (not (covered table.n.02_1 dust.n.01_1)) (not (covered table.n.02_1 mud.n.03_1)))";
  const Case dry = solve(objects, init, goal);
  EXPECT_TRUE(achievable(dry, "covered", {"table.n.02_1", "dust.n.01_1"}, true));
  EXPECT_FALSE(achievable(dry, "covered", {"table.n.02_1", "mud.n.03_1"}, true));
  EXPECT_EQ(dry.goal.achievable, 1u);
  EXPECT_EQ(dry.goal.unachievable.at("not covered").size(), 1u);

  const Case wet = solve(objects + " bucket.n.01_1 - bucket.n.01 water.n.06_1 - water.n.06",
                         init + " (filled bucket.n.01_1 water.n.06_1) (ontop bucket.n.01_1 table.n.02_1)", goal);
  EXPECT_TRUE(achievable(wet, "saturated", {"rag.n.01_1", "water.n.06_1"}));
  EXPECT_TRUE(achievable(wet, "covered", {"table.n.02_1", "mud.n.03_1"}, true));
  EXPECT_EQ(wet.goal.achievable, 2u);

  // What the conditions do not name, the remover's defaults decide: sand
  // (a visual substance; default_visual_conditions []) comes off as it is;
  // rust is named with null: a rag does not take it off.
  const Case defaults = solve(
      "mussel.n.01_1 - mussel.n.01 rag.n.01_1 - rag.n.01 sand.n.04_1 - sand.n.04 rust.n.01_1 - rust.n.01 "
      "table.n.02_1 - table.n.02 agent.n.01_1 - agent.n.01",
      "(covered mussel.n.01_1 sand.n.04_1) (covered mussel.n.01_1 rust.n.01_1) (ontop mussel.n.01_1 table.n.02_1) "
      "(ontop rag.n.01_1 table.n.02_1) (inroom table.n.02_1 kitchen)",
      "(and (not (covered mussel.n.01_1 sand.n.04_1)) (not (covered mussel.n.01_1 rust.n.01_1)))");
  EXPECT_TRUE(achievable(defaults, "covered", {"mussel.n.01_1", "sand.n.04_1"}, true));
  EXPECT_FALSE(achievable(defaults, "covered", {"mussel.n.01_1", "rust.n.01_1"}, true));
}

// Washers (washer.json): a towel inside one that is on loses its dust to
// water alone, its stain only with a solvent poured in (detergent), its rust
// never, and is soaked; a dryer that is on dries it.
TEST(Planner, WashersCleanAsWasherJsonSaysAndDryersDry) {
  const std::string objects =
      "washer.n.03_1 - washer.n.03 dishtowel.n.01_1 - dishtowel.n.01 stain.n.01_1 - stain.n.01 "
      "dust.n.01_1 - dust.n.01 rust.n.01_1 - rust.n.01 water.n.06_1 - water.n.06 floor.n.01_1 - floor.n.01 "
      "agent.n.01_1 - agent.n.01";
  const std::string init =
      "(ontop dishtowel.n.01_1 floor.n.01_1) (covered dishtowel.n.01_1 stain.n.01_1) "
      "(covered dishtowel.n.01_1 dust.n.01_1) (covered dishtowel.n.01_1 rust.n.01_1) "
      "(inroom washer.n.03_1 utility_room) (inroom floor.n.01_1 utility_room) (ontop agent.n.01_1 floor.n.01_1)";
  const std::string goal = "(and (not (covered dishtowel.n.01_1 dust.n.01_1)))";
  const Case water = solve(objects, init, goal);
  EXPECT_TRUE(achievable(water, "inside", {"dishtowel.n.01_1", "washer.n.03_1"}));
  EXPECT_TRUE(achievable(water, "covered", {"dishtowel.n.01_1", "dust.n.01_1"}, true));
  EXPECT_EQ(water.reach.achiever.count({"saturated", {1, 5}}), 1u);
  EXPECT_EQ(water.reach.achiever.at({"saturated", {1, 5}}), "washer(dishtowel.n.01_1)");
  EXPECT_FALSE(achievable(water, "covered", {"dishtowel.n.01_1", "stain.n.01_1"}, true));
  EXPECT_FALSE(achievable(water, "covered", {"dishtowel.n.01_1", "rust.n.01_1"}, true));

  const Case detergent = solve(
      objects + " detergent.n.02_1 - detergent.n.02 detergent__bottle.n.01_1 - detergent__bottle.n.01",
      init + " (filled detergent__bottle.n.01_1 detergent.n.02_1) (ontop detergent__bottle.n.01_1 floor.n.01_1)", goal);
  EXPECT_TRUE(achievable(detergent, "contains", {"washer.n.03_1", "detergent.n.02_1"}));
  EXPECT_TRUE(achievable(detergent, "covered", {"dishtowel.n.01_1", "stain.n.01_1"}, true));
  EXPECT_FALSE(achievable(detergent, "covered", {"dishtowel.n.01_1", "rust.n.01_1"}, true));

  const std::string wet = init + " (saturated dishtowel.n.01_1 water.n.06_1)";
  EXPECT_FALSE(achievable(solve(objects, wet, goal), "saturated", {"dishtowel.n.01_1", "water.n.06_1"}, true));
  EXPECT_TRUE(achievable(solve(objects + " clothes_dryer.n.01_1 - clothes_dryer.n.01",
                               wet + " (inroom clothes_dryer.n.01_1 utility_room)", goal),
                         "saturated", {"dishtowel.n.01_1", "water.n.06_1"}, true));
}

// Transition rules: an apple cut with a knife becomes its halves
// (slicing.json); without a knife the rule cannot fire; a blender
// that is on turns what is inside it into the recipe's output; a sink that
// is on gives water (its particleSource conditions).
TEST(Planner, TransitionRulesAndSources) {
  const Case apple = solve(
      "apple.n.01_1 - apple.n.01 carving_knife.n.01_1 - carving_knife.n.01 half__apple.n.01_1 half__apple.n.01_2 - "
      "half__apple.n.01 agent.n.01_1 - agent.n.01",
      "(future half__apple.n.01_1) (future half__apple.n.01_2)", "(and (real half__apple.n.01_1))");
  EXPECT_TRUE(apple.goal.future_without_rule.empty());
  // The knife cuts the apple (cut), the slicing rule makes the halves.
  EXPECT_TRUE(apple.goal.future_unreachable.empty());
  EXPECT_EQ(apple.reach.achiever.at({"sliced", {0}}), "cut(apple.n.01_1)");
  EXPECT_EQ(apple.reach.achiever.at({"real", {2}}), "slicing:apple.n.01-slicing");
  // With no knife, nothing cuts it: the rule is there, its halves are not.
  const Case no_knife = solve(
      "apple.n.01_1 - apple.n.01 half__apple.n.01_1 half__apple.n.01_2 - half__apple.n.01 agent.n.01_1 - agent.n.01",
      "(future half__apple.n.01_1) (future half__apple.n.01_2)", "(and (real half__apple.n.01_1))");
  EXPECT_TRUE(no_knife.goal.future_without_rule.empty());
  EXPECT_EQ(no_knife.goal.future_unreachable, (std::vector<std::string>{"half__apple.n.01_1", "half__apple.n.01_2"}));

  const std::string smoothie_objects =
      "strawberry.n.01_1 - strawberry.n.01 ice_cube.n.01_1 - ice_cube.n.01 lemon_juice.n.01_1 - lemon_juice.n.01 "
      "blender.n.01_1 - blender.n.01 smoothie.n.02_1 - smoothie.n.02 agent.n.01_1 - agent.n.01";
  const std::string in_blender =
      "(inside strawberry.n.01_1 blender.n.01_1) (inside ice_cube.n.01_1 blender.n.01_1) "
      "(filled blender.n.01_1 lemon_juice.n.01_1) (future smoothie.n.02_1) "
      "(inroom blender.n.01_1 kitchen)";
  const Case on = solve(smoothie_objects, in_blender + " (toggled_on blender.n.01_1)",
                        "(and (real smoothie.n.02_1) (contains blender.n.01_1 smoothie.n.02_1))");
  EXPECT_EQ(on.goal.achievable, 2u);
  EXPECT_EQ(on.reach.achiever.at({"real", {4}}), "single_toggleable_machine:smoothie_0");
  // Off, toggle_on turns the blender on first; without the lemon juice the recipe cannot run.
  const Case off = solve(smoothie_objects, in_blender, "(and (real smoothie.n.02_1))");
  EXPECT_EQ(off.goal.achievable, 1u);
  EXPECT_EQ(off.reach.achiever.at({"toggled_on", {3}}), "toggle_on(blender.n.01_1)");
  const Case dry = solve(smoothie_objects,
                         "(inside strawberry.n.01_1 blender.n.01_1) (inside ice_cube.n.01_1 blender.n.01_1) "
                         "(future smoothie.n.02_1) (inroom blender.n.01_1 kitchen) (toggled_on blender.n.01_1)",
                         "(and (real smoothie.n.02_1))");
  EXPECT_EQ(dry.goal.achievable, 0u);

  const Case sink =
      solve("sink.n.01_1 - sink.n.01 water.n.06_1 - water.n.06 agent.n.01_1 - agent.n.01",
            "(inroom sink.n.01_1 kitchen) (toggled_on sink.n.01_1)", "(and (contains sink.n.01_1 water.n.06_1))");
  EXPECT_EQ(sink.goal.achievable, 1u);
  EXPECT_EQ(sink.reach.achiever.at({"contains", {0, 1}}), "particleSource(sink.n.01_1)");
}

// Filling and pouring: water from the sink fills a mug or bowl dipped under
// it, and a bathtub only by pouring from one; a shaker (a particleApplier,
// toggled on as it is held) covers the salad. Without the sink, no water
// reaches the bowl.
TEST(Planner, PouringFromAContainerOrAnApplier) {
  const std::string objects =
      "sink.n.01_1 - sink.n.01 mug.n.04_1 - mug.n.04 bowl.n.01_1 - bowl.n.01 water.n.06_1 - water.n.06 "
      "countertop.n.01_1 - countertop.n.01 agent.n.01_1 - agent.n.01";
  const std::string init =
      "(ontop mug.n.04_1 countertop.n.01_1) (ontop bowl.n.01_1 countertop.n.01_1) (inroom sink.n.01_1 kitchen) "
      "(inroom countertop.n.01_1 kitchen)";
  const Case water = solve(objects, init, "(and (contains bowl.n.01_1 water.n.06_1))");
  EXPECT_EQ(water.goal.achievable, 1u);
  // The bowl itself can be dipped under the tap too: the first achiever found.
  EXPECT_EQ(water.reach.achiever.at({"contains", {2, 3}}), "dip(sink.n.01_1)");
  EXPECT_EQ(water.reach.achiever.at({"contains", {1, 3}}), "dip(sink.n.01_1)");
  EXPECT_EQ(water.reach.achiever.at({"toggled_on", {0}}), "toggle_on(sink.n.01_1)");
  // Into what stays where it stands, only pouring from the mug fills it.
  const Case tub = solve(objects + " bathtub.n.01_1 - bathtub.n.01", init + " (inroom bathtub.n.01_1 kitchen)",
                         "(and (contains bathtub.n.01_1 water.n.06_1))");
  EXPECT_EQ(tub.goal.achievable, 1u);
  EXPECT_EQ(tub.reach.achiever.at({"contains", {6, 3}}), "pour(bathtub.n.01_1)");
  const Case dry = solve(
      "mug.n.04_1 - mug.n.04 bowl.n.01_1 - bowl.n.01 water.n.06_1 - water.n.06 countertop.n.01_1 - countertop.n.01 "
      "agent.n.01_1 - agent.n.01",
      "(ontop mug.n.04_1 countertop.n.01_1) (ontop bowl.n.01_1 countertop.n.01_1) (inroom countertop.n.01_1 kitchen)",
      "(and (contains bowl.n.01_1 water.n.06_1))");
  EXPECT_EQ(dry.goal.achievable, 0u);

  const Case salad = solve(
      "salad.n.01_1 - salad.n.01 cinnamon__shaker.n.01_1 - cinnamon__shaker.n.01 cinnamon.n.03_1 - cinnamon.n.03 "
      "countertop.n.01_1 - countertop.n.01 agent.n.01_1 - agent.n.01",
      "(ontop salad.n.01_1 countertop.n.01_1) (ontop cinnamon__shaker.n.01_1 countertop.n.01_1) "
      "(inroom countertop.n.01_1 kitchen)",
      "(and (covered salad.n.01_1 cinnamon.n.03_1))");
  EXPECT_EQ(salad.goal.achievable, 1u);
  EXPECT_EQ(salad.reach.achiever.at({"covered", {0, 2}}), "pour(salad.n.01_1)");
}

// What the rules make on the way is there to be made, undeclared: BEHAVIOR-
// 1K's chop_an_onion declares the onion and its diced pieces; slicing makes
// the halves that dicing takes. Without the knife, neither. Diced pieces
// stay where the halves were.
TEST(Planner, IntermediatesTheRulesMakeOnTheWay) {
  const std::string objects =
      "vidalia_onion.n.01_1 - vidalia_onion.n.01 diced__vidalia_onion.n.01_1 - diced__vidalia_onion.n.01 "
      "countertop.n.01_1 - countertop.n.01 agent.n.01_1 - agent.n.01";
  const std::string init =
      "(ontop vidalia_onion.n.01_1 countertop.n.01_1) (future diced__vidalia_onion.n.01_1) "
      "(inroom countertop.n.01_1 kitchen)";
  const Case knife = solve(objects + " parer.n.02_1 - parer.n.02", init + " (ontop parer.n.02_1 countertop.n.01_1)",
                           "(and (real diced__vidalia_onion.n.01_1))");
  const int halves = knife.symbolic.index("half__vidalia_onion.n.01_made");
  ASSERT_GE(halves, 0);
  EXPECT_TRUE(knife.symbolic.init.count({"future", {halves}}));
  EXPECT_EQ(knife.reach.achiever.at({"real", {halves}}), "slicing:vidalia_onion.n.01-slicing");
  EXPECT_EQ(knife.reach.achiever.at({"real", {1}}), "dicing:uncooked-half__vidalia_onion.n.01-dicing");
  EXPECT_EQ(knife.goal.achievable, 1u);
  EXPECT_EQ(knife.goal.future, 2u);  // the diced pieces and the halves before them
  const Case none = solve(objects, init, "(and (real diced__vidalia_onion.n.01_1))");
  EXPECT_EQ(none.goal.achievable, 0u);

  // Diced where the halves lie: in a bowl, the bowl contains the pieces.
  const Case bowl = solve(objects + " parer.n.02_1 - parer.n.02 bowl.n.01_1 - bowl.n.01",
                          init + " (ontop parer.n.02_1 countertop.n.01_1) (ontop bowl.n.01_1 countertop.n.01_1)",
                          "(and (contains bowl.n.01_1 diced__vidalia_onion.n.01_1))");
  EXPECT_EQ(bowl.goal.achievable, 1u);
  EXPECT_EQ(bowl.reach.achiever.at({"contains", {5, 1}}), "dicing:uncooked-half__vidalia_onion.n.01-dicing");
}

// attach joins two objects the knowledge base calls attachable (a lid and
// its jar), not an apple to a counter; picking the lid up ends it.
TEST(Planner, AttachingNeedsTwoAttachableObjects) {
  const Case c = solve(
      "lid.n.02_1 - lid.n.02 hingeless_jar.n.01_1 - hingeless_jar.n.01 apple.n.01_1 - apple.n.01 "
      "countertop.n.01_1 - countertop.n.01 agent.n.01_1 - agent.n.01",
      "(ontop lid.n.02_1 countertop.n.01_1) (ontop hingeless_jar.n.01_1 countertop.n.01_1) "
      "(ontop apple.n.01_1 countertop.n.01_1) (inroom countertop.n.01_1 kitchen)",
      "(and (attached lid.n.02_1 hingeless_jar.n.01_1) (attached apple.n.01_1 countertop.n.01_1))");
  EXPECT_EQ(c.reach.achiever.at({"attached", {0, 1}}), "attach(hingeless_jar.n.01_1)");
  EXPECT_FALSE(achievable(c, "attached", {"apple.n.01_1", "countertop.n.01_1"}));
  EXPECT_EQ(c.goal.achievable, 1u);
  const Case on = solve("lid.n.02_1 - lid.n.02 hingeless_jar.n.01_1 - hingeless_jar.n.01 agent.n.01_1 - agent.n.01",
                        "(attached lid.n.02_1 hingeless_jar.n.01_1) (inroom hingeless_jar.n.01_1 kitchen)",
                        "(and (not (attached lid.n.02_1 hingeless_jar.n.01_1)))");
  EXPECT_EQ(on.goal.achievable, 1u);
}

// Future objects no rule makes are named.
TEST(Planner, FutureObjectsWithoutARule) {
  const Case c = solve("apple.n.01_1 - apple.n.01 agent.n.01_1 - agent.n.01", "(future apple.n.01_1)",
                       "(and (real apple.n.01_1))");
  EXPECT_EQ(c.goal.future_without_rule, std::vector<std::string>{"apple.n.01_1"});
}

// BEHAVIOR-100's dialect, read in BEHAVIOR-1K's terms: a dusty table is
// cleaned by a cleaning tool, a stained one by a soaked tool.
TEST(Planner, BehaviorHundredInOneKsTerms) {
  const std::string objects = "table.n.02_1 - table.n.02 rag.n.01_1 - rag.n.01 agent.n.01_1 - agent.n.01";
  const std::string init =
      "(dusty table.n.02_1) (stained table.n.02_1) (ontop rag.n.01_1 table.n.02_1) "
      "(inroom table.n.02_1 kitchen)";
  const Case c = solve(objects, init, "(and (not (dusty table.n.02_1)) (not (stained table.n.02_1)))", "igibson");
  EXPECT_TRUE(achievable(c, "dusty", {"table.n.02_1"}, true));
  EXPECT_FALSE(achievable(c, "stained", {"table.n.02_1"}, true));  // no water to soak the rag in
}

std::vector<std::string> names(const Plan& p) {
  std::vector<std::string> out;
  for (const PlanStep& s : p.steps) out.push_back(s.primitive ? s.name : "[" + s.name + "]");
  return out;
}

// Where `step` first stands in `steps` (steps.size() where it does not).
long position(const std::vector<std::string>& steps, const char* step) {
  return std::find(steps.begin(), steps.end(), step) - steps.begin();
}

// The planner's known answers: the shortest plan where the search finds it
// directly, a cooking plan through the world's steps, and each way it ends
// without one.
TEST(TaskPlanner, PlansThroughThePrimitivesAndTheWorldsSteps) {
  const Case floor = solve(kKitchen, kKitchenInit, "(and (ontop apple.n.01_1 floor.n.01_1))");
  const Plan put = plan_task(floor.symbolic, ground_goal(floor.problem));
  ASSERT_TRUE(put.found) << put.reason;
  // Onto the floor, or beside the countertop (furniture: on its room's floor).
  const std::vector<std::vector<std::string>> shortest = {
      {"navigate(apple.n.01_1)", "pick(apple.n.01_1)", "navigate(floor.n.01_1)", "place(floor.n.01_1)"},
      {"navigate(apple.n.01_1)", "pick(apple.n.01_1)", "navigate(countertop.n.01_1)",
       "place_next_to(countertop.n.01_1)"}};
  EXPECT_NE(std::find(shortest.begin(), shortest.end(), names(put)), shortest.end())
      << testing::PrintToString(names(put));
  EXPECT_EQ(put.primitives(), 4u);

  // A steak cooks where it lies on a stove that is on: the world's steps
  // (heated, then heat's cooked) follow the primitives that set it there.
  const Case cook = solve(
      "steak.n.01_1 - steak.n.01 stove.n.01_1 - stove.n.01 countertop.n.01_1 - countertop.n.01 "
      "floor.n.01_1 - floor.n.01 agent.n.01_1 - agent.n.01",
      "(ontop steak.n.01_1 countertop.n.01_1) (inroom stove.n.01_1 kitchen) (inroom countertop.n.01_1 kitchen) "
      "(inroom floor.n.01_1 kitchen) (ontop agent.n.01_1 floor.n.01_1)",
      "(and (cooked steak.n.01_1))");
  const Plan cooked = plan_task(cook.symbolic, ground_goal(cook.problem));
  ASSERT_TRUE(cooked.found) << cooked.reason;
  const std::vector<std::string> steps = names(cooked);
  for (const char* step : {"pick(steak.n.01_1)", "toggle_on(stove.n.01_1)", "[heated(steak.n.01_1)]"})
    EXPECT_NE(std::find(steps.begin(), steps.end(), step), steps.end()) << step;
  EXPECT_EQ(steps.back(), "[heat(steak.n.01_1)]");  // what makes it cooked
  EXPECT_LE(cooked.primitives(), 6u);

  // The goal's options: either apple on the floor (or) is as good.
  const Case either = solve(kKitchen + std::string(" apple.n.01_2 - apple.n.01"),
                            kKitchenInit + std::string(" (ontop apple.n.01_2 countertop.n.01_1)"),
                            "(and (or (inside apple.n.01_1 countertop.n.01_1) (ontop apple.n.01_2 floor.n.01_1)))");
  const Plan one = plan_task(either.symbolic, ground_goal(either.problem));
  ASSERT_TRUE(one.found) << one.reason;
  EXPECT_EQ(one.primitives(), 4u);
  EXPECT_EQ(names(one)[1], "pick(apple.n.01_2)");  // the option that can hold

  // Nothing puts an apple inside a countertop: no search at all.
  const Case never = solve(kKitchen, kKitchenInit, "(and (inside apple.n.01_1 countertop.n.01_1))");
  const Plan none = plan_task(never.symbolic, ground_goal(never.problem));
  EXPECT_FALSE(none.found);
  EXPECT_EQ(none.reason,
            "no sequence of the primitives and the world's steps reaches the goal: "
            "(inside apple.n.01_1 countertop.n.01_1): no step makes it");
  EXPECT_LE(none.expansions, 1u);
  // A budget is an outcome.
  const Plan cut = plan_task(floor.symbolic, ground_goal(floor.problem), {.max_expansions = 2});
  EXPECT_FALSE(cut.found);
  EXPECT_EQ(cut.reason, "no plan within 2 expansions");
  // What a plan would act on is known before any search: the relaxed plan's
  // primitives from the start (the env's reach checks take them when the
  // search runs out), here one of the shortest plans' four, unordered. None
  // where no option is reachable even relaxed.
  std::vector<std::string> relaxed = cut.relaxed;
  std::sort(relaxed.begin(), relaxed.end());
  EXPECT_TRUE(std::any_of(shortest.begin(), shortest.end(), [&](std::vector<std::string> plan) {
    std::sort(plan.begin(), plan.end());
    return plan == relaxed;
  })) << testing::PrintToString(relaxed);
  EXPECT_TRUE(none.relaxed.empty());
}

// Where no sequence reaches the goal, the reason follows the first missing
// literal back through what would make it: halves need the apple sliced, and
// with no knife nothing slices it; mud needs a solvent no object gives, so no
// step wipes it off.
TEST(TaskPlanner, SaysWhatTheGoalLacksAndWhy) {
  const Case no_knife = solve(
      "apple.n.01_1 - apple.n.01 half__apple.n.01_1 half__apple.n.01_2 - half__apple.n.01 agent.n.01_1 - agent.n.01 "
      "countertop.n.01_1 - countertop.n.01",
      "(future half__apple.n.01_1) (future half__apple.n.01_2) (ontop apple.n.01_1 countertop.n.01_1) "
      "(inroom countertop.n.01_1 kitchen)",
      "(and (real half__apple.n.01_1))");
  EXPECT_EQ(plan_task(no_knife.symbolic, ground_goal(no_knife.problem)).reason,
            "no sequence of the primitives and the world's steps reaches the goal: "
            "(real half__apple.n.01_1) needs (sliced apple.n.01_1): no step makes it");
  const Case mud =
      solve("table.n.02_1 - table.n.02 rag.n.01_1 - rag.n.01 mud.n.03_1 - mud.n.03 agent.n.01_1 - agent.n.01",
            "(covered table.n.02_1 mud.n.03_1) (ontop rag.n.01_1 table.n.02_1) (inroom table.n.02_1 kitchen)",
            "(and (not (covered table.n.02_1 mud.n.03_1)))");
  EXPECT_EQ(plan_task(mud.symbolic, ground_goal(mud.problem)).reason,
            "no sequence of the primitives and the world's steps reaches the goal: "
            "(not (covered table.n.02_1 mud.n.03_1)): no step removes it");
}

// The world's rules fire as soon as their trigger holds (a cut dices the
// half at once, where it lies), so a plan for diced onion in a bowl puts the
// half in the bowl before it cuts it; the rules' steps follow the primitive
// that set them off.
TEST(TaskPlanner, RulesFireAtOnce) {
  const Case c = solve(
      "vidalia_onion.n.01_1 - vidalia_onion.n.01 diced__vidalia_onion.n.01_1 - diced__vidalia_onion.n.01 "
      "parer.n.02_1 - parer.n.02 bowl.n.01_1 - bowl.n.01 chopping_board.n.01_1 - chopping_board.n.01 "
      "countertop.n.01_1 - countertop.n.01 agent.n.01_1 - agent.n.01",
      "(ontop vidalia_onion.n.01_1 chopping_board.n.01_1) (ontop chopping_board.n.01_1 countertop.n.01_1) "
      "(ontop parer.n.02_1 countertop.n.01_1) (ontop bowl.n.01_1 countertop.n.01_1) "
      "(future diced__vidalia_onion.n.01_1) (inroom countertop.n.01_1 kitchen)",
      "(and (contains bowl.n.01_1 diced__vidalia_onion.n.01_1))");
  const Plan p = plan_task(c.symbolic, ground_goal(c.problem));
  ASSERT_TRUE(p.found) << p.reason;
  const std::vector<std::string> steps = names(p);
  const auto at = [&](const std::string& name) { return std::find(steps.begin(), steps.end(), name) - steps.begin(); };
  const auto cut_onion = at("cut(vidalia_onion.n.01_1)"), cut_half = at("cut(half__vidalia_onion.n.01_made)");
  ASSERT_LT(cut_half, static_cast<long>(steps.size())) << testing::PrintToString(steps);
  EXPECT_EQ(steps[cut_onion + 1], "[slicing:vidalia_onion.n.01-slicing]");
  EXPECT_EQ(steps[cut_half + 1], "[dicing:uncooked-half__vidalia_onion.n.01-dicing]");
  EXPECT_LT(at("place(bowl.n.01_1)"), cut_half);  // the half into the bowl first
  EXPECT_EQ(steps.back(), "[dicing:uncooked-half__vidalia_onion.n.01-dicing]");
}

// place_next_to sets the load down on what the object stands on: firewood
// by a fireplace (furniture: on its room's floor) is on that floor, and a
// book by another on a shelf is on the shelf, so a goal asking for both
// relations is one placement each.
TEST(TaskPlanner, NextToIsOnWhatTheObjectStandsOn) {
  const Case fire = solve(
      "firewood.n.01_1 - firewood.n.01 wood_fireplace.n.01_1 - wood_fireplace.n.01 driveway.n.01_1 - driveway.n.01 "
      "floor.n.01_1 floor.n.01_2 - floor.n.01 agent.n.01_1 - agent.n.01",
      "(ontop firewood.n.01_1 driveway.n.01_1) (inroom driveway.n.01_1 garden) (inroom floor.n.01_1 garden) "
      "(inroom floor.n.01_2 living_room) (inroom wood_fireplace.n.01_1 living_room) "
      "(ontop agent.n.01_1 floor.n.01_1)",
      "(and (ontop firewood.n.01_1 floor.n.01_2) (nextto firewood.n.01_1 wood_fireplace.n.01_1))");
  const Plan by_fire = plan_task(fire.symbolic, ground_goal(fire.problem));
  ASSERT_TRUE(by_fire.found) << by_fire.reason;
  EXPECT_EQ(names(by_fire),
            (std::vector<std::string>{"navigate(firewood.n.01_1)", "pick(firewood.n.01_1)",
                                      "navigate(wood_fireplace.n.01_1)", "place_next_to(wood_fireplace.n.01_1)"}));
  const Case shelf = solve(
      "hardback.n.01_1 hardback.n.01_2 - hardback.n.01 shelf.n.01_1 - shelf.n.01 table.n.02_1 - table.n.02 "
      "agent.n.01_1 - agent.n.01",
      "(ontop hardback.n.01_1 table.n.02_1) (ontop hardback.n.01_2 shelf.n.01_1) (inroom shelf.n.01_1 kitchen) "
      "(inroom table.n.02_1 kitchen)",
      "(and (ontop hardback.n.01_1 shelf.n.01_1) (nextto hardback.n.01_1 hardback.n.01_2))");
  const Plan by_book = plan_task(shelf.symbolic, ground_goal(shelf.problem));
  ASSERT_TRUE(by_book.found) << by_book.reason;
  EXPECT_EQ(names(by_book).back(), "place_next_to(hardback.n.01_2)");
  EXPECT_EQ(by_book.primitives(), 4u);
  // Where it lies on nothing known, next to it is on nothing known.
  const Case loose = solve(
      "hardback.n.01_1 hardback.n.01_2 - hardback.n.01 shelf.n.01_1 - shelf.n.01 table.n.02_1 - table.n.02 "
      "agent.n.01_1 - agent.n.01",
      "(ontop hardback.n.01_1 table.n.02_1) (inroom shelf.n.01_1 kitchen) (inroom table.n.02_1 kitchen)",
      "(and (ontop hardback.n.01_1 shelf.n.01_1) (nextto hardback.n.01_1 hardback.n.01_2))");
  const Plan two = plan_task(loose.symbolic, ground_goal(loose.problem));
  ASSERT_TRUE(two.found) << two.reason;
  EXPECT_GT(two.primitives(), 4u);  // the second book goes onto the shelf first
}

// A mug in a closed cabinet is picked only once the cabinet is pushed open
// (pick's model: out of what opens only while it is open); boiled in a
// microwave, the water that filled it leaves it filled with boiled water (the
// world gives the made substance the inputs' level: transitions.cpp).
TEST(TaskPlanner, OpensWhatHoldsTheObjectAndBoilsTheWaterThatFilledTheMug) {
  const std::string objects =
      "water.n.06_1 - water.n.06 cooked__water.n.01_1 - cooked__water.n.01 mug.n.04_1 - mug.n.04 "
      "cabinet.n.01_1 - cabinet.n.01 sink.n.01_1 - sink.n.01 microwave.n.02_1 - microwave.n.02 "
      "floor.n.01_1 - floor.n.01 agent.n.01_1 - agent.n.01";
  const std::string init =
      "(inside mug.n.04_1 cabinet.n.01_1) (insource sink.n.01_1 water.n.06_1) (future cooked__water.n.01_1) "
      "(inroom floor.n.01_1 kitchen) (inroom sink.n.01_1 kitchen) (inroom microwave.n.02_1 kitchen) "
      "(inroom cabinet.n.01_1 kitchen) (ontop agent.n.01_1 floor.n.01_1)";
  const Case picked = solve(objects, init, "(and (ontop mug.n.04_1 floor.n.01_1))");
  const Plan out = plan_task(picked.symbolic, ground_goal(picked.problem));
  ASSERT_TRUE(out.found) << out.reason;
  const std::vector<std::string> steps = names(out);
  const auto at = [&](const char* step) { return position(steps, step); };
  EXPECT_LT(at("push(cabinet.n.01_1)"), at("pick(mug.n.04_1)"));
  EXPECT_LT(at("pick(mug.n.04_1)"), static_cast<long>(steps.size()));

  const Case boiled = solve(objects, init,
                            "(and (real cooked__water.n.01_1) (filled mug.n.04_1 cooked__water.n.01_1) "
                            "(inside mug.n.04_1 microwave.n.02_1))");
  const Plan boil = plan_task(boiled.symbolic, ground_goal(boiled.problem));
  ASSERT_TRUE(boil.found) << boil.reason;
  const std::vector<std::string> boiling = names(boil);
  EXPECT_NE(std::find(boiling.begin(), boiling.end(), "dip(sink.n.01_1)"), boiling.end());
  EXPECT_EQ(boiling.back(), "[substance_cooking:water.n.06-cooking]");
}

// make_lemon_or_lime_water: an ice cube in a cup in the closed fridge. :init
// says where each is directly; the fridge shuts the cube in as well, and the
// plan opens it before the pick. (Said of the cup alone, the plan picked the
// cube through the fridge's door, and no base pose reached it.)
TEST(TaskPlanner, OpensWhatHoldsTheContainerTheObjectIsIn) {
  const Case iced = solve(
      "ice_cube.n.01_1 - ice_cube.n.01 cup.n.01_1 - cup.n.01 electric_refrigerator.n.01_1 - electric_refrigerator.n.01 "
      "water_glass.n.02_1 - water_glass.n.02 countertop.n.01_1 - countertop.n.01 floor.n.01_1 - floor.n.01 "
      "agent.n.01_1 - agent.n.01",
      "(inside ice_cube.n.01_1 cup.n.01_1) (inside cup.n.01_1 electric_refrigerator.n.01_1) "
      "(ontop water_glass.n.02_1 countertop.n.01_1) (inroom electric_refrigerator.n.01_1 kitchen) "
      "(inroom countertop.n.01_1 kitchen) (inroom floor.n.01_1 kitchen) (ontop agent.n.01_1 floor.n.01_1)",
      "(and (inside ?ice_cube.n.01_1 ?water_glass.n.02_1))");
  const Plan out = plan_task(iced.symbolic, ground_goal(iced.problem));
  ASSERT_TRUE(out.found) << out.reason;
  const std::vector<std::string> steps = names(out);
  const auto at = [&](const char* step) { return position(steps, step); };
  ASSERT_LT(at("pick(ice_cube.n.01_1)"), static_cast<long>(steps.size()));
  EXPECT_LT(at("push(electric_refrigerator.n.01_1)"), at("pick(ice_cube.n.01_1)"));
}

// cool_cakes: a hot cake in an oven that is on, to cool on a cookie sheet.
// The plan went to the cake first, while the oven was shut, to let it cool
// there; the base-pose search finds no pose to what a door shuts in, and the
// plan failed there at every seed. navigate's model, as pick's, reaches into
// what opens only while it is open.
TEST(TaskPlanner, GoesToWhatADoorShutsInOnlyOnceItIsOpen) {
  const std::string objects =
      "fruitcake.n.02_1 - fruitcake.n.02 oven.n.01_1 - oven.n.01 cookie_sheet.n.01_1 - cookie_sheet.n.01 "
      "countertop.n.01_1 - countertop.n.01 floor.n.01_1 - floor.n.01 agent.n.01_1 - agent.n.01";
  const std::string init =
      "(inside fruitcake.n.02_1 oven.n.01_1) (hot fruitcake.n.02_1) (ontop cookie_sheet.n.01_1 countertop.n.01_1) "
      "(inroom countertop.n.01_1 kitchen) (inroom oven.n.01_1 kitchen) (inroom floor.n.01_1 kitchen) "
      "(ontop agent.n.01_1 floor.n.01_1) (toggled_on oven.n.01_1)";
  const Case cool =
      solve(objects, init, "(and (not (hot fruitcake.n.02_1)) (ontop fruitcake.n.02_1 cookie_sheet.n.01_1))");
  const Plan out = plan_task(cool.symbolic, ground_goal(cool.problem));
  ASSERT_TRUE(out.found) << out.reason;
  const std::vector<std::string> steps = names(out);
  const auto at = [&](const char* step) { return position(steps, step); };
  ASSERT_LT(at("navigate(fruitcake.n.02_1)"), static_cast<long>(steps.size()));
  EXPECT_LT(at("push(oven.n.01_1)"), at("navigate(fruitcake.n.02_1)"));
}

// boxing_food_after_dinner: three kabobs into a tupperware, the tupperware
// into the closed fridge, the fridge closed again. Picking the tupperware up
// leaves what is in it behind, so the kabobs go in once it is in the fridge.
// The search found no plan in 200,000 expansions (greedy on h_add: opening
// the fridge and picking anything up raise it, and a tupperware in the closed
// fridge looked as near as one on the table, the relaxation blind to what a
// step needs absent); now 3,646, within the default budget, and the steps
// it can do without left out.
TEST(TaskPlanner, PutsTheTupperwareAwayBeforeFillingIt) {
  std::string objects =
      "tupperware.n.01_1 - tupperware.n.01 electric_refrigerator.n.01_1 - electric_refrigerator.n.01 "
      "breakfast_table.n.01_1 - breakfast_table.n.01 floor.n.01_1 - floor.n.01 agent.n.01_1 - agent.n.01";
  std::string init =
      "(ontop tupperware.n.01_1 breakfast_table.n.01_1) (inroom electric_refrigerator.n.01_1 kitchen) "
      "(inroom breakfast_table.n.01_1 dining_room) (inroom floor.n.01_1 kitchen) (ontop agent.n.01_1 floor.n.01_1)";
  for (const char* n : {"1", "2", "3"}) {
    objects += std::string(" kabob.n.01_") + n + " - kabob.n.01 plate.n.04_" + n + " - plate.n.04";
    init += std::string(" (ontop kabob.n.01_") + n + " plate.n.04_" + n + ") (ontop plate.n.04_" + n +
            " breakfast_table.n.01_1)";
  }
  const Case boxing = solve(objects, init,
                            "(and (forall (?kabob.n.01 - kabob.n.01) (inside ?kabob.n.01 ?tupperware.n.01_1)) "
                            "(inside ?tupperware.n.01_1 ?electric_refrigerator.n.01_1) "
                            "(not (open ?electric_refrigerator.n.01_1)))");
  const Plan out = plan_task(boxing.symbolic, ground_goal(boxing.problem));
  ASSERT_TRUE(out.found) << out.reason;
  const std::vector<std::string> steps = names(out);
  const auto at = [&](const char* step) { return position(steps, step); };
  EXPECT_LT(at("place(electric_refrigerator.n.01_1)"), at("place(tupperware.n.01_1)"));
  EXPECT_EQ(steps.back(), "close(electric_refrigerator.n.01_1)");
  EXPECT_EQ(std::count(steps.begin(), steps.end(), "place(tupperware.n.01_1)"), 3);
  // 6 to put the tupperware away, 4 per kabob, 2 to close: the search's way
  // had 23, three of them steps the plan does without.
  EXPECT_EQ(out.primitives(), 20u);
}

}  // namespace
}  // namespace chore
