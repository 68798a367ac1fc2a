#include "planner/task_planner.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <iterator>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <unordered_map>

#include "planner/reachability.hpp"

namespace chore {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A step over interned literals.
struct Step {
  size_t source;  // index into GroundSteps::steps
  std::vector<int> needs, needs_not, deletes, adds;
  bool at_once;  // SymbolicStep::at_once: fired by settle(), never chosen
};

// A goal literal over interned literals: -1 for one no step or :init names
// (it never holds).
struct Target {
  int id;
  bool negated;
};

using State = std::vector<int>;  // sorted literal ids

struct StateHash {
  size_t operator()(const State& s) const {
    size_t h = 1469598103934665603ull;
    for (const int v : s) h = (h ^ static_cast<size_t>(v)) * 1099511628211ull;
    return h;
  }
};

class Search {
 public:
  Search(const SymbolicProblem& problem, const GroundSteps& ground, const GroundGoal& goal,
         const std::set<std::string>& actions) {
    primitives_ = ground.primitives;
    for (const SymbolicObject& o : problem.objects) objects_.push_back(o.name);
    for (const SymbolicLiteral& l : problem.init) init_.push_back(id(l));
    for (size_t i = 0; i < ground.steps.size(); ++i) {
      const SymbolicStep& s = ground.steps[i];
      if (i < primitives_ && !actions.empty() && !actions.count(s.name)) continue;
      Step step{i, ids(s.needs), ids(s.needs_not), ids(s.deletes), ids(s.adds), s.at_once};
      steps_.push_back(std::move(step));
      names_.push_back(s.name);
    }
    std::sort(init_.begin(), init_.end());
    init_.erase(std::unique(init_.begin(), init_.end()), init_.end());
    // The goal's options in interned literals; an option with a positive
    // literal on something that is not an object (a room) is dropped.
    for (size_t o = 0; o < goal.options.size(); ++o) {
      std::vector<Target> targets;
      bool expressible = true;
      for (const LiteralId l : goal.options[o]) {
        const GroundLiteral& literal = goal.literals[l];
        const std::optional<SymbolicLiteral> s = symbolic_literal(problem, literal);
        if (!s) {
          expressible = expressible && literal.negated;
          continue;
        }
        const auto it = ids_.find(*s);
        targets.push_back({it == ids_.end() ? -1 : it->second, literal.negated});
      }
      if (expressible) options_.push_back({o, std::move(targets)});
    }
    keep_relevant();
    // What wakes each step that happens at once: a literal it needs being
    // added. The more specific first (a variant of a rule's step that puts
    // what it makes where the input was, before the one that does not say).
    woken_by_.assign(literals_.size(), {});
    for (size_t i = 0; i < steps_.size(); ++i) {
      if (!steps_[i].at_once) continue;
      for (const int n : steps_[i].needs) woken_by_[n].push_back(i);
    }
    for (std::vector<size_t>& woken : woken_by_) {
      std::stable_sort(woken.begin(), woken.end(),
                       [&](size_t a, size_t b) { return steps_[a].needs.size() > steps_[b].needs.size(); });
    }
    complement_.assign(literals_.size(), -1);
    relaxed_size_ = literals_.size();
    const auto absent = [&](int l) {
      if (complement_[l] < 0) complement_[l] = static_cast<int>(relaxed_size_++);
      return complement_[l];
    };
    for (const size_t r : relevant_) {
      for (const int n : steps_[r].needs_not) absent(n);
    }
    for (const auto& [option, targets] : options_) {
      for (const Target& t : targets) {
        if (t.id >= 0 && t.negated) absent(t.id);
      }
    }
    needed_by_.assign(relaxed_size_, {});
    for (size_t i = 0; i < relevant_.size(); ++i) {
      const Step& s = steps_[relevant_[i]];
      std::vector<int> needs = s.needs, adds = s.adds;
      for (const int n : s.needs_not) needs.push_back(complement_[n]);
      for (const int d : s.deletes) {
        if (complement_[d] >= 0) adds.push_back(complement_[d]);
      }
      for (const int n : needs) needed_by_[n].push_back(i);
      relaxed_needs_.push_back(std::move(needs));
      relaxed_adds_.push_back(std::move(adds));
    }
    // Per literal: what every step adding it needs, and what every one of
    // them deletes.
    forced_needs_.assign(literals_.size(), {});
    forced_deletes_.assign(literals_.size(), {});
    std::vector<char> achieved(literals_.size(), 0);
    const auto intersect = [](std::vector<int>& into, const std::vector<int>& with) {
      std::vector<int> both;
      std::set_intersection(into.begin(), into.end(), with.begin(), with.end(), std::back_inserter(both));
      into = std::move(both);
    };
    for (const size_t r : relevant_) {
      for (const int a : steps_[r].adds) {
        if (!achieved[a]) {
          forced_needs_[a] = steps_[r].needs;
          forced_deletes_[a] = steps_[r].deletes;
          achieved[a] = 1;
        } else {
          intersect(forced_needs_[a], steps_[r].needs);
          intersect(forced_deletes_[a], steps_[r].deletes);
        }
      }
    }
  }

