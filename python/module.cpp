// chore's Python extension (_chore): Env and VectorEnv over the C++ ones,
// observations as NumPy arrays that view chore's buffers (no copy), the GIL
// released while envs work, chore::Error raised as chore.Error. The package
// around it (python/chore/) gives them Gymnasium's shape.
#include <mujoco/mujoco.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <unistd.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "env/env.hpp"
#include "env/primitive_actions.hpp"
#include "env/vector_env.hpp"
#include "python/convert.hpp"
#include "python/goal_binding.hpp"

namespace py = pybind11;

namespace chore {
namespace {

using namespace python;

// Who may call an env: the process that made it, one thread at a time. A
// child of fork() holds a copy of the parent's env whose worker threads and
// EGL context are not in the child: a call there is chore.Error, and close()
// and the destructor leave its memory to the process's end rather than join
// threads that do not exist. A second thread calling while one is inside is
// chore.Error rather than two threads inside MuJoCo; one after the other, any
// thread may call (Env::release_thread after each).
class CallGuard {
 public:
  explicit CallGuard(std::string what) : what_(std::move(what)), pid_(::getpid()) {}
  bool forked() const { return ::getpid() != pid_; }
  // Held for the call (taken with the GIL held, never waiting).
  std::unique_lock<std::mutex> enter() {
    if (forked()) {
      throw Error(what_ + ": made in process " + std::to_string(pid_) + " before a fork; make a new one in process " +
                  std::to_string(::getpid()));
    }
    std::unique_lock<std::mutex> lock(busy_, std::try_to_lock);
    if (!lock) {
      throw Error(what_ +
                  ": in use by another thread; it serves one call at a time (chore.VectorEnv steps envs in "
                  "parallel)");
    }
    return lock;
  }
  // The guarded env's close(); in a forked child its memory is left to the process's end.
  template <class Envs>
  void close(std::unique_ptr<Envs>& envs) {
    if (forked()) {
      (void)envs.release();
      return;
    }
    const auto in_call = enter();
    envs->close();
  }
  // For the destructor: the parent's env is the parent's to free.
  template <class Envs>
  void leave_if_forked(std::unique_ptr<Envs>& envs) {
    if (forked()) (void)envs.release();
  }

 private:
  std::string what_;
  pid_t pid_;
  std::mutex busy_;
};

// ---- Env ----

// The next call may come from another thread, whether this one returns or throws.
struct ReleaseThread {
  Env& env;
  ~ReleaseThread() { env.release_thread(); }
};

class PyEnv {
 public:
  explicit PyEnv(const py::dict& config) : env_(std::make_unique<Env>(env_config(config))) {}
  ~PyEnv() { guard_.leave_if_forked(env_); }

  py::tuple reset(py::object self, std::optional<uint64_t> seed) {
    const auto in_call = guard_.enter();
    std::optional<Env::ResetResult> r;
    {
      Env& e = env();
      py::gil_scoped_release release;
      const ReleaseThread after{e};
      r.emplace(e.reset(seed));
    }
    return py::make_tuple(observation_views(r->obs, self, true), info_dict(r->info));
  }

  py::tuple step(py::object self, const py::handle& action) {
    const auto in_call = guard_.enter();
    const std::vector<float> values = action_values(action, env().action_space().element_count(), "step");
    std::optional<Env::StepResult> r;
    {
      Env& e = env();
      py::gil_scoped_release release;
      const ReleaseThread after{e};
      r.emplace(e.step(values));
    }
    return py::make_tuple(observation_views(r->obs, self, true), r->reward, r->terminated, r->truncated,
                          info_dict(r->info));
  }

  Env& env() {
    if (!env_ || env_->closed()) throw Error("env: closed");
    return *env_;
  }
  void close() { guard_.close(env_); }

 private:
  std::unique_ptr<Env> env_;
  CallGuard guard_{"chore.Env"};
};

std::vector<std::string> primitive_names(const std::vector<PrimitiveAction>& actions) {
  std::vector<std::string> names;
  for (const PrimitiveAction& a : actions) names.push_back(to_string(a));
  return names;
}

// ---- VectorEnv ----

class PyVectorEnv {
 public:
  PyVectorEnv(const py::dict& config, int num_envs, int num_threads, int batch_size, const std::string& autoreset,
              const std::string& rendering) {
    VectorEnvConfig c;
    c.env = env_config(config);
    c.num_envs = num_envs;
    c.num_threads = num_threads;
    c.batch_size = batch_size;
    if (autoreset != "next_step" && autoreset != "same_step")
      throw Error("autoreset_mode '" + autoreset + "': expected next_step or same_step");
    c.autoreset = autoreset == "same_step" ? AutoReset::same_step : AutoReset::next_step;
    if (rendering != "per_thread" && rendering != "batch")
      throw Error("rendering '" + rendering + "': expected per_thread or batch");
    c.rendering = rendering == "batch" ? Rendering::batch : Rendering::per_thread;
    py::gil_scoped_release release;  // building envs compiles scenes
    envs_ = std::make_unique<VectorEnv>(c);
    action_size_ = envs_->single_action_space().element_count();
  }
  ~PyVectorEnv() { guard_.leave_if_forked(envs_); }

  // One seed per env (None: its stream continues); the package turns
  // Gymnasium's seed=int (env i: seed + i) and seed=None into this.
  py::tuple reset(py::object self, const std::vector<std::optional<uint64_t>>& seeds) {
    const auto in_call = guard_.enter();
    std::optional<Batch> b;
    {
      py::gil_scoped_release release;
      b.emplace(envs_->reset(seeds));
    }
    return py::make_tuple(observation_views(*b->obs, self, false), info_arrays(b->infos));
  }

  py::tuple step(py::object self, const py::handle& actions) {
    const auto in_call = guard_.enter();
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
    const auto in_call = guard_.enter();
    const auto ids = py::array_t<int, py::array::c_style | py::array::forcecast>::ensure(env_ids);
    if (!ids || ids.ndim() != 1) throw Error("send: env_ids: expected a list of env ids");
    const std::vector<int> id_values(ids.data(), ids.data() + ids.size());
    const std::vector<float> values = action_values(actions, action_size_ * id_values.size(), "send");
    py::gil_scoped_release release;
    envs_->send(values, id_values);
  }

  py::tuple recv(py::object self) {
    const auto in_call = guard_.enter();
    std::optional<Batch> b;
    {
      py::gil_scoped_release release;
      b.emplace(envs_->recv());
    }
    return results(self, *b);
  }

  VectorEnv& envs() {
    if (!envs_) throw Error("chore.VectorEnv: closed");
    return *envs_;
  }
  void close() { guard_.close(envs_); }

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
  CallGuard guard_{"chore.VectorEnv"};
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
  python::bind_goal(m);

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
      .def(py::init<const py::dict&, int, int, int, const std::string&, const std::string&>(), py::arg("config"),
           py::arg("num_envs"), py::arg("num_threads"), py::arg("batch_size"), py::arg("autoreset_mode"),
           py::arg("rendering"))
      .def(
          "reset",
          [](py::object self, const std::vector<std::optional<uint64_t>>& seeds) {
            return self.cast<PyVectorEnv&>().reset(self, seeds);
          },
          py::arg("seeds"))
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
      .def("close", &PyVectorEnv::close);
}
