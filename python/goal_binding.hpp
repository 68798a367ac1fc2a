// chore.Goal: a BDDL file's goal as chore reads it (tasks/activity_check.hpp),
// for tools and for checking chore against BEHAVIOR's own bddl package:
// its ground literals and options in bddl's shapes, and its score on a set of
// true atoms.
#pragma once

#include <pybind11/pybind11.h>

namespace chore::python {

void bind_goal(pybind11::module_& m);

}  // namespace chore::python
