// The world's transitions (world/transitions.hpp): the knowledge base's rules
// bound to chore's own test activities (tests/data/bddl/behavior-1k/) in their
// scene analogs, and made by the world as it steps. Slicing through the cut
// primitive is in primitives_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>

#include "env/env.hpp"
#include "env/env_impl.hpp"
#include "test_util.hpp"
#include "world/predicates.hpp"
#include "world/sampling.hpp"

namespace chore {
namespace {

// The activity's instances as sampled: the tests set the states the robot
// would (a machine or stove turned on) themselves.
EnvConfig config(const std::string& activity) {
  EnvConfig c = test::primitives_config(test::data_path("bddl/behavior-1k/" + activity + ".bddl"));
  c.reachable_instances = false;
  return c;
}

const Transition* bound(const World& w, const std::string& rule) {
  const std::vector<Transition>& all = w.states().transitions();
  const auto it = std::find_if(all.begin(), all.end(), [&](const Transition& t) { return t.name == rule; });
  return it == all.end() ? nullptr : &*it;
}

void run(World& w, double seconds) {
  for (int i = 0; i < static_cast<int>(seconds * 30); ++i) w.step(4);
}

TEST(Transitions, ACoffeeMakerTurnedOnMakesEspressoOfWaterAndInstantCoffee) {
  Env env(config("make_espresso"));
  env.reset(0);
  World& w = env.impl().world();
  const Activity& activity = *env.activity();
  const int maker = activity.object("coffee_maker.n.01_1");
  const Transition* rule = bound(w, "coffeemaker_espresso");
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->trigger, TransitionTrigger::machine);
  EXPECT_EQ(rule->places, std::vector<int>{maker});
  EXPECT_EQ(w.states().machines(), std::set<int>{maker});

  EXPECT_TRUE(contains(w, maker, "water") && contains(w, maker, "instant_coffee"));
  EXPECT_FALSE(substance_exists(w, "espresso"));
  run(w, 1);  // off: nothing happens
  EXPECT_FALSE(substance_exists(w, "espresso"));
  EXPECT_FALSE(activity.score(w).success);
  sample_state(w, "toggled_on", maker, true);
  w.step(4);
  EXPECT_TRUE(contains(w, maker, "espresso"));
  EXPECT_FALSE(contains(w, maker, "water"));
  EXPECT_FALSE(contains(w, maker, "instant_coffee"));
  EXPECT_TRUE(activity.score(w).success);
  // It runs once each time it is turned on: more coffee put in stays coffee.
  w.states().state(maker).contents["instant_coffee"] = 0.1;
  run(w, 1);
  EXPECT_TRUE(contains(w, maker, "instant_coffee"));

  // A mix no recipe takes (milk besides the two) makes sludge, and no espresso.
  env.reset(1);
  w.states().state(maker).contents["whole_milk"] = 0.1;
  const double level = w.states().state(maker).level();
  sample_state(w, "toggled_on", maker, true);
  w.step(4);
  EXPECT_EQ(w.states().state(maker).contents, (std::map<std::string, double>{{kSludge, level}}));
  EXPECT_FALSE(substance_exists(w, "espresso"));
  EXPECT_FALSE(activity.score(w).success);
}

TEST(Transitions, AStoveTurnedOnMakesSaltWaterInThePotAndCooksThenBurnsTheSteakInThePan) {
  Env env(config("make_salt_water"));
  env.reset(0);
  World& w = env.impl().world();
  const Activity& activity = *env.activity();
  const int stove = activity.object("stove.n.01_1"), pot = activity.object("stockpot.n.01_1");
  const int steak = activity.object("steak.n.01_1");
  const Transition* rule = bound(w, "salt_water");
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->trigger, TransitionTrigger::heated);
  EXPECT_EQ(rule->heat_sources, std::vector<int>{stove});
  EXPECT_EQ(rule->input_substances, (std::vector<std::string>{"salt", "water"}));

