#include "tasks/bddl.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "test_util.hpp"

namespace chore {

// Readable gtest failure output (found by argument-dependent lookup).
static void PrintTo(const Literal& l, std::ostream* os) {
  *os << to_bddl(l);
}
static void PrintTo(const Formula& f, std::ostream* os) {
  *os << "\n" << to_bddl(f);
}
static void PrintTo(const ObjectDecl& o, std::ostream* os) {
  *os << o.name << " - " << o.type;
}
static void PrintTo(const Variable& v, std::ostream* os) {
  *os << "(" << v.name << " - " << v.type << ")";
}
static void PrintTo(const Problem& p, std::ostream* os) {
  *os << "\n" << to_bddl(p);
}

namespace {

namespace fs = std::filesystem;

std::string behavior100_dir() {
  return std::string(CHORE_TEST_DATA) + "/bddl/behavior-100";
}
std::string seed_listing(int n) {
  return test::data_path("bddl/seed_listing_" + std::to_string(n) + ".bddl");
}

// The paper's listings use two objects they never declare (see SeedListings*).
ParseOptions lenient() {
  ParseOptions o;
  o.allow_undeclared_objects = true;
  return o;
}

// Printing is canonical: the printed text parses back to the same AST and
// prints identically.
void expect_round_trip(const Problem& p, const ParseOptions& options = {}) {
  const std::string text = to_bddl(p);
  const Problem again = parse_bddl(text, "printed", options);
  EXPECT_EQ(again, p) << text;
  EXPECT_EQ(to_bddl(again), text);
}

// A small problem around a goal, for error and term tests.
std::string with_goal(const std::string& goal) {
  return "(define (problem t) (:domain omnigibson)\n"
         "(:objects apple.n.01_1 apple.n.01_2 - apple.n.01 table.n.02_1 - table.n.02)\n"
         "(:init (ontop apple.n.01_1 table.n.02_1))\n"
         "(:goal " +
         goal + "))";
}

Literal lit(std::string predicate, std::vector<std::string> args, bool negated = false) {
  return Literal{std::move(predicate), std::move(args), negated};
}

Formula atom(std::string predicate, std::vector<std::string> args, bool negated = false) {
  Formula f;
  f.literal = lit(std::move(predicate), std::move(args), negated);
  return f;
}

Formula node(Op op, std::vector<Formula> children, std::vector<Variable> variables = {}, int count = 0) {
  Formula f;
  f.op = op;
  f.children = std::move(children);
  f.variables = std::move(variables);
  f.count = count;
  return f;
}

TEST(BddlCorpus, EveryBehavior100ProblemParsesAndRoundTrips) {
  // The folder holds 101 entries: 100 activity folders with a problem0.bddl
  // each, and the igibson domain file (predicate declarations, not a problem).
  std::vector<fs::path> problems;
  std::vector<std::string> other;
  for (const fs::directory_entry& e : fs::directory_iterator(behavior100_dir())) {
    if (e.is_directory())
      problems.push_back(e.path() / "problem0.bddl");
    else
      other.push_back(e.path().filename().string());
  }
  EXPECT_EQ(problems.size(), 100u);
  EXPECT_EQ(other, std::vector<std::string>{"domain_igibson.bddl"});
  for (const fs::path& path : problems) {
    SCOPED_TRACE(path.string());
    const Problem p = load_bddl(path.string());
    EXPECT_EQ(p.name, path.parent_path().filename().string() + "_0");
    EXPECT_EQ(p.domain, Domain::igibson);
    EXPECT_FALSE(p.objects.empty());
    EXPECT_FALSE(p.init.empty());
    expect_round_trip(p);
  }
}

TEST(BddlCorpus, AssemblingGiftBasketsHasItsKnownContent) {
  const Problem p = load_bddl(behavior100_dir() + "/assembling_gift_baskets/problem0.bddl");
  EXPECT_EQ(p.name, "assembling_gift_baskets_0");
  // 8 object lines: 4 baskets, a floor, 4 candles, cookies, cheeses, bows, 2 tables, the agent.
  ASSERT_EQ(p.objects.size(), 24u);
  EXPECT_EQ(p.objects[0], (ObjectDecl{"basket.n.01_1", "basket.n.01"}));
  EXPECT_EQ(p.objects[4], (ObjectDecl{"floor.n.01_1", "floor.n.01"}));
  EXPECT_EQ(p.objects.back(), (ObjectDecl{"agent.n.01_1", "agent.n.01"}));
  ASSERT_EQ(p.init.size(), 24u);
  EXPECT_EQ(p.init.front(), lit("onfloor", {"basket.n.01_1", "floor.n.01_1"}));
  EXPECT_EQ(p.init[20], lit("inroom", {"floor.n.01_1", "living_room"}));
  ASSERT_EQ(p.goal.op, Op::conjunction);
  ASSERT_EQ(p.goal.children.size(), 4u);
  const Formula expected = node(Op::forpairs, {atom("inside", {"?candle.n.01", "?basket.n.01"})},
                                {{"?basket.n.01", "basket.n.01"}, {"?candle.n.01", "candle.n.01"}});
  EXPECT_EQ(p.goal.children[0], expected);
}

TEST(BddlCorpus, BottlingFruitKeepsNegatedInitAndResolvesGoalConstants) {
  const Problem p = load_bddl(behavior100_dir() + "/bottling_fruit/problem0.bddl");
  EXPECT_EQ(p.init[2], lit("sliced", {"strawberry.n.01_1"}, true));
  ASSERT_EQ(p.goal.children.size(), 5u);
  // `?strawberry.n.01_1` names the declared object; `?jar.n.01` stays a variable.
  const Formula& exists = p.goal.children[0];
  EXPECT_EQ(exists.op, Op::exists);
  EXPECT_EQ(exists.children[0].children[0], atom("inside", {"strawberry.n.01_1", "?jar.n.01"}));
  EXPECT_EQ(exists.children[0].children[1], atom("inside", {"peach.n.03_1", "?jar.n.01"}, true));
  // The file also writes goal constants bare: (sliced strawberry.n.01_1).
  EXPECT_EQ(p.goal.children[3], atom("sliced", {"strawberry.n.01_1"}));
}

TEST(BddlCorpus, ForNReadsItsCount) {
  const Problem p = load_bddl(behavior100_dir() + "/setting_up_candles/problem0.bddl");
  std::vector<int> counts;
  const std::function<void(const Formula&)> visit = [&](const Formula& f) {
    if (f.op == Op::forn) counts.push_back(f.count);
    for (const Formula& c : f.children) visit(c);
  };
  visit(p.goal);
  EXPECT_EQ(counts, (std::vector<int>{3, 3}));
}

TEST(BddlSeedListings, AllFiveParseAndRoundTrip) {
  const std::vector<std::string> names = {"making_scones_1", "clean_your_laundry_room_1", "fixing_mailbox_1",
                                          "packing_lunches_1", "serving_hors_d_oeuvres_1"};
  for (int n = 1; n <= 5; ++n) {
    SCOPED_TRACE(n);
    const Problem p = load_bddl(seed_listing(n), lenient());
    EXPECT_EQ(p.name, names[n - 1]);
    EXPECT_EQ(p.domain, n <= 3 ? Domain::omnigibson : Domain::igibson);
    expect_round_trip(p, lenient());
  }
}

TEST(BddlSeedListings, OmniGibsonContentIsKept) {
  const Problem scones = load_bddl(seed_listing(1), lenient());
  // A declaration split over three lines, and the listing's typo in a type.
  EXPECT_EQ(scones.objects[13], (ObjectDecl{"scone.n.01_1", "scone.n.01"}));
  EXPECT_EQ(scones.objects[18], (ObjectDecl{"scone.n.01_6", "scone.n.01"}));
  EXPECT_EQ(scones.objects[1], (ObjectDecl{"sack.n.01_1", "sack.n.n01"}));
  EXPECT_EQ(scones.init[0], lit("filled", {"flour.n.01_1", "sack.n.01_1"}));
  EXPECT_EQ(scones.init[16], lit("future", {"scone.n.01_1"}));

  const Problem laundry = load_bddl(seed_listing(2), lenient());
  EXPECT_EQ(laundry.objects[2], (ObjectDecl{"water.n.06_1", "water.n.06"}));
  EXPECT_EQ(laundry.init[1], lit("covered", {"water.n.06_1", "rag.n.01_1"}, true));
  EXPECT_EQ(laundry.goal.children[0], atom("filled", {"vinegar.n.01_1", "washer.n.03_1"}));

  // for_n_pairs is the paper's spelling of fornpairs; the count is (1).
  const Problem lunch = load_bddl(seed_listing(4), lenient());
  const Formula& pairs = lunch.goal.children[0];
  EXPECT_EQ(pairs.op, Op::fornpairs);
  EXPECT_EQ(pairs.count, 1);
  EXPECT_EQ(pairs.variables[0], (Variable{"?hamburger.n.01", "hamburger.n.01"}));
  EXPECT_NE(to_bddl(lunch).find("(fornpairs\n"), std::string::npos);
}

TEST(BddlSeedListings, StrictParsingNamesTheUndeclaredObjects) {
  EXPECT_EQ(test::error_of([] { load_bddl(seed_listing(1)); }),
            seed_listing(1) + ":57:13: expected an object declared in :objects got 'oven.n.01_1'");
  EXPECT_EQ(test::error_of([] { load_bddl(seed_listing(2)); }),
            seed_listing(2) + ":26:26: expected an object declared in :objects got 'bottle.n.01_1'");
  EXPECT_NO_THROW(load_bddl(seed_listing(3)));
}

TEST(BddlPrinter, CanonicalTextIsStable) {
  const Problem p = parse_bddl(
      "(define (problem p_0) (:domain omnigibson) ; comment\n"
      "(:objects a.n.01_1 a.n.01_2 - a.n.01 b.n.01_1 - b.n.01 a.n.01_3 - a.n.01)\n"
      "(:init (ontop a.n.01_1 b.n.01_1) (not (open b.n.01_1)) (inroom b.n.01_1 kitchen))\n"
      "(:goal (and (forn (2) (?a.n.01 - a.n.01) (inside ?a.n.01 ?b.n.01_1)) (not (open b.n.01_1)))))",
      "inline");
  EXPECT_EQ(to_bddl(p),
            "(define (problem p_0)\n"
            "    (:domain omnigibson)\n"
            "\n"
            "    (:objects\n"
            "        a.n.01_1 a.n.01_2 - a.n.01\n"
            "        b.n.01_1 - b.n.01\n"
            "        a.n.01_3 - a.n.01\n"
            "    )\n"
            "\n"
            "    (:init\n"
            "        (ontop a.n.01_1 b.n.01_1)\n"
            "        (not (open b.n.01_1))\n"
            "        (inroom b.n.01_1 kitchen)\n"
            "    )\n"
            "\n"
            "    (:goal\n"
            "        (and\n"
            "            (forn\n"
            "                (2)\n"
            "                (?a.n.01 - a.n.01)\n"
            "                (inside ?a.n.01 b.n.01_1)\n"
            "            )\n"
            "            (not (open b.n.01_1))\n"
            "        )\n"
            "    )\n"
            ")\n");
}

TEST(BddlParser, CommentsAndLayoutDoNotMatter) {
  const Problem a = parse_bddl(with_goal("(cooked apple.n.01_1)"), "a");
  const Problem b = parse_bddl(
      "; header\n(define\n(problem t)(:domain omnigibson)(:objects apple.n.01_1\tapple.n.01_2 - ; x\n"
      " apple.n.01\ntable.n.02_1 - table.n.02)(:init(ontop apple.n.01_1 table.n.02_1))(:goal(cooked "
      "?apple.n.01_1)));; end",
      "b");
  EXPECT_EQ(a, b);
}

TEST(BddlParser, GoalOperatorsBuildTheirNodes) {
  const Problem p =
      parse_bddl(with_goal("(and (or (cooked apple.n.01_1) (not (not (cooked apple.n.01_2)))) "
                           "(imply (cooked apple.n.01_1) (not (ontop apple.n.01_1 table.n.02_1))) "
                           "(not (and (cooked apple.n.01_1))) "
                           "(fornpairs (1) (?a - apple.n.01) (?t - table.n.02) (mixed ?a ?t apple.n.01_2)))"),
                 "inline");
  const Formula expected = node(
      Op::conjunction,
      {node(Op::disjunction, {atom("cooked", {"apple.n.01_1"}), atom("cooked", {"apple.n.01_2"})}),
       node(Op::implication, {atom("cooked", {"apple.n.01_1"}), atom("ontop", {"apple.n.01_1", "table.n.02_1"}, true)}),
       node(Op::negation, {node(Op::conjunction, {atom("cooked", {"apple.n.01_1"})})}),
       node(Op::fornpairs, {atom("mixed", {"?a", "?t", "apple.n.01_2"})}, {{"?a", "apple.n.01"}, {"?t", "table.n.02"}},
            1)});
  EXPECT_EQ(p.goal, expected);
  expect_round_trip(p);
}

TEST(BddlParser, QuantifiersBindEachVariableOnce) {
  const Problem p =
      parse_bddl(with_goal("(forall (?x - apple.n.01) (exists (?y - table.n.02) (ontop ?x ?y)))"), "inline");
  EXPECT_EQ(p.goal.children[0].children[0], atom("ontop", {"?x", "?y"}));
  // An inner quantifier may bind a name an outer one binds: inside, the name
  // is the inner variable (as in BEHAVIOR, whose clean_snap_peas does it).
  const Problem shadowed =
      parse_bddl(with_goal("(forall (?x - apple.n.01) (exists (?x - table.n.02) (cooked ?x)))"), "shadowed");
  EXPECT_EQ(shadowed.goal.children[0].variables[0], (Variable{"?x", "table.n.02"}));
  EXPECT_EQ(shadowed.goal.children[0].children[0], atom("cooked", {"?x"}));
}

// Where BEHAVIOR's own parser is lenient, so is chore's: several formulas in
// :goal are their conjunction, a name repeated before its type is one object,
// and atoms between sections are skipped (BEHAVIOR-1K's loading_the_car,
// passing_out_drinks and wash_a_baseball_cap).
TEST(BddlParser, AcceptsWhatBehaviorsParserAccepts) {
  const Problem p = parse_bddl(
      "(define (problem p) (:domain omnigibson)\n"
      "  (:objects a.n.01_1 a.n.01_1 a.n.01_2 - apple.n.01 t.n.01_1 - table.n.02)\n"
      "  (:init (ontop a.n.01_1 t.n.01_1))\\\n"
      "  (:goal (cooked ?a.n.01_1) (not (cooked ?a.n.01_2))))",
      "lenient");
  EXPECT_EQ(p.objects, (std::vector<ObjectDecl>{
                           {"a.n.01_1", "apple.n.01"}, {"a.n.01_2", "apple.n.01"}, {"t.n.01_1", "table.n.02"}}));
  const Problem conjunction = parse_bddl(
      "(define (problem p) (:domain omnigibson) (:objects a.n.01_1 a.n.01_2 - apple.n.01 t.n.01_1 - table.n.02) "
      "(:init (ontop a.n.01_1 t.n.01_1)) (:goal (and (cooked ?a.n.01_1) (not (cooked ?a.n.01_2)))))",
      "conjunction");
  EXPECT_EQ(p, conjunction);
  // Repeated with another type, or after its type, a name is still an error.
  EXPECT_NE(test::error_of([] {
              parse_bddl(
                  "(define (problem p) (:domain omnigibson) (:objects a.n.01_1 - apple.n.01 a.n.01_1 - "
                  "apple.n.01) (:init) (:goal (cooked ?a.n.01_1)))",
                  "again");
            }).find("again:1:74: expected an object name not declared before got 'a.n.01_1'"),
            std::string::npos);
}

struct BadInput {
  std::string input;  // a goal, a whole text or a file name
  std::string error;  // after the file name and ':'
};

TEST(BddlParser, MalformedGoalsNameWhatAndWhere) {
  // Line 4 is the goal line; its text starts at column 8, after "(:goal ".
  const std::vector<BadInput> cases = {
      {"(fooall (?x - apple.n.01) (cooked ?x))", "4:16: expected a term got '(?x'"},
      {"(forn 2 (?x - apple.n.01) (cooked ?x))", "4:14: expected a count such as (2) got '2'"},
      {"(forn (0) (?x - apple.n.01) (cooked ?x))", "4:15: expected a count from 1 to 1000000 got '0'"},
      {"(forall (?x - apple.n.01))", "4:33: expected a formula got ')'"},
      {"(forall (?x -) (cooked ?x))", "4:21: expected a type got ')'"},
      {"(forall (x - apple.n.01) (cooked x))", "4:17: expected a variable such as ?x got 'x'"},
      {"(forall (?x - apple.n.01) (cooked ?x) (cooked ?x))", "4:46: expected ')' got '(cooked'"},
      {"(not (cooked apple.n.01_1) (cooked apple.n.01_2))", "4:35: expected ')' got '(cooked'"},
      {"(imply (cooked apple.n.01_1))", "4:36: expected a consequent formula got ')'"},
      {"(cooked pear.n.01_1)", "4:16: expected an object declared in :objects got 'pear.n.01_1'"},
      {"(?x apple.n.01_1)", "4:9: expected a predicate name got '?x'"},
      {"cooked", "4:8: expected a formula got 'cooked'"},
      {"()", "4:8: expected a formula got '('"},
  };
  for (const BadInput& c : cases)
    EXPECT_EQ(test::error_of([&] { parse_bddl(with_goal(c.input), "f"); }), "f:" + c.error) << c.input;
}

TEST(BddlParser, MalformedStructureNamesWhatAndWhere) {
  const std::vector<BadInput> cases = {
      {"", "1:1: expected '(define' got end of file"},
      {")", "1:1: expected '(define' got ')'"},
      {"(define (problem p) (:domain igibson) (:objects) (:init) (:goal (and))))",
       "1:72: expected end of file got ')'"},
      {"(define (problem p) (:domain bullet) (:objects) (:init) (:goal (and)))",
       "1:30: expected igibson or omnigibson got 'bullet'"},
      {"(define (problem p) (:domain igibson) (:init) (:goal (and)))", "1:39: expected (:objects ...) got '(:init'"},
      {"(define (problem p) (:domain igibson) (:objects a b) (:init) (:goal (and)))",
       "1:52: expected '- TYPE' after 'b' got ')'"},
      {"(define (problem p) (:domain igibson) (:objects a - t a - t) (:init) (:goal (and)))",
       "1:55: expected an object name not declared before got 'a' (declared at 1:49)"},
      {"(define (problem p) (:domain igibson) (:objects - t) (:init) (:goal (and)))",
       "1:49: expected an object name got '-'"},
      {"(define (problem p) (:domain igibson) (:objects a - t) (:init (and (open a))) (:goal (and)))",
       "1:64: expected a predicate name got 'and'"},
      {"(define (problem p) (:domain igibson) (:objects a - t) (:init (open ?b)) (:goal (and)))",
       "1:69: expected a variable bound by an enclosing quantifier or a declared object got '?b'"},
  };
  for (const BadInput& c : cases)
    EXPECT_EQ(test::error_of([&] { parse_bddl(c.input, "f"); }), "f:" + c.error) << c.input;
}

TEST(BddlParser, MalformedFilesNameWhatAndWhere) {
  const std::vector<BadInput> cases = {
      {"error_unbalanced.bddl", "3:1: expected ')' closing this '(' got end of file"},
      {"error_undeclared_object.bddl", "8:29: expected an object declared in :objects got 'table.n.02_1'"},
      {"error_undeclared_variable.bddl",
       "13:23: expected a variable bound by an enclosing quantifier or a declared object got '?y'"},
      {"error_bad_quantifier.bddl", "11:21: expected '-' got 'apple.n.01'"},
      {"error_missing_goal.bddl", "10:1: expected (:goal ...) got ')'"},
  };
  for (const BadInput& c : cases) {
    const std::string path = test::data_path("bddl/" + c.input);
    EXPECT_EQ(test::error_of([&] { load_bddl(path); }), path + ":" + c.error);
  }
  EXPECT_EQ(test::error_of([] { load_bddl("/nonexistent/problem0.bddl"); }),
            "/nonexistent/problem0.bddl: no such file; expected a BDDL file");
}

TEST(BddlParser, RoomsInInroomAreNotObjects) {
  const Problem p = parse_bddl(with_goal("(inroom apple.n.01_1 garden)"), "inline");
  EXPECT_EQ(p.goal, atom("inroom", {"apple.n.01_1", "garden"}));
  EXPECT_EQ(test::error_of([] { parse_bddl(with_goal("(inroom garden apple.n.01_1)"), "f"); }),
            "f:4:16: expected an object declared in :objects got 'garden'");
}

// With a vocabulary, what the grammar allows but the domain, the room types
// or the knowledge base do not is an error where it is written.
TEST(BddlParser, AVocabularyChecksPredicatesArityRoomsAndSynsetsWhereWritten) {
  Vocabulary v;
  v.omnigibson = parse_domain(
      "(define (domain d) (:requirements :strips) (:predicates (ontop ?a ?b) (cooked ?a) "
      "(inroom ?a ?r) (grasped ?a - agent ?b - object)))",
      "d.bddl");
  EXPECT_EQ(v.omnigibson, (Predicates{{"ontop", 2}, {"cooked", 1}, {"inroom", 2}, {"grasped", 2}}));
  v.room_types = {"kitchen", "garden"};
  v.unknown_synset = [](Domain, const std::string& s) {
    return s == "apple.n.01" || s == "table.n.02" ? "" : "unknown synset '" + s + "'";
  };
  const ParseOptions checked{.vocabulary = &v};
  const auto error = [&](const std::string& goal) {
    return test::error_of([&] { parse_bddl(with_goal(goal), "f", checked); });
  };
  EXPECT_NO_THROW(parse_bddl(with_goal("(and (cooked apple.n.01_1) (inroom table.n.02_1 kitchen_0))"), "f", checked));
  EXPECT_EQ(error("(toasted apple.n.01_1)"), "f:4:9: expected a predicate of the domain got 'toasted'");
  EXPECT_EQ(error("(ontop apple.n.01_1)"), "f:4:8: expected 2 argument(s) to 'ontop' got 1");
  EXPECT_EQ(error("(inroom table.n.02_1 kichen)"),
            "f:4:29: expected a room type (or a room named TYPE_N) got 'kichen'");
  EXPECT_EQ(error("(forall (?p - pear.n.01) (cooked ?p))"), "f:4:22: unknown synset 'pear.n.01'");
  EXPECT_EQ(test::error_of([&] {
              parse_bddl(
                  "(define (problem t) (:domain omnigibson) (:objects b - bowl.n.01) (:init) (:goal (cooked b)))", "g",
                  checked);
            }),
            "g:1:56: unknown synset 'bowl.n.01'");
  // Without one, only the grammar.
  EXPECT_NO_THROW(parse_bddl(with_goal("(toasted apple.n.01_1)"), "f"));
  EXPECT_EQ(test::error_of([] { parse_domain("(define (domain d))", "d.bddl"); }),
            "d.bddl:1:19: expected (:predicates ...) got ')'");
}

TEST(BddlParser, DeepNestingIsRefusedNotOverflowed) {
  std::string goal = "(cooked apple.n.01_1)";
  for (int i = 0; i < 200; ++i) goal = "(and " + goal + ")";
  // define and :goal hold the first two levels; the 99th (and is the 101st.
  EXPECT_EQ(test::error_of([&] { parse_bddl(with_goal(goal), "f"); }),
            "f:4:" + std::to_string(8 + 5 * 98) + ": expected at most 100 nested lists got '('");
}

TEST(BddlNnf, DeMorganPushesNegationsToLiterals) {
  const Formula a = atom("p", {"a"}), b = atom("p", {"b"}), c = atom("p", {"c"});
  const Formula na = atom("p", {"a"}, true), nb = atom("p", {"b"}, true), nc = atom("p", {"c"}, true);
  // not (a and (b or not c)) = (not a) or ((not b) and c)
  EXPECT_EQ(to_nnf(node(Op::negation, {node(Op::conjunction, {a, node(Op::disjunction, {b, nc})})})),
            node(Op::disjunction, {na, node(Op::conjunction, {nb, c})}));
  // imply(a, b) = (not a) or b; not imply(a, b) = a and not b.
  EXPECT_EQ(to_nnf(node(Op::implication, {a, b})), node(Op::disjunction, {na, b}));
  EXPECT_EQ(to_nnf(node(Op::negation, {node(Op::implication, {a, b})})), node(Op::conjunction, {a, nb}));
  // not forall = exists not; not exists = forall not.
  const std::vector<Variable> x = {{"?x", "t"}};
  const Formula px = atom("p", {"?x"}), npx = atom("p", {"?x"}, true);
  EXPECT_EQ(to_nnf(node(Op::negation, {node(Op::forall, {px}, x)})), node(Op::exists, {npx}, x));
  EXPECT_EQ(to_nnf(node(Op::negation, {node(Op::exists, {px}, x)})), node(Op::forall, {npx}, x));
  // Double negation cancels; a negated literal stays a literal with the flag.
  EXPECT_EQ(to_nnf(node(Op::negation, {node(Op::negation, {na})})), na);
  // A counting quantifier keeps its negation node; its body is still normalised.
  const Formula forn = node(Op::forn, {node(Op::negation, {node(Op::disjunction, {px})})}, x, 2);
  EXPECT_EQ(to_nnf(node(Op::negation, {forn})),
            node(Op::negation, {node(Op::forn, {node(Op::conjunction, {npx})}, x, 2)}));
}

TEST(BddlNnf, ParsedNegatedThreeValuedPredicateIsTheFlaggedLiteral) {
  const Problem p = parse_bddl(with_goal("(not (open apple.n.01_1))"), "inline");
  EXPECT_EQ(p.goal, atom("open", {"apple.n.01_1"}, true));
  EXPECT_EQ(to_nnf(p.goal), p.goal);
  EXPECT_EQ(to_bddl(p.goal), "(not (open apple.n.01_1))");
}

}  // namespace
}  // namespace chore