  Plan run(const PlanOptions& o) {
    Plan plan;
    if (options_.empty()) {
      plan.reason = "no option of the goal is on the activity's objects";
      return plan;
    }
    std::vector<size_t> at_start;
    const State start = settle(init_, init_, at_start);
    std::vector<State> states = {start};
    std::vector<std::pair<int, int>> parent = {{-1, -1}};  // node, step
    // Per node: the steps that happened at once on the way in (at the root,
    // what :init sets off).
    std::vector<std::vector<size_t>> fired = {at_start};
    std::unordered_map<State, int, StateHash> seen = {{start, 0}};
    // Two open lists, as Fast Downward's lazy greedy search with preferred
    // operators (Richter and Helmert 2009): every child, and the children by
    // helpful steps (those of the relaxed plan that apply now), taking turns.
    // With one list, a goal with a literal that must first get worse (the
    // fridge opened, to be closed again) left the search expanding every
    // arrangement of the objects at the lowest value. (Fast Downward's boost,
    // extra turns for the helpful list at each new lowest value, planned
    // fewer of BEHAVIOR-1K's activities within the budget when tried.)
    using Entry = std::tuple<double, size_t, int>;  // priority, order, node
    using Open = std::priority_queue<Entry, std::vector<Entry>, std::greater<>>;
    std::array<Open, 2> open;  // all, helpful
    open[0].push({0, 0, 0});
    size_t order = 1, turn = 0;
    bool any_finite = false;
    std::vector<char> expanded;  // per node: expanded (from either list)
    while (!open[0].empty() || !open[1].empty()) {
      size_t which = turn++ % 2;
      if (open[which].empty()) which = 1 - which;
      const int node = std::get<2>(open[which].top());
      open[which].pop();
      expanded.resize(states.size(), 0);
      if (expanded[node]) continue;
      expanded[node] = 1;
      const State state = states[node];
      if (holds(state)) {
        std::vector<int> chosen;
        for (int n = node; n >= 0; n = parent[n].first) {
          if (parent[n].second >= 0) chosen.push_back(parent[n].second);
        }
        std::reverse(chosen.begin(), chosen.end());
        // The way the search found, without the steps it can do without.
        chosen = without_detours(start, std::move(chosen));
        plan.found = true;
        for (const size_t f : at_start) plan.steps.push_back({names_[f], false});
        State now = start;
        for (const int r : chosen) {
          std::vector<size_t> at_once;
          now = settle(apply(now, r), steps_[r].adds, at_once);
          plan.steps.push_back({names_[r], steps_[r].source < primitives_});
          for (const size_t f : at_once) plan.steps.push_back({names_[f], false});
        }
        plan.option = *holds(now);
        return plan;
      }
      if (plan.expansions >= o.max_expansions) {
        plan.reason = "no plan within " + std::to_string(o.max_expansions) + " expansions";
        return plan;
      }
      ++plan.expansions;
      const State estimated = undone_on_the_way(state);
      if (heuristic(estimated) == kInfinity) continue;  // a dead end: no option is reachable from here
      double h = 0;
      std::vector<char> relaxed;
      const std::vector<char> helpful = helpful_steps(estimated, &h, &relaxed);
      if (node == 0) {
        for (size_t k = 0; k < relevant_.size(); ++k) {
          const size_t r = relevant_[k];
          if (relaxed[k] && steps_[r].source < primitives_) plan.relaxed.push_back(names_[r]);
        }
      }
      any_finite = true;
      std::vector<char> in(literals_.size(), 0);
      for (const int l : state) in[l] = 1;
      for (size_t k = 0; k < relevant_.size(); ++k) {
        const size_t r = relevant_[k];
        const Step& s = steps_[r];
        if (s.at_once) continue;
        if (!std::all_of(s.needs.begin(), s.needs.end(), [&](int l) { return in[l]; })) continue;
        if (std::any_of(s.needs_not.begin(), s.needs_not.end(), [&](int l) { return in[l]; })) continue;
        std::vector<size_t> at_once;
        State next = settle(apply(state, static_cast<int>(r)), s.adds, at_once);
        if (seen.count(next)) continue;
        const int child = static_cast<int>(states.size());
        seen.emplace(next, child);
        states.push_back(std::move(next));
        parent.push_back({node, static_cast<int>(r)});
        fired.push_back(std::move(at_once));
        open[0].push({h, order, child});
        if (helpful[k]) open[1].push({h, order, child});
        ++order;
      }
    }
    plan.reason = any_finite
                      ? "the search ran out of states without reaching the goal"
                      : "no sequence of the primitives and the world's steps reaches the goal: " + missing(init_);
    return plan;
  }

