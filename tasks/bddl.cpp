#include "tasks/bddl.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

#include "base/error.hpp"
#include "base/json_file.hpp"

namespace chore {

namespace {

// The operator keywords, in Op order; for_n_pairs is the BEHAVIOR-1K paper's
// spelling of fornpairs.
constexpr std::pair<const char*, Op> kOperators[] = {
    {"not", Op::negation},        {"and", Op::conjunction},       {"or", Op::disjunction}, {"imply", Op::implication},
    {"forall", Op::forall},       {"exists", Op::exists},         {"forn", Op::forn},      {"forpairs", Op::forpairs},
    {"fornpairs", Op::fornpairs}, {"for_n_pairs", Op::fornpairs},
};

std::optional<Op> operator_named(std::string_view name) {
  for (const auto& [word, op] : kOperators)
    if (name == word) return op;
  return std::nullopt;
}

// Deeper nesting than any activity needs is refused, so that hostile input
// cannot exhaust the stack of the recursive parser and printer.
constexpr size_t kMaxNesting = 100;
constexpr size_t kMaxBddlBytes = 16u << 20;  // BEHAVIOR's largest activity is ~10 KB
constexpr int kMaxCount = 1000000;

// kitchen_0 -> kitchen: a scene's room names are its types numbered.
std::string_view room_type(std::string_view room) {
  const size_t underscore = room.rfind('_');
  if (underscore == std::string_view::npos || underscore + 1 == room.size()) return room;
  const std::string_view number = room.substr(underscore + 1);
  const bool digits = std::all_of(number.begin(), number.end(), [](char c) { return c >= '0' && c <= '9'; });
  return digits ? room.substr(0, underscore) : room;
}

bool is_pair_quantifier(Op op) {
  return op == Op::forpairs || op == Op::fornpairs;
}
bool has_count(Op op) {
  return op == Op::forn || op == Op::fornpairs;
}

struct Pos {
  int line = 1, column = 1;
};

std::string to_string(Pos p) {
  return std::to_string(p.line) + ":" + std::to_string(p.column);
}

// A name or a list, with where it starts; a list also keeps where its ')' is:
// a missing element is reported there.
struct Sexp {
  bool is_list = false;
  std::string atom;
  std::vector<Sexp> items;
  Pos pos, end;
};

std::string quote(std::string_view s) {
  return "'" + std::string(s) + "'";
}

// How an expression shows up after "got": 'name', '(name' or '('.
std::string describe(const Sexp& e) {
  if (!e.is_list) return quote(e.atom);
  if (!e.items.empty() && !e.items[0].is_list) return quote("(" + e.items[0].atom);
  return quote("(");
}

[[noreturn]] void fail(std::string_view file, Pos p, std::string_view expected, std::string_view got) {
  throw Error(std::string(file) + ":" + to_string(p) + ": expected " + std::string(expected) + " got " +
              std::string(got));
}

// Text -> one s-expression, nested at most kMaxNesting deep.
class Reader {
 public:
  Reader(std::string_view text, std::string_view file) : text_(text), file_(file) {}

  Sexp document() {
    std::vector<Sexp> open;  // lists being read, innermost last
    std::optional<Sexp> top;
    for (;;) {
      skip_space_and_comments();
      if (i_ == text_.size()) {
        if (!open.empty()) fail(file_, open.back().pos, "')' closing this '('", "end of file");
        if (!top) fail(file_, here_, "'(define'", "end of file");
        return std::move(*top);
      }
      const Pos start = here_;
      const char c = text_[i_];
      if (open.empty() && top)
        fail(file_, start, "end of file", c == '(' || c == ')' ? quote(std::string(1, c)) : quote(name()));
      Sexp item;
      if (c == '(') {
        if (open.size() == kMaxNesting)
          fail(file_, start, "at most " + std::to_string(kMaxNesting) + " nested lists", "'('");
        advance();
        open.emplace_back().is_list = true;
        open.back().pos = start;
        continue;
      }
      if (c == ')') {
        if (open.empty()) fail(file_, start, "'(define'", "')'");
        advance();
        item = std::move(open.back());
        open.pop_back();
        item.end = start;
      } else {
        item.atom = name();
        item.pos = start;
      }
      if (open.empty())
        top = std::move(item);
      else
        open.back().items.push_back(std::move(item));
    }
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
  static bool ends_name(char c) { return is_space(c) || c == '(' || c == ')' || c == ';'; }

  void advance() {
    if (text_[i_] == '\n') {
      ++here_.line;
      here_.column = 1;
    } else {
      ++here_.column;
    }
    ++i_;
  }

  void skip_space_and_comments() {
    while (i_ < text_.size()) {
      if (text_[i_] == ';') {
        while (i_ < text_.size() && text_[i_] != '\n') advance();
      } else if (is_space(text_[i_])) {
        advance();
      } else {
        return;
      }
    }
  }

  std::string name() {
    const size_t start = i_;
    while (i_ < text_.size() && !ends_name(text_[i_])) advance();
    return std::string(text_.substr(start, i_ - start));
  }

  std::string_view text_, file_;
  size_t i_ = 0;
  Pos here_;
};

// S-expression -> Problem, checking names against :objects and the variables
// in scope.
class Parser {
 public:
  Parser(std::string_view file, const ParseOptions& options) : file_(file), options_(options) {}

