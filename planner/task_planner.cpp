#include "planner/task_planner.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>
#include <queue>
#include <unordered_map>

#include "planner/reachability.hpp"

namespace chore {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A step over interned literals.
struct Step {
  size_t source;  // index into GroundSteps::steps
  std::vector<int> needs, needs_not, deletes, adds;
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
    for (const SymbolicLiteral& l : problem.init) init_.push_back(id(l));
    for (size_t i = 0; i < ground.steps.size(); ++i) {
      const SymbolicStep& s = ground.steps[i];
      if (i < primitives_ && !actions.empty() && !actions.count(s.name)) continue;
      Step step{i, ids(s.needs), ids(s.needs_not), ids(s.deletes), ids(s.adds)};
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
    for (size_t i = 0; i < relevant_.size(); ++i) {
      for (const int n : steps_[relevant_[i]].needs) needed_by_[n].push_back(i);
      for (const int d : steps_[relevant_[i]].deletes) deleted_by_[d].push_back(i);
    }
  }

  Plan run(const PlanOptions& o) {
    Plan plan;
    if (options_.empty()) {
      plan.reason = "no option of the goal is on the activity's objects";
      return plan;
    }
    std::vector<State> states = {init_};
    std::vector<std::pair<int, int>> parent = {{-1, -1}};  // node, step
    std::unordered_map<State, int, StateHash> seen = {{init_, 0}};
    using Entry = std::tuple<double, size_t, int>;  // priority, order, node
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
    open.push({0, 0, 0});
    size_t order = 1;
    bool any_finite = false;
    while (!open.empty()) {
      const int node = std::get<2>(open.top());
      open.pop();
      const State state = states[node];
      if (const std::optional<size_t> reached = holds(state)) {
        plan.found = true;
        plan.option = *reached;
        for (int n = node; parent[n].first >= 0; n = parent[n].first) {
          const int s = parent[n].second;
          plan.steps.push_back({names_[s], steps_[s].source < primitives_});
        }
        std::reverse(plan.steps.begin(), plan.steps.end());
        return plan;
      }
      if (plan.expansions >= o.max_expansions) {
        plan.reason = "no plan within " + std::to_string(o.max_expansions) + " expansions";
        return plan;
      }
      ++plan.expansions;
      const double h = heuristic(state);
      if (h == kInfinity) continue;  // a dead end: no option is reachable from here
      any_finite = true;
      std::vector<char> in(literals_.size(), 0);
      for (const int l : state) in[l] = 1;
      for (const size_t r : relevant_) {
        const Step& s = steps_[r];
        if (!std::all_of(s.needs.begin(), s.needs.end(), [&](int l) { return in[l]; })) continue;
        if (std::any_of(s.needs_not.begin(), s.needs_not.end(), [&](int l) { return in[l]; })) continue;
        State next;
        next.reserve(state.size() + s.adds.size());
        for (const int l : state) {
          if (std::find(s.deletes.begin(), s.deletes.end(), l) == s.deletes.end()) next.push_back(l);
        }
        next.insert(next.end(), s.adds.begin(), s.adds.end());
        std::sort(next.begin(), next.end());
        next.erase(std::unique(next.begin(), next.end()), next.end());
        if (seen.count(next)) continue;
        const int child = static_cast<int>(states.size());
        seen.emplace(next, child);
        states.push_back(std::move(next));
        parent.push_back({node, static_cast<int>(r)});
        open.push({h, order++, child});
      }
    }
    plan.reason = any_finite ? "the search ran out of states without reaching the goal"
                             : "no sequence of the primitives and the world's steps reaches the goal";
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
    needed_by_.assign(literals_.size(), {});
    deleted_by_.assign(literals_.size(), {});
  }

  // h_add to the cheapest option: each literal's cost is that of the
  // cheapest step adding it, a step's 1 plus the sum of its needs' costs
  // (generalised Dijkstra); a negated literal that holds costs the cheapest
  // step deleting it.
  double heuristic(const State& state) {
    cost_.assign(literals_.size(), kInfinity);
    step_cost_.assign(relevant_.size(), kInfinity);
    remaining_.resize(relevant_.size());
    sum_.assign(relevant_.size(), 0.0);
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    const auto reach = [&](size_t i) {
      step_cost_[i] = 1 + sum_[i];
      for (const int a : steps_[relevant_[i]].adds) {
        if (step_cost_[i] < cost_[a]) {
          cost_[a] = step_cost_[i];
          queue.push({cost_[a], a});
        }
      }
    };
    for (const int l : state) {
      cost_[l] = 0;
      queue.push({0, l});
    }
    for (size_t i = 0; i < relevant_.size(); ++i) {
      remaining_[i] = steps_[relevant_[i]].needs.size();
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
    for (const auto& [option, targets] : options_) {
      double h = 0;
      for (const Target& t : targets) {
        const bool present = t.id >= 0 && std::binary_search(state.begin(), state.end(), t.id);
        if (!t.negated) {
          h += t.id >= 0 ? cost_[t.id] : kInfinity;
        } else if (present) {
          double remove = kInfinity;
          for (const size_t i : deleted_by_[t.id]) remove = std::min(remove, step_cost_[i]);
          h += remove;
        }
        if (h >= best) break;
      }
      best = std::min(best, h);
    }
    return best;
  }

  std::map<SymbolicLiteral, int> ids_;
  std::vector<SymbolicLiteral> literals_;
  std::vector<Step> steps_;
  std::vector<std::string> names_;
  size_t primitives_ = 0;
  State init_;
  std::vector<std::pair<size_t, std::vector<Target>>> options_;
  std::vector<size_t> relevant_;                // indices into steps_
  std::vector<std::vector<size_t>> needed_by_;  // literal -> indices into relevant_
  std::vector<std::vector<size_t>> deleted_by_;  // literal -> indices into relevant_
  std::vector<double> cost_, step_cost_, sum_;  // the heuristic's
  std::vector<size_t> remaining_;
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
