// A BDDL goal grounded on an activity's objects, and scored against the world
// as BEHAVIOR's own bddl package does (condition_evaluation.py), option for
// option: bddl 1.0.1 (iGibson 2.0) for the igibson dialect of BEHAVIOR-100's
// files, bddl 3.6.0 (OmniGibson) for the omnigibson dialect of BEHAVIOR-1K's.
// python/tests/test_bddl_reference.py runs both against every corpus file.
//
// - The goal is put in negation normal form (tasks/bddl.hpp) and split into
//   top-level conditions (the operands of a top-level `and`).
// - Each condition expands its quantifiers over the instances declared in
//   :objects with the quantifier's synset (bddl's object map: not its
//   descendants), in file order. A pair quantifier never binds one instance
//   to both of its variables. A quantifier ranging over no instance is an
//   error (bddl's KeyError; a forall would otherwise hold vacuously).
// - Each condition gets ground options: lists of literals, any one of which
//   satisfies it, repeats kept (bddl's Q counts a literal each time it
//   appears). and, a negation's choices = the product of the operands'
//   options: complete (bddl 1), or the first kMaxGroundOptions tuples of
//   bddl's truncated_product (bddl 3); or, exists = union; forall = truncated
//   product; forn = the N-combinations of each truncated-product option;
//   forpairs, fornpairs = the first L instances of one side paired with
//   truncated permutations (kMaxGroundPermutations) of the other, each a
//   truncated product; a negation left over a counting quantifier = one
//   complemented literal from each option of its operand.
// - The goal's options are the product of its conditions' options (as and's,
//   per dialect), without options holding both c and (not c), sorted by
//   length (stable).
//
// Where bddl has no bound chore has one (kMaxGoalOptions, past every corpus
// file), and where bddl 3 finds no consistent option (it asserts) chore looks
// further; docs/activities.md lists the files where chore and bddl differ.
//
// Success evaluates the formula itself: forn holds when exactly N bindings
// satisfy its body; forpairs when at least L = min(rows, columns) rows and L
// columns hold a satisfied pair; fornpairs the same with N. Q is the best
// fraction of satisfied literals over the goal's options.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

#include "tasks/bddl.hpp"

namespace chore {

inline constexpr size_t kMaxGroundOptions = 20;       // bddl GROUND_GOALS_MAX_OPTIONS
inline constexpr size_t kMaxGroundPermutations = 10;  // bddl GROUND_GOALS_MAX_PERMUTATIONS
// Bounds what bddl 1 leaves unbounded: the complete products (and, the
// goal's options, a negation's choices) and forn's combinations. The
// largest in the corpora: BEHAVIOR-100's assembling_gift_baskets, four 4x4
// forpairs, 10^4 goal options. Under the bound a product is complete and
// lexicographic (itertools.product); past it, it is the first
// kMaxGoalOptions consistent ones in forall's order.
inline constexpr size_t kMaxGoalOptions = 10000;
// Bounds on the work of grounding, which the input sizes (objects, nested
// quantifiers, options that contradict themselves) could otherwise make
// unbounded: formula nodes built, and option tuples visited plus literals
// copied into options. Past either, ground_goal throws an error naming the
// construct (file:line:col) that exceeds it.
inline constexpr size_t kMaxGroundNodes = 1000000;
inline constexpr size_t kMaxGroundWork = 20000000;

// A literal on object instances (no variables). `negated` is part of it: the
// checker answers (not (open x)) as "x is closed".
using GroundLiteral = Literal;
using LiteralId = size_t;  // index into GroundGoal::literals
using GroundOption = std::vector<LiteralId>;

// A goal condition with its quantifiers expanded.
struct GroundFormula {
  Op op = Op::literal;    // never implication (gone in negation normal form)
  LiteralId literal = 0;  // op == literal
  size_t count = 0;       // forn, fornpairs: N
  // forpairs, fornpairs: children are the rows x columns pairs, row-major
  // (rows: first variable). The pair binding one instance to both variables
  // is an empty disjunction: false, with no option.
  size_t columns = 0;
  std::vector<GroundFormula> children;
  int line = 0, column = 0;  // of the construct in its BDDL file (0: not parsed)
};

struct GroundCondition {
  GroundFormula formula;
  std::vector<GroundOption> options;
};

struct GroundGoal {
  std::vector<GroundLiteral> literals;  // each distinct literal once
  std::vector<GroundCondition> conditions;
  std::vector<GroundOption> options;  // the goal's options, shortest first
};

GroundGoal ground_goal(const Problem& problem);

// Does this literal (negated flag included) hold in the world now?
using Truth = std::function<bool(const GroundLiteral&)>;

struct Score {
  bool success = false;               // every condition holds
  std::vector<bool> condition_holds;  // per GroundGoal::conditions
  double q = 0;                       // best fraction of satisfied literals; 0 without options
  size_t satisfied = 0, total = 0;    // of the best option
  std::optional<size_t> best_option;  // first option reaching q; none without options
};

// Asks `truth` at most once per distinct literal. An option without literals
// counts as fully satisfied.
Score score(const GroundGoal& goal, const Truth& truth);

// Fraction of goal.options[option] satisfied: BEHAVIOR's potential, which its
// reward reads on option 0 only. The env's reward is
// weight * (potential(now) - potential(before)): positive when a literal of
// that option becomes true, negative when one is undone.
double potential(const GroundGoal& goal, size_t option, const Truth& truth);

}  // namespace chore