  Problem problem(const Sexp& file) {
    Problem p;
    if (!file.is_list) fail_at(file, "'(define'");
    // Atoms between the sections are skipped, as BEHAVIOR's parser skips them
    // (BEHAVIOR-1K's wash_a_baseball_cap has a stray '\' after :init).
    Sexp define{.is_list = true, .pos = file.pos, .end = file.end};
    for (size_t i = 0; i < file.items.size(); ++i) {
      if (i == 0 || file.items[i].is_list) define.items.push_back(file.items[i]);
    }
    keyword(define, 0, "define");
    const Sexp& header = list(item(define, 1, "(problem NAME)"), "(problem NAME)");
    keyword(header, 0, "problem");
    p.name = name(item(header, 1, "a problem name"), "a problem name");
    expect_size(header, 2);

    const Sexp& domain = section(define, 2, ":domain");
    const Sexp& domain_name = item(domain, 1, "igibson or omnigibson");
    if (domain_name.atom == "igibson")
      p.domain = Domain::igibson;
    else if (domain_name.atom == "omnigibson")
      p.domain = Domain::omnigibson;
    else
      fail_at(domain_name, "igibson or omnigibson");
    expect_size(domain, 2);
    domain_ = p.domain;
    if (options_.vocabulary) {
      predicates_ = p.domain == Domain::igibson ? &options_.vocabulary->igibson : &options_.vocabulary->omnigibson;
    }

    p.objects = objects(section(define, 3, ":objects"));
    const Sexp& init = section(define, 4, ":init");
    for (size_t i = 1; i < init.items.size(); ++i) p.init.push_back(ground_literal(init.items[i]));
    const Sexp& goal = section(define, 5, ":goal");
    p.goal = formula(item(goal, 1, "a formula"));
    if (goal.items.size() > 2) {
      // Several formulas: their conjunction, as in BEHAVIOR's parser
      // (BEHAVIOR-1K's loading_the_car).
      Formula all{.op = Op::conjunction, .line = goal.pos.line, .column = goal.pos.column};
      all.children.push_back(std::move(p.goal));
      for (size_t i = 2; i < goal.items.size(); ++i) all.children.push_back(formula(goal.items[i]));
      p.goal = std::move(all);
    }
    expect_size(define, 6);
    return p;
  }

 private:
  [[noreturn]] void fail_at(const Sexp& e, std::string_view expected) const {
    fail(file_, e.pos, expected, describe(e));
  }

  // list.items[index], or an error at the list's ')' when it has fewer items.
  const Sexp& item(const Sexp& list, size_t index, std::string_view expected) const {
    if (index >= list.items.size()) fail(file_, list.end, expected, "')'");
    return list.items[index];
  }

  void expect_size(const Sexp& list, size_t size) const {
    if (list.items.size() > size) fail_at(list.items[size], "')'");
  }

  const std::string& name(const Sexp& e, std::string_view expected) const {
    if (e.is_list) fail_at(e, expected);
    return e.atom;
  }

  const Sexp& list(const Sexp& e, std::string_view expected) const {
    if (!e.is_list) fail_at(e, expected);
    return e;
  }

  void keyword(const Sexp& list, size_t index, std::string_view word) const {
    const Sexp& e = item(list, index, quote(word));
    if (e.is_list || e.atom != word) fail_at(e, quote(word));
  }