  run(w, 2);  // off
  EXPECT_FALSE(contains(w, pot, "seawater"));
  EXPECT_FALSE(cooked(w, steak));
  sample_state(w, "toggled_on", stove, true);
  w.step(4);
  EXPECT_TRUE(contains(w, pot, "seawater"));
  EXPECT_FALSE(contains(w, pot, "water") || contains(w, pot, "salt"));
  // Heat takes its time (the knowledge base's stove: 1980 C, 0.1 of the
  // difference a second): the steak cooks (63 C), then burns (OmniGibson's
  // default burn temperature, 200 C: BEHAVIOR-1K's knowledge base gives none).
  EXPECT_FALSE(cooked(w, steak));
  run(w, 0.5);
  EXPECT_TRUE(cooked(w, steak));
  EXPECT_FALSE(burnt(w, steak));
  EXPECT_TRUE(activity.score(w).success);
  run(w, 2);
  EXPECT_TRUE(burnt(w, steak));
}

TEST(Transitions, AHalfAppleIsDicedLemonadeStirredButterMeltedAndRiceCooked) {
  Env env(config("kitchen_transitions"));
  env.reset(0);
  World& w = env.impl().world();
  const Activity& activity = *env.activity();
  const int stove = activity.object("stove.n.01_1"), saucepan = activity.object("saucepan.n.01_1");
  const int butter = activity.object("butter.n.01_1"), stockpot = activity.object("stockpot.n.01_1");
  const int bowl = activity.object("bowl.n.01_1"), spoon = activity.object("wooden_spoon.n.02_1");
  const int board = activity.object("chopping_board.n.01_1"), half = activity.object("half__apple.n.01_1");
  // Bound where the activity has the inputs and names the output: the
  // uncooked half apple's dicing, not the cooked one's (no cooked diced apple here).
  for (const auto& [rule, trigger] : {std::pair{"uncooked-half__apple.n.01-dicing", TransitionTrigger::sliced},
                                      {"lemonade", TransitionTrigger::stirred},
                                      {"butter.n.01-melting", TransitionTrigger::melted},
                                      {"white_rice.n.01-cooking", TransitionTrigger::heated}}) {
    const Transition* t = bound(w, rule);
    ASSERT_NE(t, nullptr) << rule;
    EXPECT_EQ(t->trigger, trigger) << rule;
  }
  EXPECT_EQ(bound(w, "cooked-half__apple.n.01-dicing"), nullptr);
  EXPECT_EQ(bound(w, "lemonade")->tools, std::vector<int>{spoon});
  run(w, 1);  // nothing is cut, stirred or heated
  EXPECT_TRUE(w.real(half) && w.real(butter));
  EXPECT_EQ(activity.score(w).q, 0.0);

  // Dicing: the half apple cut (as the cut primitive leaves it) becomes diced
  // apple covering the board it lay on.
  w.states().state(half).sliced = true;
  w.step(4);
  EXPECT_FALSE(w.real(half));
  EXPECT_TRUE(covered(w, board, "diced__apple"));
  // Stirring: the spoon laid across the bowl of water, sugar and lemon juice.
  EXPECT_TRUE(contains(w, bowl, "lemon_juice"));
  Rng rng(0);
  ASSERT_TRUE(sample_ontop(w, spoon, bowl, rng));
  w.step(4);
  EXPECT_TRUE(touching(w, spoon, bowl));
  EXPECT_TRUE(contains(w, bowl, "lemonade"));
  EXPECT_FALSE(contains(w, bowl, "water") || contains(w, bowl, "granulated_sugar") || contains(w, bowl, "lemon_juice"));
  // The stove on: the butter in the saucepan melts (100 C), the rice in the stockpot cooks.
  sample_state(w, "toggled_on", stove, true);
  run(w, 2);
  EXPECT_FALSE(w.real(butter));
  EXPECT_TRUE(contains(w, saucepan, "melted__butter"));
  EXPECT_TRUE(contains(w, stockpot, "cooked__white_rice"));
  EXPECT_FALSE(contains(w, stockpot, "white_rice"));
  EXPECT_TRUE(activity.score(w).success);
}

