// chore's Python extension (_chore): Env and VectorEnv over the C++ ones,
// observations as NumPy arrays that view chore's buffers (no copy), the GIL
// released while envs work, chore::Error raised as chore.Error. The package
// around it (python/chore/) gives them Gymnasium's shape.
#include <mujoco/mujoco.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "env/env.hpp"
#include "env/primitive_actions.hpp"
#include "env/vector_env.hpp"
#include "python/convert.hpp"

namespace py = pybind11;

namespace chore {
namespace {

using namespace python;

// ---- Env ----

class PyEnv {
 public:
  explicit PyEnv(const py::dict& config) : env_(std::make_unique<Env>(env_config(config))) {}

  py::tuple reset(py::object self, std::optional<uint64_t> seed) {
    std::optional<Env::ResetResult> r;
    {
      py::gil_scoped_release release;
      r.emplace(env().reset(seed));
    }
    return py::make_tuple(observation_views(r->obs, self, true), info_dict(r->info));
  }

  py::tuple step(py::object self, const py::handle& action) {
    const std::vector<float> values = action_values(action, env().action_space().element_count(), "step");
    std::optional<Env::StepResult> r;
    {
      py::gil_scoped_release release;
      r.emplace(env().step(values));
    }
    return py::make_tuple(observation_views(r->obs, self, true), r->reward, r->terminated, r->truncated,
                          info_dict(r->info));
  }

  Env& env() {
    if (env_->closed()) throw Error("env: closed");
    return *env_;
  }
  void close() { env_->close(); }

 private:
  std::unique_ptr<Env> env_;
};

std::vector<std::string> primitive_names(const std::vector<PrimitiveAction>& actions) {
  std::vector<std::string> names;
  for (const PrimitiveAction& a : actions) names.push_back(to_string(a));
  return names;
}

// ---- VectorEnv ----

class PyVectorEnv {
 public:
  PyVectorEnv(const py::dict& config, int num_envs, int num_threads, int batch_size, const std::string& autoreset) {
    VectorEnvConfig c;
    c.env = env_config(config);
    c.num_envs = num_envs;
    c.num_threads = num_threads;
    c.batch_size = batch_size;
    if (autoreset != "next_step" && autoreset != "same_step")
      throw Error("autoreset_mode '" + autoreset + "': expected next_step or same_step");
    c.autoreset = autoreset == "same_step" ? AutoReset::same_step : AutoReset::next_step;
    py::gil_scoped_release release;  // building envs compiles scenes
    envs_ = std::make_unique<VectorEnv>(c);
    action_size_ = envs_->single_action_space().element_count();
  }

  py::tuple reset(py::object self, std::optional<uint64_t> seed) {
    std::optional<Batch> b;
    {
      py::gil_scoped_release release;
      b.emplace(envs_->reset(seed));
    }
    return py::make_tuple(observation_views(*b->obs, self, false), info_arrays(b->infos));
  }

  py::tuple step(py::object self, const py::handle& actions) {
    const std::vector<float> values =
        action_values(actions, action_size_ * static_cast<size_t>(envs_->num_envs()), "step");
    std::optional<Batch> b;
    {
      py::gil_scoped_release release;
      b.emplace(envs_->step(values));
    }
    return results(self, *b);
  }

  void send(const py::handle& actions, const py::handle& env_ids) {
    const auto ids = py::array_t<int, py::array::c_style | py::array::forcecast>::ensure(env_ids);
    if (!ids || ids.ndim() != 1) throw Error("send: env_ids: expected a list of env ids");
    const std::vector<int> id_values(ids.data(), ids.data() + ids.size());
    const std::vector<float> values = action_values(actions, action_size_ * id_values.size(), "send");
    py::gil_scoped_release release;
    envs_->send(values, id_values);
  }

  py::tuple recv(py::object self) {
    std::optional<Batch> b;
    {
      py::gil_scoped_release release;
      b.emplace(envs_->recv());
    }
    return results(self, *b);
  }

  VectorEnv& envs() { return *envs_; }

 private:
  // (obs, rewards, terminated, truncated, info): views of the batch; info's
  // arrays are made (small), with same_step's final_obs and final_info.
  py::tuple results(const py::handle& self, const Batch& b) {
    const auto n = static_cast<py::ssize_t>(b.size());
    py::dict info = info_arrays(b.infos);
    if (b.final_obs) {
      info["final_obs"] = observation_views(*b.final_obs, self, false);
      info["final_info"] = info_arrays(b.final_infos);
    }
    return py::make_tuple(observation_views(*b.obs, self, false),
                          view(py::dtype::of<float>(), {n}, b.rewards.data(), self),
                          view(py::dtype::of<bool>(), {n}, b.terminated.data(), self),
                          view(py::dtype::of<bool>(), {n}, b.truncated.data(), self), info);
  }

  std::unique_ptr<VectorEnv> envs_;
  size_t action_size_ = 0;
};

}  // namespace
}  // namespace chore

PYBIND11_MODULE(_chore, m) {
  using namespace chore;
  m.doc() = "chore's C++ environments (the chore package wraps them in Gymnasium's API)";
  py::register_exception<Error>(m, "Error");
  // The MuJoCo the environments run on (the C library chore is built against,
  // whatever `import mujoco` in the same process gives).
  m.attr("mujoco_version") = mj_versionString();

  py::class_<PyEnv>(m, "Env")
      .def(py::init<const py::dict&>(), py::arg("config"))
      .def(
          "reset", [](py::object self, std::optional<uint64_t> seed) { return self.cast<PyEnv&>().reset(self, seed); },
          py::arg("seed") = py::none())
      .def("step", [](py::object self, const py::handle& a) { return self.cast<PyEnv&>().step(self, a); })
      .def_property_readonly("observation_space", [](PyEnv& e) { return describe(e.env().observation_space()); })
      .def_property_readonly("action_space", [](PyEnv& e) { return describe(e.env().action_space()); })
      .def_property_readonly("primitive_actions", [](PyEnv& e) { return primitive_names(e.env().primitive_actions()); })
      .def("close", &PyEnv::close);

  py::class_<PyVectorEnv>(m, "VectorEnv")
      .def(py::init<const py::dict&, int, int, int, const std::string&>(), py::arg("config"), py::arg("num_envs"),
           py::arg("num_threads"), py::arg("batch_size"), py::arg("autoreset_mode"))
      .def(
          "reset",
          [](py::object self, std::optional<uint64_t> seed) { return self.cast<PyVectorEnv&>().reset(self, seed); },
          py::arg("seed") = py::none())
      .def("step", [](py::object self, const py::handle& a) { return self.cast<PyVectorEnv&>().step(self, a); })
      .def("send", &PyVectorEnv::send, py::arg("actions"), py::arg("env_ids"))
      .def("recv", [](py::object self) { return self.cast<PyVectorEnv&>().recv(self); })
      .def_property_readonly("num_envs", [](PyVectorEnv& v) { return v.envs().num_envs(); })
      .def_property_readonly("batch_size", [](PyVectorEnv& v) { return v.envs().batch_size(); })
      .def_property_readonly("single_observation_space",
                             [](PyVectorEnv& v) { return describe(v.envs().single_observation_space()); })
      .def_property_readonly("single_action_space",
                             [](PyVectorEnv& v) { return describe(v.envs().single_action_space()); })
      .def_property_readonly("primitive_actions",
                             [](PyVectorEnv& v) { return primitive_names(v.envs().state(0).primitive_actions()); })
      .def("close", [](PyVectorEnv& v) { v.envs().close(); });
}
