// What both of chore's Python extensions convert between Python and C++:
// env configs from dicts, spaces as plain dicts (the package makes
// gymnasium.spaces of them), observations as read-only NumPy views of
// chore's buffers, infos as dicts, actions as float32 values.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <span>
#include <string>
#include <vector>

#include "env/env.hpp"

namespace chore::python {

namespace py = pybind11;

// EnvConfig's fields from a dict; chore::Error for an unknown key or a bad value.
EnvConfig env_config(const py::dict& d);
py::object describe(const Space& s);
// Observations: one read-only array per field that keeps `owner` alive;
// `drop_batch` for a single env's (a batch of one).
py::dict observation_views(const ArrayDict& obs, const py::handle& owner, bool drop_batch);
py::array view(const py::dtype& dtype, std::vector<py::ssize_t> shape, const void* data, const py::handle& owner);
py::dict info_dict(const Info& info);
py::dict info_arrays(std::span<const Info> infos);  // Gymnasium's vector info: an array per field
// An action as float32 values, `size` of them; chore::Error naming `what` otherwise.
std::vector<float> action_values(const py::handle& action, size_t size, const std::string& what);

}  // namespace chore::python
