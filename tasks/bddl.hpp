// BDDL activity definitions: text -> immutable AST, the AST printed back in a
// canonical form, and the goal put in negation normal form for grounding
// (tasks/goal.hpp). Both dialects: BEHAVIOR-100 (:domain igibson) and
// BEHAVIOR-1K (:domain omnigibson: substances such as water.n.06_1, future
// objects and the (future x) / (real x) literals, predicates of any arity).
//
// Grammar (';' starts a comment that runs to the end of the line):
//   (define (problem NAME) (:domain igibson|omnigibson)
//     (:objects NAME... - TYPE ...)  (:init LITERAL...)  (:goal FORMULA))
//   LITERAL = (PREDICATE TERM...) | (not LITERAL)
//   FORMULA = LITERAL | (not F) | (and F...) | (or F...) | (imply F F)
//           | (forall V F) | (exists V F) | (forn (N) V F)
//           | (forpairs V V F) | (fornpairs (N) V V F)      V = (?name - TYPE)
// The operator keywords are fixed; any other head is a predicate name, so an
// unknown quantifier such as (fooall (?x - t) ...) fails on its list argument.
// `for_n_pairs` (the BEHAVIOR-1K paper's spelling) is read as fornpairs.
//
// Terms: a goal term `?x` is the innermost enclosing quantifier's variable if
// one binds it, else the declared object `x`; a bare name is a declared
// object. The second argument of inroom is a room, never checked. Bad input
// throws chore::Error "FILE:LINE:COL: expected ... got ...", with columns
// counted in bytes from 1 (a tab is one column).
#pragma once

#include <compare>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace chore {

enum class Domain { igibson, omnigibson };
const char* to_string(Domain domain);

// A predicate applied to terms, possibly negated. Terms are object instance
// names (or a room name as inroom's second argument) and, inside a goal,
// variables, which keep their leading '?'; a goal's `?basket.n.01_1` naming a
// declared object is stored as the bare `basket.n.01_1`.
// (not (open x)) is this literal with `negated` set, never a separate node:
// BEHAVIOR's negated three-valued predicates (not open = closed, not filled =
// empty, not folded = unfolded) are answered by the predicate checker, which
// receives the flag (tasks/goal.hpp's Truth).
struct Literal {
  std::string predicate;
  std::vector<std::string> args;
  bool negated = false;
  auto operator<=>(const Literal&) const = default;
};

struct ObjectDecl {
  std::string name;  // instance, e.g. basket.n.01_1
  std::string type;  // synset, e.g. basket.n.01
  bool operator==(const ObjectDecl&) const = default;
};

struct Variable {
  std::string name;  // with its '?', e.g. ?basket.n.01
  std::string type;
  bool operator==(const Variable&) const = default;
};

enum class Op {
  literal,
  negation,     // over anything but a literal: negated literals fold into Literal
  conjunction,  // and
  disjunction,  // or
  implication,  // imply: children = antecedent, consequent
  forall,
  exists,
  forn,       // exactly `count` of the bindings satisfy the body
  forpairs,   // BEHAVIOR's pairing of the two variables' instances (tasks/goal.hpp)
  fornpairs,  // the same with `count` pairs
};
const char* keyword(Op op);  // "and", "forall", ...; "" for a literal

struct Formula {
  Op op = Op::literal;
  Literal literal;                  // op == literal
  std::vector<Variable> variables;  // quantifiers: one, or two for the pair quantifiers
  int count = 0;                    // forn, fornpairs: N >= 1
  std::vector<Formula> children;    // operands; a quantifier's body is children[0]
  int line = 0, column = 0;         // where it starts in its file (0: not parsed); not compared
  bool operator==(const Formula& o) const {
    return op == o.op && literal == o.literal && variables == o.variables && count == o.count && children == o.children;
  }
};

struct Problem {
  std::string file;  // the file it was parsed from, for messages; not compared
  std::string name;
  Domain domain = Domain::igibson;
  std::vector<ObjectDecl> objects;  // in file order
  std::vector<Literal> init;        // ground; includes (inroom obj room)
  Formula goal;
  bool operator==(const Problem& o) const {
    return name == o.name && domain == o.domain && objects == o.objects && init == o.init && goal == o.goal;
  }
};

// A domain's predicates with their arities, from its
// (define (domain NAME) ... (:predicates (PREDICATE ?a ?b) ...)).
using Predicates = std::map<std::string, int, std::less<>>;
Predicates parse_domain(std::string_view text, std::string_view file_name);

// What a problem may name beyond the grammar: each dialect's predicates and
// arities, the room types `inroom` may name, and the synsets objects and
// variables may have (`unknown_synset` says why one is not known, or "").
// The parser checks them where they are written (FILE:LINE:COL).
struct Vocabulary {
  Predicates igibson, omnigibson;
  std::set<std::string, std::less<>> room_types;
  std::function<std::string(Domain domain, const std::string& synset)> unknown_synset;
};

struct ParseOptions {
  // Accept bare names that :objects does not declare. Off by default; the
  // BEHAVIOR-1K paper's Listings 1 and 2 need it (oven.n.01_1, bottle.n.01_1).
  bool allow_undeclared_objects = false;
  const Vocabulary* vocabulary = nullptr;  // none: the grammar alone
};

// `file_name` only labels error messages.
Problem parse_bddl(std::string_view text, std::string_view file_name, const ParseOptions& options = {});
Problem load_bddl(const std::string& path, const ParseOptions& options = {});

// Canonical text: four-space indentation, one literal per line, consecutive
// objects of one type on one line, goal constants as bare names.
// parse_bddl(to_bddl(p)) == p for every parsed p.
std::string to_bddl(const Problem& problem);
std::string to_bddl(const Formula& formula);  // multi-line, no trailing newline
std::string to_bddl(const Literal& literal);  // one line: (ontop a b), (not (open c))

// Negation normal form: negations pushed to the literals by De Morgan
// (not and = or not, not forall = exists not, not imply(a, b) = a and not b;
// imply becomes (or (not a) b)). A negation over forn, forpairs or fornpairs
// stays a negation node: those counting quantifiers have no dual in BDDL.
Formula to_nnf(const Formula& formula);

}  // namespace chore