 private:
  int id(const SymbolicLiteral& l) {
    const auto [it, added] = ids_.emplace(l, static_cast<int>(literals_.size()));
    if (added) literals_.push_back(l);
    return it->second;
  }
  std::vector<int> ids(const std::vector<SymbolicLiteral>& ls) {
    std::vector<int> out;
    for (const SymbolicLiteral& l : ls) out.push_back(id(l));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  // Greedy action elimination (Nakhost and Mueller 2010): each chosen step
  // in turn left out, with those after it that no longer apply; kept out
  // where the rest still reaches the goal. A greedy search's way wanders
  // (cook_asparagus: 185 primitives, half of them fetching and putting back).
  std::vector<int> without_detours(const State& start, std::vector<int> chosen) const {
    const auto applies = [&](const State& state, int r) {
      const auto has = [&](int l) { return std::binary_search(state.begin(), state.end(), l); };
      return std::all_of(steps_[r].needs.begin(), steps_[r].needs.end(), has) &&
             std::none_of(steps_[r].needs_not.begin(), steps_[r].needs_not.end(), has);
    };
    for (size_t i = 0; i < chosen.size();) {
      std::vector<int> rest;
      State state = start;
      for (size_t j = 0; j < chosen.size(); ++j) {
        if (j == i || !applies(state, chosen[j])) continue;
        std::vector<size_t> at_once;
        state = settle(apply(state, chosen[j]), steps_[chosen[j]].adds, at_once);
        rest.push_back(chosen[j]);
      }
      if (holds(state)) {
        chosen = std::move(rest);
      } else {
        ++i;
      }
    }
    return chosen;
  }

  // `state` after step `r`.
  State apply(const State& state, int r) const {
    const Step& s = steps_[r];
    State next;
    next.reserve(state.size() + s.adds.size());
    for (const int l : state) {
      if (std::find(s.deletes.begin(), s.deletes.end(), l) == s.deletes.end()) next.push_back(l);
    }
    next.insert(next.end(), s.adds.begin(), s.adds.end());
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    return next;
  }

  // `state` once what happens at once has happened: each step woken by a
  // literal `added` (or by one its own effects add) whose conditions hold
  // and that changes the state, in turn, at most kMaxAtOnce of them (a rule
  // fires once: it uses up its inputs). The steps fired go to `fired`.
  State settle(State state, const std::vector<int>& added, std::vector<size_t>& fired) const {
    constexpr size_t kMaxAtOnce = 64;
    std::vector<int> woken_literals = added;
    for (size_t k = 0; k < woken_literals.size() && fired.size() < kMaxAtOnce; ++k) {
      for (const size_t i : woken_by_[woken_literals[k]]) {
        const Step& s = steps_[i];
        const auto has = [&](int l) { return std::binary_search(state.begin(), state.end(), l); };
        if (!std::all_of(s.needs.begin(), s.needs.end(), has) ||
            std::any_of(s.needs_not.begin(), s.needs_not.end(), has))
          continue;
        State next = apply(state, static_cast<int>(i));
        if (next == state) continue;
        state = std::move(next);
        fired.push_back(i);
        woken_literals.insert(woken_literals.end(), s.adds.begin(), s.adds.end());
        if (fired.size() >= kMaxAtOnce) break;
      }
    }
    return state;
  }

  // The option that holds in `state`, if one does.
  std::optional<size_t> holds(const State& state) const {
    for (const auto& [option, targets] : options_) {
      const bool all = std::all_of(targets.begin(), targets.end(), [&](const Target& t) {
        const bool present = t.id >= 0 && std::binary_search(state.begin(), state.end(), t.id);
        return present != t.negated;
      });
      if (all) return option;
    }
    return std::nullopt;
  }

  // Why no option is reachable from `state`, relaxed (what a step needs
  // absent ignored): the option missing the fewest literals, its first
  // missing literal (or one it needs absent that no step can remove), then
  // the need that the step making (removing) it with the fewest missing
  // needs lacks, and so on, as far as kExplainDepth. E.g. make_lemonade's
  // "(real lemonade.n.01_1) needs (contains pitcher.n.02_1
  // granulated_sugar.n.01_1) needs (grasped agent.n.01_1 sugar__sack.n.01_1):
  // no step makes it" (the sack, 35 kg, is too heavy to pick up).
  std::string missing(const State& state) const {
    constexpr int kExplainDepth = 4;
    std::vector<char> reachable(literals_.size(), 0);
    for (const int l : state) reachable[l] = 1;
    for (bool changed = true; changed;) {
      changed = false;
      for (const Step& s : steps_) {
        if (!std::all_of(s.needs.begin(), s.needs.end(), [&](int l) { return reachable[l]; })) continue;
        for (const int a : s.adds) {
          if (!reachable[a]) reachable[a] = changed = true;
        }
      }
    }
    const auto unmet = [&](const std::vector<int>& needs) {
      return std::count_if(needs.begin(), needs.end(), [&](int l) { return !reachable[l]; });
    };
    // A literal the goal needs absent goes only by a step that deletes it.
    const auto removable = [&](int l) {
      return std::any_of(steps_.begin(), steps_.end(), [&](const Step& s) {
        return unmet(s.needs) == 0 && std::find(s.deletes.begin(), s.deletes.end(), l) != s.deletes.end();
      });
    };
    // The option missing the fewest, and its first missing literal that
    // some step or :init names (-1: only ones none names).
    int first = -1;
    bool absent = false;  // the goal needs `first` absent
    long fewest = std::numeric_limits<long>::max();
    for (const auto& [option, targets] : options_) {
      long count = 0;
      int lead = -1;
      bool lead_absent = false;
      for (const Target& t : targets) {
        const bool present = t.id >= 0 && std::binary_search(state.begin(), state.end(), t.id);
        if (t.negated ? !present || removable(t.id) : t.id >= 0 && reachable[t.id]) continue;
        ++count;
        if (lead < 0 && t.id >= 0) lead = t.id, lead_absent = t.negated;
      }
      if (count > 0 && count < fewest) fewest = count, first = lead, absent = lead_absent;
    }
    if (fewest == std::numeric_limits<long>::max()) return "each literal is reachable, not all together";
    if (first < 0) return "the goal names a literal no step or :init has";
    std::string out = absent ? "(not " + text(first) + ")" : text(first);
    std::set<int> told = {first};
    for (int depth = 0, l = first; depth < kExplainDepth; ++depth) {
      const Step* best = nullptr;
      for (const Step& s : steps_) {
        const std::vector<int>& effects = depth == 0 && absent ? s.deletes : s.adds;
        if (std::find(effects.begin(), effects.end(), l) == effects.end()) continue;
        if (!best || unmet(s.needs) < unmet(best->needs)) best = &s;
      }
      if (!best) return out + (depth == 0 && absent ? ": no step removes it" : ": no step makes it");
      const auto need =
          std::find_if(best->needs.begin(), best->needs.end(), [&](int n) { return !reachable[n] && !told.count(n); });
      if (need == best->needs.end()) break;
      l = *need;
      told.insert(l);
      out += " needs " + text(l);
    }
    return out;
  }
  std::string text(int l) const {
    const SymbolicLiteral& literal = literals_[l];
    std::string out = "(" + literal.predicate;
    for (const int a : literal.args) out += " " + objects_[a];
    return out + ")";
  }

  // Steps that can ever apply (their needs reachable from :init, relaxed)
  // and bear on the goal (they add a literal the goal or a kept step needs,
  // or delete one the goal or a kept step needs absent).
  void keep_relevant() {
    std::vector<char> reachable(literals_.size(), 0);
    for (const int l : init_) reachable[l] = 1;
    std::vector<char> usable(steps_.size(), 0);
    for (bool changed = true; changed;) {
      changed = false;
      for (size_t i = 0; i < steps_.size(); ++i) {
        if (usable[i]) continue;
        const Step& s = steps_[i];
        if (!std::all_of(s.needs.begin(), s.needs.end(), [&](int l) { return reachable[l]; })) continue;
        usable[i] = changed = true;
        for (const int a : s.adds) reachable[a] = 1;
      }
    }
    std::vector<char> wanted(literals_.size(), 0), unwanted(literals_.size(), 0);
    for (const auto& [option, targets] : options_) {
      for (const Target& t : targets) {
        if (t.id >= 0) (t.negated ? unwanted : wanted)[t.id] = 1;
      }
    }
    std::vector<char> kept(steps_.size(), 0);
    for (bool changed = true; changed;) {
      changed = false;
      for (size_t i = 0; i < steps_.size(); ++i) {
        if (kept[i] || !usable[i]) continue;
        const Step& s = steps_[i];
        const bool bears = std::any_of(s.adds.begin(), s.adds.end(), [&](int l) { return wanted[l]; }) ||
                           std::any_of(s.deletes.begin(), s.deletes.end(), [&](int l) { return unwanted[l]; });
        if (!bears) continue;
        kept[i] = changed = true;
        for (const int n : s.needs) wanted[n] = 1;
        for (const int n : s.needs_not) unwanted[n] = 1;
      }
    }
    for (size_t i = 0; i < steps_.size(); ++i) {
      if (kept[i]) relevant_.push_back(i);
    }
  }

  // `state` less the goal's literals that hold but must go again on the way
  // to the rest of their option: a literal the option still lacks needs
  // another that does not hold (every step adding it needs it, and so on
  // down), and every step adding that one deletes the literal. The delete
  // relaxation cannot see it: with the kabobs in the tupperware on the table,
  // the tupperware still to go into the fridge must be picked up, which
  // leaves them behind; the heuristic counts them as still to be put in,
  // so that the search puts the tupperware away first.
  State undone_on_the_way(const State& state) const {
    std::vector<char> in(literals_.size(), 0), undone(literals_.size(), 0);
    for (const int l : state) in[l] = 1;
    bool any = false;
    for (const auto& [option, targets] : options_) {
      std::vector<char> wanted(literals_.size(), 0);
      for (const Target& t : targets) {
        if (t.id >= 0 && !t.negated && in[t.id]) wanted[t.id] = 1;
      }
      // What the missing literals force, walked once for them all (what one
      // forces undoes the same whichever literal led to it).
      std::vector<char> forced(literals_.size(), 0);
      std::vector<int> todo;
      for (const Target& t : targets) {
        if (t.id >= 0 && !t.negated && !in[t.id] && !forced[t.id]) forced[t.id] = 1, todo.push_back(t.id);
      }
      while (!todo.empty()) {
        const int f = todo.back();
        todo.pop_back();
        for (const int d : forced_deletes_[f]) {
          if (wanted[d]) undone[d] = 1, any = true;
        }
        for (const int n : forced_needs_[f]) {
          if (!in[n] && !forced[n]) forced[n] = 1, todo.push_back(n);
        }
      }
    }
    if (!any) return state;
    State out;
    for (const int l : state) {
      if (!undone[l]) out.push_back(l);
    }
    return out;
  }

  // h_add to the cheapest option: each literal's cost is that of the
  // cheapest step adding it, a step's 1 plus the sum of its needs' costs
  // (generalised Dijkstra). A literal a step needs absent, or the goal does,
  // has a complement that holds where it does not and that the steps
  // deleting it add (the relaxation keeps it: a tupperware in the closed
  // fridge is reached by opening the fridge, not as if it stood outside).
  double heuristic(const State& state) {
    cost_.assign(relaxed_size_, kInfinity);
    step_cost_.assign(relevant_.size(), kInfinity);
    remaining_.resize(relevant_.size());
    sum_.assign(relevant_.size(), 0.0);
    supporter_.assign(relaxed_size_, -1);
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    const auto reach = [&](size_t i) {
      step_cost_[i] = 1 + sum_[i];
      for (const int a : relaxed_adds_[i]) {
        if (step_cost_[i] < cost_[a]) {
          cost_[a] = step_cost_[i];
          supporter_[a] = static_cast<int>(i);
          queue.push({cost_[a], a});
        }
      }
    };
    const std::vector<char> in = relaxed_state(state);
    for (size_t l = 0; l < relaxed_size_; ++l) {
      if (!in[l]) continue;
      cost_[l] = 0;
      queue.push({0, static_cast<int>(l)});
    }
    for (size_t i = 0; i < relevant_.size(); ++i) {
      remaining_[i] = relaxed_needs_[i].size();
      if (remaining_[i] == 0) reach(i);
    }
    while (!queue.empty()) {
      const auto [c, l] = queue.top();
      queue.pop();
      if (c > cost_[l]) continue;
      for (const size_t i : needed_by_[l]) {
        sum_[i] += c;
        if (--remaining_[i] == 0) reach(i);
      }
    }
    double best = kInfinity;
    best_option_ = 0;
    for (size_t o = 0; o < options_.size(); ++o) {
      double h = 0;
      for (const Target& t : options_[o].second) {
        h += t.id < 0 ? (t.negated ? 0 : kInfinity) : cost_[t.negated ? complement_[t.id] : t.id];
        if (h >= best) break;
      }
      if (h < best) best = h, best_option_ = o;
    }
    return best;
  }

  // Over literals and their complements: which hold in `state`.
  std::vector<char> relaxed_state(const State& state) const {
    std::vector<char> in(relaxed_size_, 0);
    for (const int l : state) in[l] = 1;
    for (size_t l = 0; l < complement_.size(); ++l) {
      if (complement_[l] >= 0) in[complement_[l]] = !in[l];
    }
    return in;
  }

  // After heuristic(state): the relevant steps (by index into relevant_) of
  // the relaxed plan to its cheapest option that apply in `state`, the plan
  // read back from each literal's cheapest supporter (Hoffmann and Nebel's
  // helpful actions, over h_add's supporters); `length`, its number of
  // steps (h_FF); `relaxed_plan`, its steps.
  std::vector<char> helpful_steps(const State& state, double* length = nullptr,
                                  std::vector<char>* relaxed_plan = nullptr) const {
    const std::vector<char> in = relaxed_state(state);
    std::vector<char> marked(relaxed_size_, 0), in_plan(relevant_.size(), 0);
    std::vector<int> todo;
    const auto want = [&](int l) {
      if (!in[l] && !marked[l]) marked[l] = 1, todo.push_back(l);
    };
    for (const Target& t : options_[best_option_].second) {
      if (t.id >= 0) want(t.negated ? complement_[t.id] : t.id);
    }
    while (!todo.empty()) {
      const int l = todo.back();
      todo.pop_back();
      const int i = supporter_[l];
      if (i < 0 || in_plan[i]) continue;
      in_plan[i] = 1;
      for (const int n : relaxed_needs_[i]) want(n);
    }
    std::vector<char> helpful(relevant_.size(), 0);
    if (length) *length = static_cast<double>(std::count(in_plan.begin(), in_plan.end(), 1));
    if (relaxed_plan) *relaxed_plan = in_plan;
    for (size_t i = 0; i < relevant_.size(); ++i) {
      helpful[i] =
          in_plan[i] && std::all_of(relaxed_needs_[i].begin(), relaxed_needs_[i].end(), [&](int l) { return in[l]; });
    }
    return helpful;
  }

  std::map<SymbolicLiteral, int> ids_;
  std::vector<SymbolicLiteral> literals_;
  std::vector<std::vector<size_t>> woken_by_;  // literal -> steps that happen at once, into steps_
  std::vector<Step> steps_;
  std::vector<std::string> names_;
  std::vector<std::string> objects_;  // the problem's, by index
  size_t primitives_ = 0;
  State init_;
  std::vector<std::pair<size_t, std::vector<Target>>> options_;
  std::vector<size_t> relevant_;  // indices into steps_
  std::vector<int> complement_;   // literal -> its complement in the relaxation (holds where it does not), or -1
  size_t relaxed_size_ = 0;       // literals and complements
  std::vector<std::vector<int>> relaxed_needs_, relaxed_adds_;  // per index into relevant_
  std::vector<std::vector<size_t>> needed_by_;                  // relaxed literal -> indices into relevant_
  std::vector<double> cost_, step_cost_, sum_;                  // the heuristic's
  std::vector<size_t> remaining_;
  std::vector<std::vector<int>> forced_needs_;    // literal -> what every relevant step adding it needs
  std::vector<std::vector<int>> forced_deletes_;  // literal -> what every relevant step adding it deletes
  std::vector<int> supporter_;                    // literal -> the relevant step that reaches it cheapest, or -1
  size_t best_option_ = 0;                        // index into options_ of heuristic()'s cheapest
};

}  // namespace

size_t Plan::primitives() const {
  return static_cast<size_t>(std::count_if(steps.begin(), steps.end(), [](const PlanStep& s) { return s.primitive; }));
}

Plan plan_task(const SymbolicProblem& problem, const GroundGoal& goal, const PlanOptions& options) {
  return plan_task(problem, ground_steps(problem), goal, options);
}

Plan plan_task(const SymbolicProblem& problem, const GroundSteps& steps, const GroundGoal& goal,
               const PlanOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  Search search(problem, steps, goal, options.actions);
  Plan plan = search.run(options);
  plan.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return plan;
}

}  // namespace chore