  const Sexp& section(const Sexp& define, size_t index, std::string_view word) const {
    const std::string expected = "(" + std::string(word) + " ...)";
    const Sexp& s = item(define, index, expected);
    if (!s.is_list || s.items.empty() || s.items[0].is_list || s.items[0].atom != word) fail_at(s, expected);
    return s;
  }

  // NAME... - TYPE groups.
  std::vector<ObjectDecl> objects(const Sexp& section) {
    std::vector<ObjectDecl> decls;
    size_t untyped = 0;  // trailing declarations still waiting for their type
    for (size_t i = 1; i < section.items.size(); ++i) {
      const Sexp& e = section.items[i];
      const std::string& word = name(e, "an object name");
      if (word == "-") {
        if (untyped == 0) fail_at(e, "an object name");
        const Sexp& type = item(section, ++i, "a type after '-'");
        if (type.is_list || type.atom == "-" || type.atom.starts_with('?')) fail_at(type, "a type after '-'");
        check_synset(type);
        for (size_t k = decls.size() - untyped; k < decls.size(); ++k) decls[k].type = type.atom;
        untyped = 0;
        continue;
      }
      if (word.starts_with('?') || word.starts_with(':')) fail_at(e, "an object name");
      // A name repeated before its type is one object, as in BEHAVIOR's object
      // scope (BEHAVIOR-1K's passing_out_drinks lists one bottle twice).
      if (std::any_of(decls.end() - untyped, decls.end(), [&](const ObjectDecl& d) { return d.name == word; }))
        continue;
      if (const auto it = declared_.find(word); it != declared_.end())
        fail(file_, e.pos, "an object name not declared before",
             quote(word) + " (declared at " + to_string(it->second) + ")");
      declared_.emplace(word, e.pos);
      decls.push_back({word, ""});
      ++untyped;
    }
    if (untyped > 0) fail(file_, section.end, "'- TYPE' after " + quote(decls.back().name), "')'");
    return decls;
  }

  // An :init entry: (PREDICATE NAME...) or (not ...).
  Literal ground_literal(const Sexp& e) {
    if (!e.is_list || e.items.empty()) fail_at(e, "a literal");
    if (!e.items[0].is_list && e.items[0].atom == "not") {
      Literal l = ground_literal(item(e, 1, "a literal"));
      expect_size(e, 2);
      l.negated = !l.negated;
      return l;
    }
    return atom(e);
  }

  Literal atom(const Sexp& e) const {
    const Sexp& head = e.items[0];
    if (head.is_list || head.atom.starts_with('?') || head.atom.starts_with(':') || operator_named(head.atom))
      fail_at(head, "a predicate name");
    Literal l{head.atom, {}, false};
    if (predicates_) {
      const auto known = predicates_->find(head.atom);
      if (known == predicates_->end()) fail_at(head, "a predicate of the domain");
      if (static_cast<int>(e.items.size()) - 1 != known->second) {
        fail(file_, e.pos, std::to_string(known->second) + " argument(s) to " + quote(head.atom),
             std::to_string(e.items.size() - 1));
      }
    }
    for (size_t i = 1; i < e.items.size(); ++i) l.args.push_back(term(e.items[i], l.predicate, i - 1));
    return l;
  }

  // A synset the vocabulary knows (agent.n.01 and floor.n.01 always).
  void check_synset(const Sexp& type) const {
    if (!options_.vocabulary || !options_.vocabulary->unknown_synset) return;
    if (type.atom == "agent.n.01" || type.atom == "floor.n.01") return;
    const std::string why = options_.vocabulary->unknown_synset(domain_, type.atom);
    if (!why.empty()) throw Error(std::string(file_) + ":" + to_string(type.pos) + ": " + why);
  }

  std::string term(const Sexp& e, std::string_view predicate, size_t index) const {
    if (e.is_list) fail_at(e, "a term");
    const std::string& t = e.atom;
    if (t.starts_with('?')) {
      if (std::find(scope_.begin(), scope_.end(), t) != scope_.end()) return t;
      std::string object = t.substr(1);
      if (declared_.contains(object)) return object;
      fail_at(e, "a variable bound by an enclosing quantifier or a declared object");
    }
    const bool room = predicate == "inroom" && index == 1;
    if (room && options_.vocabulary && !options_.vocabulary->room_types.contains(room_type(t)))
      fail_at(e, "a room type (or a room named TYPE_N)");
    if (!room && !options_.allow_undeclared_objects && !declared_.contains(t))
      fail_at(e, "an object declared in :objects");
    return t;
  }

