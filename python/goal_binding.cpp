#include "python/goal_binding.hpp"

#include <pybind11/stl.h>

#include <set>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "tasks/activity_check.hpp"
#include "tasks/vocabulary.hpp"

namespace chore::python {
namespace {

namespace py = pybind11;

const Vocabulary& vocabulary() {
  static const Vocabulary v = load_vocabulary();  // each dialect's knowledge base, loaded once
  return v;
}

// bddl's shape of a ground literal: ["ontop", "a", "b"] or ["not", ["ontop", "a", "b"]] (as tuples).
py::tuple literal_tuple(const GroundLiteral& l) {
  py::tuple atom(1 + l.args.size());
  atom[0] = l.predicate;
  for (size_t i = 0; i < l.args.size(); ++i) atom[i + 1] = l.args[i];
  return l.negated ? py::make_tuple("not", atom) : atom;
}

// An atom (predicate, arg, ...) of strings; chore.Error naming its position otherwise.
Literal atom_literal(const py::handle& item, size_t index) {
  const std::string where = "Goal.score: true_atoms[" + std::to_string(index) + "]";
  if (!py::isinstance<py::tuple>(item) && !py::isinstance<py::list>(item)) {
    throw Error(where + ": expected a tuple (predicate, object, ...), got " + std::string(py::str(item.get_type())));
  }
  const py::sequence seq = py::reinterpret_borrow<py::sequence>(item);
  if (seq.size() < 2) throw Error(where + ": expected a predicate and at least one object");
  Literal l;
  for (size_t i = 0; i < seq.size(); ++i) {
    if (!py::isinstance<py::str>(seq[i])) throw Error(where + "[" + std::to_string(i) + "]: expected a str");
    (i == 0 ? l.predicate : l.args.emplace_back()) = seq[i].cast<std::string>();
  }
  return l;
}

py::dict score_dict(const GroundGoal& goal, const py::iterable& true_atoms) {
  std::set<Literal> atoms;
  size_t index = 0;
  for (const py::handle item : true_atoms) atoms.insert(atom_literal(item, index++));
  const Score s = score(goal, [&](const GroundLiteral& l) {
    Literal atom = l;
    atom.negated = false;
    return atoms.contains(atom) != l.negated;
  });
  py::dict d;
  d["success"] = s.success;
  d["q"] = s.q;
  d["satisfied"] = s.satisfied;
  d["total"] = s.total;
  d["condition_holds"] = s.condition_holds;
  d["best_option"] = s.best_option ? py::object(py::int_(*s.best_option)) : py::object(py::none());
  return d;
}

}  // namespace

void bind_goal(py::module_& m) {
  py::class_<CheckedActivity>(m, "Goal", R"doc(A BDDL file's goal as `chore activity check` reads it.

Goal(path) parses the file against its dialect, grounds the goal with the
knowledge base and checks the agent's roles and the states :init sets;
chore.Error names the file, line and column otherwise. `literals` are the
distinct ground literals in bddl's shapes (("ontop", "a", "b"), or
("not", ("open", "c"))); `options` the goal's ground options as indices into
`literals`, shortest first. score(true_atoms) evaluates the goal where exactly
the given atoms hold.)doc")
      .def(py::init([](const std::string& path) { return check_activity(path, vocabulary()); }), py::arg("path"))
      .def_property_readonly("activity", [](const CheckedActivity& a) { return a.problem.name; })
      .def_property_readonly("domain",
                             [](const CheckedActivity& a) { return std::string(to_string(a.problem.domain)); })
      .def_property_readonly("objects",
                             [](const CheckedActivity& a) {
                               py::list objects;
                               for (const ObjectDecl& o : a.problem.objects)
                                 objects.append(py::make_tuple(o.name, o.type));
                               return objects;
                             })
      .def_property_readonly("conditions", [](const CheckedActivity& a) { return a.goal.conditions.size(); })
      .def_property_readonly("literals",
                             [](const CheckedActivity& a) {
                               py::list literals;
                               for (const GroundLiteral& l : a.goal.literals) literals.append(literal_tuple(l));
                               return literals;
                             })
      .def_property_readonly("options", [](const CheckedActivity& a) { return a.goal.options; })
      .def(
          "score", [](const CheckedActivity& a, const py::iterable& atoms) { return score_dict(a.goal, atoms); },
          py::arg("true_atoms"),
          "success, q (the best fraction of an option's literals satisfied), satisfied and total of that option, "
          "condition_holds per top-level condition, best_option; every atom not given is false");
}

}  // namespace chore::python