// substance_watercooking: beans cook in water the stove has boiled first.
TEST(Transitions, BlackBeansCookInTheWaterTheStoveBoiled) {
  Env env(config("cook_black_beans"));
  env.reset(0);
  World& w = env.impl().world();
  const Activity& activity = *env.activity();
  const int stove = activity.object("stove.n.01_1"), pot = activity.object("stockpot.n.01_1");
  ASSERT_NE(bound(w, "water.n.06-cooking"), nullptr);
  const Transition* beans = bound(w, "black_bean.n.01-cooking");
  ASSERT_NE(beans, nullptr);
  EXPECT_EQ(beans->input_substances, (std::vector<std::string>{"black_bean", "cooked__water"}));
  run(w, 1);  // off
  EXPECT_TRUE(contains(w, pot, "water") && contains(w, pot, "black_bean"));
  sample_state(w, "toggled_on", stove, true);
  w.step(4);
  // The water boils, and the beans' rule (after the water's in the
  // knowledge base's order) takes the boiled water in the same pass.
  EXPECT_FALSE(contains(w, pot, "water"));
  EXPECT_TRUE(contains(w, pot, "cooked__black_bean"));
  EXPECT_FALSE(contains(w, pot, "black_bean") || contains(w, pot, "cooked__water"));
  EXPECT_TRUE(activity.score(w).success);
}

// OmniGibson's WasherRule with washer.json, and its DryerRule: what a washer
// that is on takes off the towel depends on what it holds.
TEST(Transitions, AWasherCleansTheTowelAsWasherJsonSaysAndSoaksItAndADryerDriesTheSock) {
  Env env(config("do_the_laundry"));
  env.reset(0);
  World& w = env.impl().world();
  const Activity& activity = *env.activity();
  const int washer = activity.object("washer.n.03_1"), dryer = activity.object("clothes_dryer.n.01_1");
  const int towel = activity.object("dishtowel.n.01_1"), sock = activity.object("sock.n.01_1");
  ASSERT_EQ(w.states().washers().size(), 2u);
  ASSERT_TRUE(inside(w, towel, washer) && inside(w, sock, dryer));
  ASSERT_TRUE(covered(w, towel, "stain") && covered(w, towel, "dust") && covered(w, towel, "rust"));
  ASSERT_TRUE(saturated(w, sock));
  run(w, 1);  // both off: nothing happens
  EXPECT_TRUE(covered(w, towel, "dust"));
  EXPECT_FALSE(saturated(w, towel));

  sample_state(w, "toggled_on", washer, true);
  w.step(4);
  // With water alone the dust comes off; the stain needs one of its
  // solvents in the washer; rust never comes off. The towel is soaked.
  EXPECT_FALSE(covered(w, towel, "dust"));
  EXPECT_TRUE(covered(w, towel, "stain"));
  EXPECT_TRUE(covered(w, towel, "rust"));
  EXPECT_TRUE(saturated(w, towel));
  EXPECT_FALSE(activity.score(w).success);
  // Detergent in the washer: the stain comes off, and the detergent goes
  // too (washer.json does not name it: OmniGibson removes it always).
  w.states().state(washer).contents["detergent"] = 0.1;
  w.step(4);
  EXPECT_FALSE(covered(w, towel, "stain"));
  EXPECT_TRUE(covered(w, towel, "rust"));
  EXPECT_FALSE(contains(w, washer, "detergent"));

  EXPECT_TRUE(saturated(w, sock));
  sample_state(w, "toggled_on", dryer, true);
  w.step(4);
  EXPECT_FALSE(saturated(w, sock));
  EXPECT_TRUE(activity.score(w).success);
}

}  // namespace
}  // namespace chore