  Formula formula(const Sexp& e) {
    if (!e.is_list || e.items.empty()) fail_at(e, "a formula");
    const Sexp& head = e.items[0];
    const std::optional<Op> op = head.is_list ? std::nullopt : operator_named(head.atom);
    Formula f;
    f.line = e.pos.line;
    f.column = e.pos.column;
    if (!op) {
      f.literal = atom(e);
      return f;
    }
    f.op = *op;
    switch (*op) {
      case Op::negation: {
        Formula operand = formula(item(e, 1, "a formula"));
        expect_size(e, 2);
        if (operand.op == Op::literal) {
          operand.literal.negated = !operand.literal.negated;
          operand.line = f.line;
          operand.column = f.column;
          return operand;
        }
        f.children.push_back(std::move(operand));
        return f;
      }
      case Op::conjunction:
      case Op::disjunction:
        for (size_t i = 1; i < e.items.size(); ++i) f.children.push_back(formula(e.items[i]));
        return f;
      case Op::implication:
        f.children.push_back(formula(item(e, 1, "an antecedent formula")));
        f.children.push_back(formula(item(e, 2, "a consequent formula")));
        expect_size(e, 3);
        return f;
      default:
        return quantifier(e, std::move(f));
    }
  }

  Formula quantifier(const Sexp& e, Formula f) {
    size_t next = 1;
    if (has_count(f.op)) f.count = count(item(e, next++, "a count such as (2)"));
    const size_t variables = is_pair_quantifier(f.op) ? 2 : 1;
    for (size_t k = 0; k < variables; ++k) {
      f.variables.push_back(variable(item(e, next++, "a variable declaration (?x - TYPE)")));
      scope_.push_back(f.variables.back().name);
    }
    f.children.push_back(formula(item(e, next++, "a formula")));
    scope_.resize(scope_.size() - variables);
    expect_size(e, next);
    return f;
  }

  Variable variable(const Sexp& e) const {
    list(e, "a variable declaration (?x - TYPE)");
    const Sexp& var = item(e, 0, "a variable such as ?x");
    if (var.is_list || !var.atom.starts_with('?') || var.atom.size() == 1) fail_at(var, "a variable such as ?x");
    const Sexp& dash = item(e, 1, "'-'");
    if (dash.is_list || dash.atom != "-") fail_at(dash, "'-'");
    const Sexp& type = item(e, 2, "a type");
    if (type.is_list || type.atom == "-" || type.atom.starts_with('?')) fail_at(type, "a type");
    check_synset(type);
    expect_size(e, 3);
    return {var.atom, type.atom};
  }

