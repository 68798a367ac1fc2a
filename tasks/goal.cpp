#include "tasks/goal.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/error.hpp"

namespace chore {
namespace {

using Options = std::vector<GroundOption>;
using Visit = std::function<bool(const std::vector<size_t>&)>;  // an index tuple; true: accepted

// "FILE:LINE:COL" of a construct of a parsed problem, else "activity NAME".
std::string where(const Problem& problem, int line, int column) {
  if (line == 0) return "activity " + problem.name;
  return problem.file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

// The work grounding may do (goal.hpp's kMaxGroundNodes, kMaxGroundWork),
// and the construct being ground, which an error names.
class Budget {
 public:
  explicit Budget(const Problem& problem) : problem_(problem) {}

  void node() {
    if (++nodes_ > kMaxGroundNodes) exceeded(std::to_string(kMaxGroundNodes) + " formula nodes");
  }
  void work(size_t steps) {
    work_ += steps;
    if (work_ > kMaxGroundWork)
      exceeded(std::to_string(kMaxGroundWork) + " steps (option tuples visited plus literals copied)");
  }
  // The construct at file line:column, described by `what`, is being ground.
  // No string is built here: it is called for every node.
  void at(int line, int column, std::optional<Op> op) {
    line_ = line;
    column_ = column;
    op_ = op;
  }

 private:
  [[noreturn]] void exceeded(const std::string& limit) const {
    const std::string what = !op_                  ? "the goal's options"
                             : *op_ == Op::literal ? "a literal"
                                                   : "(" + std::string(keyword(*op_)) + " ...)";
    throw Error(where(problem_, line_, column_) + ": grounding " + what + " takes more than " + limit + ", the limit");
  }

  const Problem& problem_;
  size_t nodes_ = 0, work_ = 0;
  int line_ = 0, column_ = 0;
  std::optional<Op> op_;  // none: the goal's options
};

// bddl's truncated_product, tuple for tuple: index tuples in increasing
// index sum, then lexicographic order, until `cap` tuples are counted. bddl
// counts the tuples it skips because an index lies past its sequence's end,
// so a product of many short sequences stops early: six sequences of sizes
// 4, 1, 1, 1, 1, 1 give 2 tuples, not 4. The tuple of last elements comes
// last, outside the order. At most `cap` tuples are looked at; `visit`'s
// answer is not used. An empty sequence: nothing.
void truncated_product(const std::vector<size_t>& sizes, size_t cap, Budget& budget, const Visit& visit) {
  if (std::find(sizes.begin(), sizes.end(), 0) != sizes.end()) return;
  const size_t k = sizes.size();
  size_t last_sum = 0;  // the index sum of the tuple of last elements
  for (size_t s : sizes) last_sum += s - 1;
  std::vector<size_t> index(k);
  size_t counted = 0;
  for (size_t sum = 0; sum < last_sum; ++sum) {
    // The compositions of `sum` into k parts, from (0, ..., 0, sum) on.
    std::fill(index.begin(), index.end(), 0);
    index[k - 1] = sum;
    for (;;) {
      if (counted == cap) return;
      ++counted;
      budget.work(1 + k);
      bool in_range = true;
      for (size_t j = 0; j < k && in_range; ++j) in_range = index[j] < sizes[j];
      if (in_range) visit(index);
      // The next composition: the rightmost part after the first gives one to
      // the part before it and the rest to the last part.
      size_t p = k - 1;
      while (p > 0 && index[p] == 0) --p;
      if (p == 0) break;
      const size_t rest = index[p] - 1;
      index[p] = 0;
      ++index[p - 1];
      index[k - 1] += rest;
    }
  }
  if (counted == cap) return;
  for (size_t j = 0; j < k; ++j) index[j] = sizes[j] - 1;
  budget.work(1 + k);
  visit(index);
}

// Visits elements of the product of sequences of the given sizes, as index
// tuples, in bddl's truncated_product order: increasing index sum, then
// lexicographic. Stops once `visit` has accepted `cap` of them (chore's own
// bounds, where bddl has none or finds nothing). No sequences: one empty
// tuple; an empty sequence: nothing. Iterative: the number of sequences is
// data-sized (a forall over every object).
void first_accepted_in_product_order(const std::vector<size_t>& sizes, size_t cap, Budget& budget, const Visit& visit) {
  if (std::find(sizes.begin(), sizes.end(), 0) != sizes.end()) return;
  const size_t k = sizes.size();
  std::vector<size_t> slack(k + 1, 0);  // slack[j]: the largest index sum of sequences j..k-1
  for (size_t j = k; j-- > 0;) slack[j] = slack[j + 1] + sizes[j] - 1;
  std::vector<size_t> index(k);
  // index[j..] := the lexicographically first tuple with sum `rest`: each
  // index as low as what follows can make up for.
  const auto first_from = [&](size_t j, size_t rest) {
    for (; j < k; ++j) {
      index[j] = rest > slack[j + 1] ? rest - slack[j + 1] : 0;
      rest -= index[j];
    }
  };
  size_t accepted = 0;
  for (size_t sum = 0; sum <= slack[0]; ++sum) {
    first_from(0, sum);
    for (;;) {
      budget.work(1 + k);
      if (visit(index) && ++accepted >= cap) return;
      // The next tuple of this sum: raise the rightmost index that can take
      // one from those after it, which then start again from their first.
      size_t j = k, tail = 0;  // tail: the sum of index[j..]
      while (j > 0 && !(tail >= 1 && index[j - 1] + 1 < sizes[j - 1])) tail += index[--j];
      if (j == 0) break;
      ++index[j - 1];
      first_from(j, tail - 1);
    }
  }
}

// bddl's itertools.product (and, the goal's options): complete, in
// lexicographic order, when it has at most `cap` elements; else the first
// `cap` accepted in truncated_product's order (chore's bound: bddl 1 has none).
void bounded_product(const std::vector<size_t>& sizes, size_t cap, Budget& budget, const Visit& visit) {
  size_t count = 1;
  for (size_t s : sizes) count = s == 0 ? 0 : (count > cap / s ? cap + 1 : count * s);
  if (count > cap) return first_accepted_in_product_order(sizes, cap, budget, visit);
  if (count == 0) return;
  std::vector<size_t> index(sizes.size(), 0);
  for (;;) {
    budget.work(1 + sizes.size());
    visit(index);
    size_t j = sizes.size();
    while (j > 0 && ++index[j - 1] == sizes[j - 1]) index[--j] = 0;
    if (j == 0) return;
  }
}

// The first kMaxGroundPermutations r-permutations of 0..n-1 in lexicographic
// order (bddl's truncated_permutations); none when r > n.
std::vector<std::vector<size_t>> truncated_permutations(size_t n, size_t r) {
  std::vector<std::vector<size_t>> out;
  std::vector<size_t> current;
  std::vector<bool> used(n, false);
  const std::function<void()> extend = [&] {
    if (out.size() == kMaxGroundPermutations) return;
    if (current.size() == r) {
      out.push_back(current);
      return;
    }
    for (size_t i = 0; i < n; ++i) {
      if (used[i]) continue;
      used[i] = true;
      current.push_back(i);
      extend();
      current.pop_back();
      used[i] = false;
    }
  };
  if (r <= n) extend();
  return out;
}

// Calls visit for each n-combination of 0..k-1 in lexicographic order
// (itertools.combinations) until it returns false.
void combinations(size_t k, size_t n, const Visit& visit) {
  if (n > k) return;
  std::vector<size_t> c(n);
  for (size_t i = 0; i < n; ++i) c[i] = i;
  for (;;) {
    if (!visit(c)) return;
    size_t i = n;
    while (i > 0 && c[i - 1] == k - n + i - 1) --i;
    if (i == 0) return;
    ++c[i - 1];
    for (size_t j = i; j < n; ++j) c[j] = c[j - 1] + 1;
  }
}

void append(GroundOption& to, const GroundOption& from) {
  to.insert(to.end(), from.begin(), from.end());
}

using Product = void (*)(const std::vector<size_t>& sizes, size_t cap, Budget& budget, const Visit& visit);

// Options with the chosen element of each sequence concatenated.
Options product(Product order, const std::vector<Options>& sequences, size_t cap, Budget& budget) {
  std::vector<size_t> sizes;
  for (const Options& s : sequences) sizes.push_back(s.size());
  Options out;
  order(sizes, cap, budget, [&](const std::vector<size_t>& index) {
    GroundOption& option = out.emplace_back();
    for (size_t j = 0; j < index.size(); ++j) {
      budget.work(sequences[j][index[j]].size());
      append(option, sequences[j][index[j]]);
    }
    return true;
  });
  return out;
}

// Which bddl release's option generation a file's dialect follows: the
// products of and, of a negation's choices and of the goal's conditions are
// complete (itertools.product) in bddl 1.0.1, iGibson 2.0's, which
// BEHAVIOR-100's files were written for, and truncated to the first
// kMaxGroundOptions in bddl 3.x, OmniGibson's (BEHAVIOR-1K).
struct Rules {
  Product product;
  size_t cap;
};
Rules dialect_rules(Domain domain) {
  if (domain == Domain::omnigibson) return {truncated_product, kMaxGroundOptions};
  return {bounded_product, kMaxGoalOptions};
}

class Grounder {
 public:
  Grounder(const Problem& problem, GroundGoal& goal, Budget& budget)
      : problem_(problem), rules_(dialect_rules(problem.domain)), goal_(goal), budget_(budget) {}

  GroundCondition condition(const Formula& f) {
    budget_.at(f.line, f.column, f.op);
    GroundCondition c;
    c.formula = expand(f);
    c.options = options(c.formula);
    return c;
  }

  // complement[id]: the id of the literal with the opposite flag, if any.
  std::vector<std::optional<LiteralId>> complements() const {
    std::vector<std::optional<LiteralId>> out;
    for (GroundLiteral l : goal_.literals) {
      l.negated = !l.negated;
      const auto it = ids_.find(l);
      out.push_back(it == ids_.end() ? std::nullopt : std::optional(it->second));
    }
    return out;
  }

 private:
  LiteralId intern(const GroundLiteral& l) {
    const auto [it, inserted] = ids_.emplace(l, goal_.literals.size());
    if (inserted) goal_.literals.push_back(l);
    return it->second;
  }

  std::vector<std::string> instances(const Formula& quantifier, const Variable& v) const {
    std::vector<std::string> out;
    for (const ObjectDecl& o : problem_.objects)
      if (o.type == v.type) out.push_back(o.name);
    if (out.empty())
      throw Error(where(problem_, quantifier.line, quantifier.column) + ": (" + v.name + " - " + v.type +
                  ") ranges over no object declared in :objects");
    return out;
  }

  GroundFormula bound(const Formula& body, const std::vector<std::pair<std::string, std::string>>& b) {
    bindings_.insert(bindings_.end(), b.begin(), b.end());
    GroundFormula g = expand(body);
    bindings_.resize(bindings_.size() - b.size());
    return g;
  }

  GroundFormula expand(const Formula& f) {
    budget_.node();
    GroundFormula g;
    g.op = f.op;
    g.count = static_cast<size_t>(f.count);
    g.line = f.line;
    g.column = f.column;
    switch (f.op) {
      case Op::literal: {
        GroundLiteral l = f.literal;
        for (std::string& arg : l.args) {
          if (!arg.starts_with('?')) continue;
          const auto it =
              std::find_if(bindings_.rbegin(), bindings_.rend(), [&](const auto& b) { return b.first == arg; });
          if (it == bindings_.rend()) throw Error(where(problem_, f.line, f.column) + ": unbound variable " + arg);
          arg = it->second;
        }
        g.literal = intern(l);
        return g;
      }
      case Op::forall:
      case Op::exists:
      case Op::forn:
        for (const std::string& x : instances(f, f.variables[0]))
          g.children.push_back(bound(f.children[0], {{f.variables[0].name, x}}));
        return g;
      case Op::forpairs:
      case Op::fornpairs: {
        const std::vector<std::string> columns = instances(f, f.variables[1]);
        g.columns = columns.size();
        GroundFormula no_pair;  // the empty disjunction: false, with no option
        no_pair.op = Op::disjunction;
        for (const std::string& x : instances(f, f.variables[0]))
          for (const std::string& y : columns)
            g.children.push_back(x == y ? no_pair
                                        : bound(f.children[0], {{f.variables[0].name, x}, {f.variables[1].name, y}}));
        return g;
      }
      default:  // negation, conjunction, disjunction, implication
        for (const Formula& c : f.children) g.children.push_back(expand(c));
        return g;
    }
  }

  Options options(const GroundFormula& g) {
    std::vector<Options> children;
    for (const GroundFormula& c : g.children) children.push_back(options(c));
    budget_.at(g.line, g.column, g.op);
    switch (g.op) {
      case Op::literal:
        return {{g.literal}};
      case Op::negation:
        return negated(children[0]);
      case Op::conjunction:
        return product(rules_.product, children, rules_.cap, budget_);
      case Op::disjunction:
      case Op::exists: {
        Options out;
        for (Options& c : children) {
          for (const GroundOption& o : c) budget_.work(1 + o.size());
          out.insert(out.end(), c.begin(), c.end());
        }
        return out;
      }
      case Op::forall:
        return product(truncated_product, children, kMaxGroundOptions, budget_);
      case Op::forn:
        return forn(children, g.count);
      case Op::forpairs:
      case Op::fornpairs:
        return pairs(g, children);
      case Op::implication:
        break;
    }
    throw std::logic_error("ground goal: imply must be gone after to_nnf");
  }

  // De Morgan on options: the operand fails when one literal of each of its
  // options fails.
  Options negated(const Options& operand) {
    std::vector<Options> choices;
    for (const GroundOption& option : operand) {
      Options& c = choices.emplace_back();
      for (LiteralId id : option) {
        GroundLiteral l = goal_.literals[id];
        l.negated = !l.negated;
        c.push_back({intern(l)});
      }
    }
    return product(rules_.product, choices, rules_.cap, budget_);
  }

  // Exactly N: the N-combinations of the operands within each truncated-product option.
  Options forn(const std::vector<Options>& children, size_t n) {
    std::vector<size_t> sizes;
    for (const Options& c : children) sizes.push_back(c.size());
    Options out;
    truncated_product(sizes, kMaxGroundOptions, budget_, [&](const std::vector<size_t>& index) {
      combinations(children.size(), n, [&](const std::vector<size_t>& chosen) {
        if (out.size() == kMaxGoalOptions) return false;
        GroundOption& option = out.emplace_back();
        budget_.work(1);
        for (size_t j : chosen) {
          budget_.work(children[j][index[j]].size());
          append(option, children[j][index[j]]);
        }
        return true;
      });
      return true;
    });
    return out;
  }

  // bddl's ForPairs / ForNPairs: the first L instances of one side in order
  // (the rows of fornpairs; of forpairs, the rows when they are fewer than
  // the columns, else the columns), the k-th paired with the k-th of each
  // L-permutation of the other side (the first kMaxGroundPermutations); each
  // choice's pairs combine by truncated product. bddl permutes the first side
  // too, but reads the other's permutations from a generator that its first
  // permutation uses up.
  Options pairs(const GroundFormula& g, const std::vector<Options>& cells) {
    const size_t columns = g.columns, rows = columns == 0 ? 0 : g.children.size() / columns;
    const size_t l = g.op == Op::fornpairs ? g.count : std::min(rows, columns);
    const bool rows_in_order = g.op == Op::fornpairs || rows < columns;
    if (l > (rows_in_order ? rows : columns)) return {};
    Options out;
    for (const std::vector<size_t>& p : truncated_permutations(rows_in_order ? columns : rows, l)) {
      std::vector<Options> chosen;
      for (size_t k = 0; k < l; ++k) {
        const size_t row = rows_in_order ? k : p[k], column = rows_in_order ? p[k] : k;
        chosen.push_back(cells[row * columns + column]);
      }
      const Options choice = product(truncated_product, chosen, kMaxGroundOptions, budget_);
      out.insert(out.end(), choice.begin(), choice.end());
    }
    return out;
  }

  const Problem& problem_;
  const Rules rules_;
  GroundGoal& goal_;
  Budget& budget_;
  std::map<GroundLiteral, LiteralId> ids_;
  std::vector<std::pair<std::string, std::string>> bindings_;  // variable -> instance, innermost last
};

// Answers literal truth at most once per literal.
class Evaluator {
 public:
  Evaluator(const GroundGoal& goal, const Truth& truth)
      : goal_(goal), truth_(truth), known_(goal.literals.size(), -1) {}

  bool holds(LiteralId id) {
    if (known_[id] < 0) known_[id] = truth_(goal_.literals[id]) ? 1 : 0;
    return known_[id] == 1;
  }

  bool holds(const GroundFormula& g) {
    const auto child_holds = [&](const GroundFormula& c) { return holds(c); };
    switch (g.op) {
      case Op::literal:
        return holds(g.literal);
      case Op::negation:
        return !holds(g.children[0]);
      case Op::conjunction:
      case Op::forall:
        return std::all_of(g.children.begin(), g.children.end(), child_holds);
      case Op::disjunction:
      case Op::exists:
        return std::any_of(g.children.begin(), g.children.end(), child_holds);
      case Op::forn:
        return static_cast<size_t>(std::count_if(g.children.begin(), g.children.end(), child_holds)) == g.count;
      case Op::forpairs:
      case Op::fornpairs:
        return pairs_hold(g);
      case Op::implication:
        break;
    }
    throw std::logic_error("score goal: imply must be gone after to_nnf");
  }

  size_t satisfied(const GroundOption& option) {
    return static_cast<size_t>(std::count_if(option.begin(), option.end(), [&](LiteralId id) { return holds(id); }));
  }

 private:
  // At least L rows and L columns hold a satisfied pair.
  bool pairs_hold(const GroundFormula& g) {
    const size_t columns = g.columns, rows = columns == 0 ? 0 : g.children.size() / columns;
    const size_t l = g.op == Op::fornpairs ? g.count : std::min(rows, columns);
    std::vector<bool> row_hit(rows, false), column_hit(columns, false);
    for (size_t r = 0; r < rows; ++r)
      for (size_t c = 0; c < columns; ++c)
        if (holds(g.children[r * columns + c])) row_hit[r] = column_hit[c] = true;
    return static_cast<size_t>(std::count(row_hit.begin(), row_hit.end(), true)) >= l &&
           static_cast<size_t>(std::count(column_hit.begin(), column_hit.end(), true)) >= l;
  }

  const GroundGoal& goal_;
  const Truth& truth_;
  std::vector<signed char> known_;  // -1 unknown, else 0/1
};

double fraction(size_t satisfied, size_t total) {
  return total == 0 ? 1.0 : static_cast<double>(satisfied) / static_cast<double>(total);
}

}  // namespace

GroundGoal ground_goal(const Problem& problem) {
  GroundGoal goal;
  Budget budget(problem);
  Grounder grounder(problem, goal, budget);
  const Formula nnf = to_nnf(problem.goal);
  if (nnf.op == Op::conjunction) {
    for (const Formula& c : nnf.children) goal.conditions.push_back(grounder.condition(c));
  } else {
    goal.conditions.push_back(grounder.condition(nnf));
  }

  // The product of the conditions' options without those holding c and
  // (not c): bddl filters the product it made (the dialect's). Where bddl 3's
  // tuples all contradict themselves (it asserts there: four BEHAVIOR-1K
  // activities), chore takes the first kMaxGroundOptions consistent ones.
  const Rules rules = dialect_rules(problem.domain);
  const std::vector<std::optional<LiteralId>> complement = grounder.complements();
  std::vector<size_t> sizes;
  for (const GroundCondition& c : goal.conditions) sizes.push_back(c.options.size());
  std::vector<bool> in_option(goal.literals.size(), false);
  budget.at(problem.goal.line, problem.goal.column, std::nullopt);
  const auto consistent_options = [&](Product order, size_t cap) {
    Options options;
    order(sizes, cap, budget, [&](const std::vector<size_t>& index) {
      GroundOption option;
      for (size_t j = 0; j < index.size(); ++j) {
        budget.work(goal.conditions[j].options[index[j]].size());
        append(option, goal.conditions[j].options[index[j]]);
      }
      for (LiteralId id : option) in_option[id] = true;
      const bool consistent = std::none_of(option.begin(), option.end(),
                                           [&](LiteralId id) { return complement[id] && in_option[*complement[id]]; });
      for (LiteralId id : option) in_option[id] = false;
      if (consistent) options.push_back(std::move(option));
      return consistent;
    });
    return options;
  };
  goal.options = consistent_options(rules.product, rules.cap);
  if (goal.options.empty()) goal.options = consistent_options(first_accepted_in_product_order, kMaxGroundOptions);
  std::stable_sort(goal.options.begin(), goal.options.end(),
                   [](const GroundOption& a, const GroundOption& b) { return a.size() < b.size(); });
  return goal;
}

Score score(const GroundGoal& goal, const Truth& truth) {
  Evaluator evaluator(goal, truth);
  Score s;
  s.success = true;
  for (const GroundCondition& c : goal.conditions) {
    s.condition_holds.push_back(evaluator.holds(c.formula));
    s.success = s.success && s.condition_holds.back();
  }
  for (size_t i = 0; i < goal.options.size(); ++i) {
    const size_t satisfied = evaluator.satisfied(goal.options[i]);
    const double q = fraction(satisfied, goal.options[i].size());
    if (!s.best_option || q > s.q) {
      s.q = q;
      s.satisfied = satisfied;
      s.total = goal.options[i].size();
      s.best_option = i;
    }
  }
  return s;
}

double potential(const GroundGoal& goal, size_t option, const Truth& truth) {
  const GroundOption& o = goal.options.at(option);
  return fraction(Evaluator(goal, truth).satisfied(o), o.size());
}

}  // namespace chore
