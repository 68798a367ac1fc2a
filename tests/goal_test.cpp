#include "tasks/goal.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "tasks/bddl.hpp"
#include "test_util.hpp"

namespace chore {
namespace {

using Texts = std::vector<std::vector<std::string>>;

// A problem over `objects` ("a1 a2 - apple b - basket") with this goal, in
// the omnigibson dialect (grounded as bddl 3 does) unless `domain` says igibson
// (bddl 1). The expected options below are what bddl 3.6.0 and 1.0.1 give.
Problem problem(const std::string& objects, const std::string& goal, const std::string& domain = "omnigibson") {
  return parse_bddl("(define (problem g) (:domain " + domain + ") (:objects " + objects + ") (:init) (:goal " + goal +
                        "))",
                    "goal_test");
}

// A world given by the positive literals that hold, e.g. {"(p a)"}; a negated
// literal holds where its positive one does not.
Truth world(std::set<std::string> facts) {
  return [facts = std::move(facts)](const GroundLiteral& l) {
    GroundLiteral positive = l;
    positive.negated = false;
    return facts.contains(to_bddl(positive)) != l.negated;
  };
}

Texts texts(const GroundGoal& g, const std::vector<GroundOption>& options) {
  Texts out;
  for (const GroundOption& o : options) {
    std::vector<std::string>& t = out.emplace_back();
    for (LiteralId id : o) t.push_back(to_bddl(g.literals[id]));
  }
  return out;
}

TEST(GoalConnectives, AndOrNotImplyFollowTheirTruthTables) {
  const GroundGoal g =
      ground_goal(problem("x y z - t", "(and (or (p x) (p y)) (imply (p y) (p z)) (not (and (p x) (p z))))"));
  ASSERT_EQ(g.conditions.size(), 3u);
  for (int bits = 0; bits < 8; ++bits) {
    const bool x = bits & 1, y = bits & 2, z = bits & 4;
    std::set<std::string> facts;
    if (x) facts.insert("(p x)");
    if (y) facts.insert("(p y)");
    if (z) facts.insert("(p z)");
    const Score s = score(g, world(facts));
    SCOPED_TRACE(bits);
    EXPECT_EQ(s.condition_holds, (std::vector<bool>{x || y, !y || z, !(x && z)}));
    EXPECT_EQ(s.success, (x || y) && (!y || z) && !(x && z));
    // These options are the goal's exact disjunctive form: Q reaches 1 exactly on success.
    EXPECT_EQ(s.q == 1.0, s.success);
  }
}

// An inner variable shadows an outer one of the same name (BEHAVIOR binds the
// innermost first): the outer forall repeats the inner one's conditions, and
// the option keeps the repeat, as bddl's does (its Q counts it twice).
TEST(GoalConnectives, AnInnerVariableShadowsAnOuterOne) {
  const GroundGoal g =
      ground_goal(problem("a1 a2 - apple b - basket", "(forall (?x - apple) (forall (?x - basket) (p ?x)))"));
  EXPECT_EQ(texts(g, g.options), (Texts{{"(p b)", "(p b)"}}));
}

TEST(GoalConnectives, OptionsAreTheProductWithoutContradictions) {
  const GroundGoal g = ground_goal(problem("x z - t", "(and (or (p x) (q x)) (not (and (p x) (p z))))"));
  EXPECT_EQ(texts(g, g.conditions[0].options), (Texts{{"(p x)"}, {"(q x)"}}));
  EXPECT_EQ(texts(g, g.conditions[1].options), (Texts{{"(not (p x))"}, {"(not (p z))"}}));
  // (p x) with (not (p x)) is dropped.
  EXPECT_EQ(texts(g, g.options), (Texts{{"(p x)", "(not (p z))"}, {"(q x)", "(not (p x))"}, {"(q x)", "(not (p z))"}}));
}

TEST(GoalConnectives, ProductsFollowTheDialectsBddl) {
  // bddl 1 (igibson): complete and lexicographic (itertools.product).
  const std::string goal = "(and (or (p a) (p b)) (or (q a) (q b)) (or (r a) (r b)))";
  const GroundGoal one = ground_goal(problem("a b - t", goal, "igibson"));
  const Texts t1 = texts(one, one.options);
  ASSERT_EQ(t1.size(), 8u);
  EXPECT_EQ(t1[0], (std::vector<std::string>{"(p a)", "(q a)", "(r a)"}));
  EXPECT_EQ(t1[3], (std::vector<std::string>{"(p a)", "(q b)", "(r b)"}));
  EXPECT_EQ(t1[4], (std::vector<std::string>{"(p b)", "(q a)", "(r a)"}));
  // bddl 3 (omnigibson): truncated_product's order, by index sum.
  const GroundGoal three = ground_goal(problem("a b - t", goal));
  const Texts t3 = texts(three, three.options);
  ASSERT_EQ(t3.size(), 8u);
  EXPECT_EQ(t3[3], (std::vector<std::string>{"(p b)", "(q a)", "(r a)"}));
  EXPECT_EQ(t3[4], (std::vector<std::string>{"(p a)", "(q b)", "(r b)"}));
}

TEST(GoalConnectives, Bddl3CountsTheTuplesItSkipsTowardItsCap) {
  // Six conditions, one with four options: truncated_product counts the
  // tuples with an index past a sequence's end, so bddl 3 reaches 2 options
  // (cleaning_bedroom's goal has this shape); bddl 1 has all 4.
  const std::string goal =
      "(and (forall (?x - t) (exists (?y - u) (inside ?x ?y))) (p c) (p d) (p e) (p f) (p g))";
  const std::string objects = "a b - t c d e f g - v k l - u";
  EXPECT_EQ(ground_goal(problem(objects, goal)).options.size(), 2u);
  EXPECT_EQ(ground_goal(problem(objects, goal, "igibson")).options.size(), 4u);
}

TEST(GoalConnectives, AContradictoryGoalHasNoOptionAndNoScore) {
  const GroundGoal g = ground_goal(problem("x - t", "(and (p x) (not (p x)))"));
  EXPECT_TRUE(g.options.empty());
  for (const std::set<std::string>& facts : {std::set<std::string>{}, std::set<std::string>{"(p x)"}}) {
    const Score s = score(g, world(facts));
    EXPECT_FALSE(s.success);
    EXPECT_EQ(s.q, 0.0);
    EXPECT_FALSE(s.best_option.has_value());
  }
}

TEST(GoalConnectives, DeMorganOnNegatedAndAndForall) {
  const GroundGoal nand = ground_goal(problem("a b - t", "(not (and (p a) (p b)))"));
  EXPECT_EQ(texts(nand, nand.options), (Texts{{"(not (p a))"}, {"(not (p b))"}}));
  EXPECT_TRUE(score(nand, world({"(p a)"})).success);
  EXPECT_FALSE(score(nand, world({"(p a)", "(p b)"})).success);

  const GroundGoal nforall = ground_goal(problem("a b c - t", "(not (forall (?x - t) (p ?x)))"));
  EXPECT_EQ(texts(nforall, nforall.options), (Texts{{"(not (p a))"}, {"(not (p b))"}, {"(not (p c))"}}));
  EXPECT_TRUE(score(nforall, world({"(p a)", "(p c)"})).success);
  EXPECT_FALSE(score(nforall, world({"(p a)", "(p b)", "(p c)"})).success);
}

TEST(GoalConnectives, NegatedForNTakesOneComplementFromEachOption) {
  const GroundGoal g = ground_goal(problem("a b - t", "(not (forn (1) (?x - t) (p ?x)))"));
  ASSERT_EQ(g.conditions[0].formula.op, Op::negation);
  EXPECT_EQ(texts(g, g.options), (Texts{{"(not (p a))", "(not (p b))"}}));
  EXPECT_TRUE(score(g, world({})).success);
  EXPECT_FALSE(score(g, world({"(p b)"})).success);
  EXPECT_TRUE(score(g, world({"(p a)", "(p b)"})).success);  // two is not exactly one
}

TEST(GoalQuantifiers, ForallOverThreeObjects) {
  const GroundGoal g = ground_goal(problem("a1 a2 a3 - apple b - basket", "(forall (?a - apple) (inside ?a b))"));
  EXPECT_EQ(texts(g, g.options), (Texts{{"(inside a1 b)", "(inside a2 b)", "(inside a3 b)"}}));
  const Score two = score(g, world({"(inside a1 b)", "(inside a3 b)"}));
  EXPECT_FALSE(two.success);
  EXPECT_DOUBLE_EQ(two.q, 2.0 / 3.0);
  EXPECT_EQ(two.satisfied, 2u);
  EXPECT_EQ(two.total, 3u);
  EXPECT_TRUE(score(g, world({"(inside a1 b)", "(inside a2 b)", "(inside a3 b)"})).success);
}

TEST(GoalQuantifiers, ExistsIsTheUnionOfItsBindings) {
  const GroundGoal g = ground_goal(problem("a1 a2 a3 - apple b - basket", "(exists (?a - apple) (inside ?a b))"));
  EXPECT_EQ(texts(g, g.options), (Texts{{"(inside a1 b)"}, {"(inside a2 b)"}, {"(inside a3 b)"}}));
  const Score none = score(g, world({}));
  EXPECT_FALSE(none.success);
  EXPECT_EQ(none.q, 0.0);
  const Score one = score(g, world({"(inside a2 b)"}));
  EXPECT_TRUE(one.success);
  EXPECT_EQ(one.q, 1.0);
  EXPECT_EQ(one.best_option, 1u);
}

TEST(GoalQuantifiers, NestedQuantifiersBindTheirOwnVariables) {
  const GroundGoal g = ground_goal(
      problem("a1 a2 - apple b1 b2 - basket", "(forall (?a - apple) (exists (?b - basket) (inside ?a ?b)))"));
  EXPECT_TRUE(score(g, world({"(inside a1 b2)", "(inside a2 b1)"})).success);
  EXPECT_FALSE(score(g, world({"(inside a1 b2)", "(inside a1 b1)"})).success);
  EXPECT_EQ(g.options.size(), 4u);  // 2 x 2 choices of basket
}

TEST(GoalQuantifiers, ForNMeansExactlyNWhileQCountsTheChosenN) {
  const GroundGoal g = ground_goal(problem("a1 a2 a3 - apple b - basket", "(forn (2) (?a - apple) (inside ?a b))"));
  EXPECT_EQ(texts(g, g.options), (Texts{{"(inside a1 b)", "(inside a2 b)"},
                                        {"(inside a1 b)", "(inside a3 b)"},
                                        {"(inside a2 b)", "(inside a3 b)"}}));
  const Score two = score(g, world({"(inside a1 b)", "(inside a3 b)"}));
  EXPECT_TRUE(two.success);
  EXPECT_EQ(two.q, 1.0);
  EXPECT_EQ(two.best_option, 1u);
  // Three is not exactly two: failure, though an option is fully satisfied.
  const Score three = score(g, world({"(inside a1 b)", "(inside a2 b)", "(inside a3 b)"}));
  EXPECT_FALSE(three.success);
  EXPECT_EQ(three.q, 1.0);
  const Score one = score(g, world({"(inside a2 b)"}));
  EXPECT_FALSE(one.success);
  EXPECT_EQ(one.q, 0.5);
}

TEST(GoalQuantifiers, ForPairsTwoByTwoNeedsBothRowsAndBothColumns) {
  const GroundGoal g =
      ground_goal(problem("a1 a2 - apple b1 b2 - basket", "(forpairs (?a - apple) (?b - basket) (inside ?a ?b))"));
  EXPECT_EQ(texts(g, g.options), (Texts{{"(inside a1 b1)", "(inside a2 b2)"}, {"(inside a2 b1)", "(inside a1 b2)"}}));
  const Score one_column = score(g, world({"(inside a1 b1)", "(inside a2 b1)"}));
  EXPECT_FALSE(one_column.success);
  EXPECT_EQ(one_column.q, 0.5);
  const Score crossed = score(g, world({"(inside a1 b2)", "(inside a2 b1)"}));
  EXPECT_TRUE(crossed.success);
  EXPECT_EQ(crossed.best_option, 1u);
}

TEST(GoalQuantifiers, ForPairsTwoByThreeNeedsTwoRowsAndTwoColumns) {
  const GroundGoal g =
      ground_goal(problem("a1 a2 - apple b1 b2 b3 - basket", "(forpairs (?a - apple) (?b - basket) (inside ?a ?b))"));
  // L = min(2, 3) = 2: every injection of the two apples into the three baskets.
  EXPECT_EQ(texts(g, g.options), (Texts{{"(inside a1 b1)", "(inside a2 b2)"},
                                        {"(inside a1 b1)", "(inside a2 b3)"},
                                        {"(inside a1 b2)", "(inside a2 b1)"},
                                        {"(inside a1 b2)", "(inside a2 b3)"},
                                        {"(inside a1 b3)", "(inside a2 b1)"},
                                        {"(inside a1 b3)", "(inside a2 b2)"}}));
  EXPECT_FALSE(score(g, world({"(inside a1 b1)", "(inside a2 b1)"})).success);
  EXPECT_TRUE(score(g, world({"(inside a1 b1)", "(inside a2 b3)"})).success);
  EXPECT_FALSE(score(g, world({"(inside a1 b1)", "(inside a1 b3)"})).success);  // one row

  // Three by two: the longer side is now the rows.
  const GroundGoal t =
      ground_goal(problem("a1 a2 a3 - apple b1 b2 - basket", "(forpairs (?a - apple) (?b - basket) (inside ?a ?b))"));
  ASSERT_EQ(t.options.size(), 6u);
  EXPECT_EQ(texts(t, t.options)[1], (std::vector<std::string>{"(inside a1 b1)", "(inside a3 b2)"}));
  EXPECT_EQ(texts(t, t.options)[2], (std::vector<std::string>{"(inside a2 b1)", "(inside a1 b2)"}));
}

TEST(GoalQuantifiers, ForPairsSucceedsWithoutAPerfectMatchingSoQCanStayBelowOne) {
  // Every row and column holds a pair, but a2 and a3 only fit b1.
  const GroundGoal g = ground_goal(
      problem("a1 a2 a3 - apple b1 b2 b3 - basket", "(forpairs (?a - apple) (?b - basket) (inside ?a ?b))"));
  EXPECT_EQ(g.options.size(), 6u);  // the 3! matchings
  const Score s = score(g, world({"(inside a1 b2)", "(inside a1 b3)", "(inside a2 b1)", "(inside a3 b1)"}));
  EXPECT_TRUE(s.success);
  EXPECT_DOUBLE_EQ(s.q, 2.0 / 3.0);
}

TEST(GoalQuantifiers, ForNPairsCountsNRowsAndNColumns) {
  // Options: the first N rows in order against permutations of the columns
  // (bddl's second permutation generator is used up by its first row choice).
  const GroundGoal one = ground_goal(
      problem("a1 a2 - apple b1 b2 b3 - basket", "(fornpairs (1) (?a - apple) (?b - basket) (inside ?a ?b))"));
  EXPECT_EQ(texts(one, one.options), (Texts{{"(inside a1 b1)"}, {"(inside a1 b2)"}, {"(inside a1 b3)"}}));
  EXPECT_FALSE(score(one, world({})).success);
  EXPECT_TRUE(score(one, world({"(inside a2 b3)"})).success);

  const GroundGoal two = ground_goal(
      problem("a1 a2 - apple b1 b2 b3 - basket", "(fornpairs (2) (?a - apple) (?b - basket) (inside ?a ?b))"));
  EXPECT_FALSE(score(two, world({"(inside a1 b1)", "(inside a2 b1)"})).success);
  EXPECT_TRUE(score(two, world({"(inside a1 b1)", "(inside a2 b2)"})).success);
}

TEST(GoalQuantifiers, APairNeverBindsOneInstanceToBothVariables) {
  const GroundGoal g = ground_goal(problem("a1 a2 - apple", "(forpairs (?x - apple) (?y - apple) (nextto ?x ?y))"));
  EXPECT_EQ(texts(g, g.options), (Texts{{"(nextto a2 a1)", "(nextto a1 a2)"}}));
  EXPECT_TRUE(score(g, world({"(nextto a1 a2)", "(nextto a2 a1)"})).success);
  EXPECT_FALSE(score(g, world({"(nextto a1 a2)"})).success);  // one row
}

TEST(GoalCaps, ForallKeepsTheFirstTwentyOptionsInIndexSumOrder) {
  std::string objects;
  for (int i = 1; i <= 25; ++i) objects += "o" + std::to_string(i) + " ";
  const GroundGoal g = ground_goal(problem(objects + "- t", "(forall (?x - t) (or (p ?x) (q ?x)))"));
  ASSERT_EQ(g.options.size(), kMaxGroundOptions);
  const Texts t = texts(g, g.options);
  EXPECT_EQ(t[0].back(), "(p o25)");
  EXPECT_EQ(t[1][23], "(p o24)");
  EXPECT_EQ(t[1][24], "(q o25)");  // index sum 1 starts with the last sequence
  EXPECT_EQ(t[2][23], "(q o24)");
  EXPECT_EQ(t[2][24], "(p o25)");
  for (const auto& option : t) EXPECT_EQ(option.size(), 25u);
  // exists is a union, never capped; the goal's product of its one condition
  // is, in bddl 3.
  EXPECT_EQ(ground_goal(problem(objects + "- t", "(exists (?x - t) (p ?x))", "igibson")).options.size(), 25u);
  EXPECT_EQ(ground_goal(problem(objects + "- t", "(exists (?x - t) (p ?x))")).options.size(), kMaxGroundOptions);
}

TEST(GoalCaps, ForPairsPermutationsAreCappedAtTen) {
  // 4 x 4: the columns in order against 10 of the 24 row permutations.
  const GroundGoal g = ground_goal(
      problem("a1 a2 a3 a4 - apple b1 b2 b3 b4 - basket", "(forpairs (?a - apple) (?b - basket) (inside ?a ?b))"));
  EXPECT_EQ(g.options.size(), 10u);
  for (const GroundOption& o : g.options) EXPECT_EQ(o.size(), 4u);
}

TEST(GoalScore, QIsTheBestFractionOverOptionsSortedByLength) {
  const GroundGoal g = ground_goal(problem("a b c - t", "(or (and (q a) (q b) (q c)) (and (p a) (p b)))"));
  EXPECT_EQ(texts(g, g.options), (Texts{{"(p a)", "(p b)"}, {"(q a)", "(q b)", "(q c)"}}));
  const Score s = score(g, world({"(q a)", "(q b)", "(p b)"}));
  EXPECT_FALSE(s.success);
  EXPECT_DOUBLE_EQ(s.q, 2.0 / 3.0);
  EXPECT_EQ(s.best_option, 1u);
  EXPECT_EQ(s.satisfied, 2u);
  EXPECT_EQ(s.total, 3u);
}

TEST(GoalScore, TruthIsAskedOncePerDistinctLiteral) {
  const GroundGoal g = ground_goal(problem("a1 a2 a3 - apple b1 b2 b3 - basket",
                                           "(and (forpairs (?a - apple) (?b - basket) (inside ?a ?b)) "
                                           "(exists (?a - apple) (inside ?a b1)))"));
  std::vector<std::string> asked;
  score(g, [&](const GroundLiteral& l) {
    asked.push_back(to_bddl(l));
    return l.args[1] == "b1";
  });
  const std::set<std::string> distinct(asked.begin(), asked.end());
  EXPECT_EQ(asked.size(), distinct.size());
  EXPECT_EQ(asked.size(), g.literals.size());
}

TEST(GoalScore, PotentialOfOptionZeroRisesAndFalls) {
  const GroundGoal g = ground_goal(problem("a1 a2 a3 - apple b - basket", "(forall (?a - apple) (inside ?a b))"));
  const double none = potential(g, 0, world({}));
  const double one = potential(g, 0, world({"(inside a2 b)"}));
  const double two = potential(g, 0, world({"(inside a2 b)", "(inside a3 b)"}));
  EXPECT_EQ(none, 0.0);
  EXPECT_DOUBLE_EQ(one, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(two, 2.0 / 3.0);
  EXPECT_GT(two - one, 0.0);  // reward for satisfying a literal
  EXPECT_LT(one - two, 0.0);  // penalty for undoing it
  EXPECT_THROW(potential(g, 1, world({})), std::out_of_range);
}

// bddl's object map: a quantifier ranges over the instances declared with its
// synset, not over those of its descendants (sorting_books quantifies over
// book.n.02 and hardback.n.01 separately).
TEST(GoalTypes, QuantifiersRangeOverTheInstancesDeclaredWithTheirSynset) {
  const Problem p = problem("fruit1 - fruit.n.01 apple1 - apple.n.01 table1 - table.n.02",
                            "(forall (?f - fruit.n.01) (cooked ?f))");
  const GroundGoal g = ground_goal(p);
  EXPECT_EQ(texts(g, g.options), (Texts{{"(cooked fruit1)"}}));
  try {
    ground_goal(problem("apple1 - apple.n.01 pear1 - pear.n.01", "(forall (?f - fruit.n.01) (cooked ?f))"));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "goal_test:1:106: (?f - fruit.n.01) ranges over no object declared in :objects");
  }
}

// Behaviour-100 activity definitions, plus the seed listings that ground.
std::vector<Problem> corpus() {
  std::vector<Problem> out;
  for (const auto& e : std::filesystem::directory_iterator(std::string(CHORE_TEST_DATA) + "/bddl/behavior-100"))
    if (e.is_directory()) out.push_back(load_bddl((e.path() / "problem0.bddl").string()));
  ParseOptions lenient;
  lenient.allow_undeclared_objects = true;
  for (int n = 1; n <= 5; ++n)
    out.push_back(load_bddl(test::data_path("bddl/seed_listing_" + std::to_string(n) + ".bddl"), lenient));
  return out;
}

// The grounding's bounds: a data-sized product is iterative, and work past
// the limits is an error naming the construct, not a hang or a crash.
TEST(GoalBounds, AForallOverManyObjectsGroundsWithoutRecursingPerObject) {
  std::string objects;
  for (int i = 0; i < 150000; ++i) objects += "o" + std::to_string(i) + " ";
  const GroundGoal g = ground_goal(problem(objects + "- t", "(forall (?x - t) (p ?x))"));
  ASSERT_EQ(g.options.size(), 1u);
  EXPECT_EQ(g.options[0].size(), 150000u);
  EXPECT_EQ(to_bddl(g.literals[g.options[0].back()]), "(p o149999)");
}

TEST(GoalBounds, OptionsThatContradictThemselvesSpendTheBudget) {
  // Every one of the 2^30 options holds (p x) and (not (p x)).
  std::string goal = "(and (p x) (not (p x))";
  for (int i = 0; i < 30; ++i) goal += " (or (q" + std::to_string(i) + " x) (r" + std::to_string(i) + " x))";
  const std::string error = test::error_of([&] { ground_goal(problem("x - t", goal + ")")); });
  EXPECT_EQ(error,
            "goal_test:1:74: grounding the goal's options takes more than 20000000 steps (option tuples "
            "visited plus literals copied), the limit");
}

TEST(GoalBounds, NestedQuantifiersBuildAtMostTheNodeLimit) {
  std::string objects;
  for (int i = 0; i < 40; ++i) objects += "o" + std::to_string(i) + " ";
  const std::string goal = "(forall (?a - t) (forall (?b - t) (forall (?c - t) (forall (?d - t) (p ?a ?b ?c ?d)))))";
  const std::string error = test::error_of([&] { ground_goal(problem(objects + "- t", goal)); });
  EXPECT_NE(error.find("goal_test:1:"), std::string::npos) << error;
  EXPECT_NE(error.find(": grounding (forall ...) takes more than 1000000 formula nodes, the limit"), std::string::npos)
      << error;
  // Under the limit (40^3 bindings) it grounds.
  const GroundGoal g =
      ground_goal(problem(objects + "- t", "(forall (?a - t) (forall (?b - t) (forall (?c - t) (p ?a ?b ?c))))"));
  EXPECT_EQ(g.literals.size(), 64000u);
}

TEST(GoalCorpus, EveryActivityGroundsAndItsFirstOptionSucceeds) {
  const std::vector<Problem> problems = corpus();
  ASSERT_EQ(problems.size(), 105u);
  for (const Problem& p : problems) {
    SCOPED_TRACE(p.name);
    const GroundGoal g = ground_goal(p);
    ASSERT_FALSE(g.options.empty());
    EXPECT_LE(g.options.size(), kMaxGoalOptions);
    for (size_t i = 1; i < g.options.size(); ++i) EXPECT_LE(g.options[i - 1].size(), g.options[i].size());
    // The world where exactly option 0's positive literals hold.
    std::set<std::string> facts;
    for (LiteralId id : g.options[0])
      if (!g.literals[id].negated) facts.insert(to_bddl(g.literals[id]));
    const Score s = score(g, world(facts));
    EXPECT_TRUE(s.success);
    EXPECT_EQ(s.q, 1.0);
    EXPECT_EQ(s.best_option, 0u);
    EXPECT_EQ(potential(g, 0, world(facts)), 1.0);
  }
}

TEST(GoalCorpus, AssemblingGiftBasketsProductIsComplete) {
  const GroundGoal g =
      ground_goal(load_bddl(std::string(CHORE_TEST_DATA) + "/bddl/behavior-100/assembling_gift_baskets/problem0.bddl"));
  ASSERT_EQ(g.conditions.size(), 4u);
  for (const GroundCondition& c : g.conditions) EXPECT_EQ(c.options.size(), 10u);
  EXPECT_EQ(g.options.size(), 10000u);  // bddl 1's complete product
  EXPECT_EQ(g.options[0].size(), 16u);
  EXPECT_EQ(g.literals.size(), 64u);
}

}  // namespace
}  // namespace chore