  int count(const Sexp& e) const {
    constexpr std::string_view expected = "a count such as (2)";
    list(e, expected);
    const Sexp& n = item(e, 0, expected);
    const bool digits = !n.is_list && !n.atom.empty() && n.atom.size() <= 7 &&
                        std::all_of(n.atom.begin(), n.atom.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (!digits || std::stoi(n.atom) < 1 || std::stoi(n.atom) > kMaxCount) fail_at(n, "a count from 1 to 1000000");
    expect_size(e, 1);
    return std::stoi(n.atom);
  }

  std::string_view file_;
  ParseOptions options_;
  std::map<std::string, Pos, std::less<>> declared_;  // :objects, with where each is declared
  std::vector<std::string> scope_;                    // goal variables in scope, innermost last
  const Predicates* predicates_ = nullptr;            // the vocabulary's, for the problem's dialect
  Domain domain_ = Domain::igibson;                   // the problem's dialect, once read
};

void print(std::string& out, const Formula& f, int depth) {
  const std::string indent(4 * depth, ' ');
  if (f.op == Op::literal) {
    out += indent + to_bddl(f.literal) + "\n";
    return;
  }
  const std::string inner(4 * (depth + 1), ' ');
  out += indent + "(" + keyword(f.op) + "\n";
  if (has_count(f.op)) out += inner + "(" + std::to_string(f.count) + ")\n";
  for (const Variable& v : f.variables) out += inner + "(" + v.name + " - " + v.type + ")\n";
  for (const Formula& c : f.children) print(out, c, depth + 1);
  out += indent + ")\n";
}

Formula nnf(const Formula& f, bool negate) {
  Formula out = f;
  switch (f.op) {
    case Op::literal:
      out.literal.negated = f.literal.negated != negate;
      return out;
    case Op::negation:
      return nnf(f.children[0], !negate);
    case Op::conjunction:
    case Op::disjunction:
      if (negate) out.op = f.op == Op::conjunction ? Op::disjunction : Op::conjunction;
      break;
    case Op::implication: {
      // imply(a, b) = (or (not a) b); its negation = (and a (not b)).
      out.op = negate ? Op::conjunction : Op::disjunction;
      out.children = {nnf(f.children[0], !negate), nnf(f.children[1], negate)};
      return out;
    }
    case Op::forall:
    case Op::exists:
      if (negate) out.op = f.op == Op::forall ? Op::exists : Op::forall;
      break;
    case Op::forn:
    case Op::forpairs:
    case Op::fornpairs: {
      out.children = {nnf(f.children[0], false)};
      if (!negate) return out;
      Formula negation;
      negation.op = Op::negation;
      negation.line = f.line;
      negation.column = f.column;
      negation.children.push_back(std::move(out));
      return negation;
    }
  }
  for (Formula& c : out.children) c = nnf(c, negate);
  return out;
}

}  // namespace

const char* to_string(Domain domain) {
  return domain == Domain::igibson ? "igibson" : "omnigibson";
}

const char* keyword(Op op) {
  for (const auto& [word, o] : kOperators)
    if (o == op) return word;
  return "";  // a literal
}

Problem parse_bddl(std::string_view text, std::string_view file_name, const ParseOptions& options) {
  const Sexp document = Reader(text, file_name).document();
  Problem p = Parser(file_name, options).problem(document);
  p.file = file_name;
  return p;
}

Predicates parse_domain(std::string_view text, std::string_view file_name) {
  const Sexp define = Reader(text, file_name).document();
  const auto fail_at = [&](const Sexp& e, std::string_view expected) { fail(file_name, e.pos, expected, describe(e)); };
  if (!define.is_list || define.items.empty() || define.items[0].atom != "define") fail_at(define, "'(define'");
  for (const Sexp& section : define.items) {
    if (!section.is_list || section.items.empty() || section.items[0].atom != ":predicates") continue;
    Predicates predicates;
    for (size_t i = 1; i < section.items.size(); ++i) {
      const Sexp& p = section.items[i];
      if (!p.is_list || p.items.empty() || p.items[0].is_list) fail_at(p, "a predicate such as (ontop ?a ?b)");
      int arity = 0;  // variables, less typed-list '- TYPE's
      for (size_t k = 1; k < p.items.size(); ++k) {
        if (p.items[k].is_list) fail_at(p.items[k], "a variable");
        if (p.items[k].atom.starts_with('?')) ++arity;
      }
      predicates[p.items[0].atom] = arity;
    }
    return predicates;
  }
  fail(file_name, define.end, "(:predicates ...)", "')'");
}

Problem load_bddl(const std::string& path, const ParseOptions& options) {
  return parse_bddl(read_text_file(path, kMaxBddlBytes, "a BDDL file"), path, options);
}

std::string to_bddl(const Literal& literal) {
  std::string s = "(" + literal.predicate;
  for (const std::string& a : literal.args) s += " " + a;
  s += ")";
  return literal.negated ? "(not " + s + ")" : s;
}

std::string to_bddl(const Formula& formula) {
  std::string out;
  print(out, formula, 0);
  out.pop_back();  // the last newline
  return out;
}

std::string to_bddl(const Problem& problem) {
  std::string out = "(define (problem " + problem.name + ")\n";
  out += "    (:domain " + std::string(to_string(problem.domain)) + ")\n\n    (:objects\n";
  for (size_t i = 0; i < problem.objects.size();) {
    const std::string& type = problem.objects[i].type;
    out += "        ";
    for (; i < problem.objects.size() && problem.objects[i].type == type; ++i) out += problem.objects[i].name + " ";
    out += "- " + type + "\n";
  }
  out += "    )\n\n    (:init\n";
  for (const Literal& l : problem.init) out += "        " + to_bddl(l) + "\n";
  out += "    )\n\n    (:goal\n";
  print(out, problem.goal, 2);
  out += "    )\n)\n";
  return out;
}

Formula to_nnf(const Formula& formula) {
  return nnf(formula, false);
}

}  // namespace chore
