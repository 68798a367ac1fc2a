// chore's Python extension (_chore): Env and VectorEnv over the C++ ones,
// observations as NumPy arrays that view chore's buffers (no copy), the GIL
// released while envs work, chore::Error raised as chore.Error. The package
// around it (python/chore/) gives them Gymnasium's shape.
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

namespace py = pybind11;

namespace chore {
namespace {

// ---- configs: a dict of EnvConfig's fields, each checked ----

EnvConfig env_config(const py::dict& d) {
  EnvConfig c;
  const auto text = [](const py::handle& v, const std::string& key) {
    if (!py::isinstance<py::str>(v)) throw Error("config '" + key + "': expected a string");
    return v.cast<std::string>();
  };
  const auto integer = [](const py::handle& v, const std::string& key, long lo, long hi) {
    if (!py::isinstance<py::int_>(v) || py::isinstance<py::bool_>(v))
      throw Error("config '" + key + "': expected an integer");
    const long long n = v.cast<long long>();
    if (n < lo || n > hi) {
      throw Error("config '" + key + "' = " + std::to_string(n) + ": expected " + std::to_string(lo) + ".." +
                  std::to_string(hi));
    }
    return static_cast<int>(n);
  };
  const auto flag = [](const py::handle& v, const std::string& key) {
    if (!py::isinstance<py::bool_>(v)) throw Error("config '" + key + "': expected True or False");
    return v.cast<bool>();
  };
  for (const auto& [k, v] : d) {
    if (!py::isinstance<py::str>(k)) throw Error("config: keys must be strings");
    const std::string key = k.cast<std::string>();
    if (key == "activity") {
      c.activity = text(v, key);
    } else if (key == "scene") {
      c.scene = text(v, key);
    } else if (key == "width") {
      c.width = integer(v, key, 8, 4096);
    } else if (key == "height") {
      c.height = integer(v, key, 8, 4096);
    } else if (key == "observations") {
      if (!py::isinstance<py::list>(v) && !py::isinstance<py::tuple>(v))
        throw Error("config 'observations': expected a list of names");
      c.observations.clear();
      for (const py::handle& o : v) c.observations.push_back(text(o, key));
    } else if (key == "action_space") {
      c.action_space = text(v, key);
    } else if (key == "mode") {
      c.primitive_mode = parse_execution_mode(text(v, key));
    } else if (key == "max_episode_steps") {
      c.max_episode_steps = integer(v, key, 1, 1 << 30);
    } else if (key == "reward") {
      c.reward = text(v, key);
    } else if (key == "reachable_instances") {
      c.reachable_instances = flag(v, key);
    } else if (key == "robot") {
      c.robot = flag(v, key);
    } else if (key == "object_states") {
      c.object_states = flag(v, key);
    } else if (key == "cloth") {
      c.cloth = flag(v, key);
    } else {
      throw Error("config: unknown key '" + key +
                  "' (known: activity, scene, width, height, observations, action_space, mode, "
                  "max_episode_steps, reward, reachable_instances, robot, object_states, cloth)");
    }
  }
  return c;
}

// ---- spaces: plain dicts the package turns into gymnasium.spaces ----

py::object describe(const Space& s) {
  py::dict d;
  switch (s.kind) {
    case Space::Kind::box:
      d["kind"] = "box";
      d["shape"] = py::tuple(py::cast(s.shape));
      d["dtype"] = dtype_name(s.dtype);
      d["low"] = s.low;
      d["high"] = s.high;
      break;
    case Space::Kind::discrete:
      d["kind"] = "discrete";
      d["n"] = s.n;
      break;
    case Space::Kind::dict: {
      d["kind"] = "dict";
      py::list fields;
      for (const auto& [name, field] : s.fields) fields.append(py::make_tuple(name, describe(field)));
      d["fields"] = fields;
      break;
    }
  }
  return d;
}

py::dtype numpy_dtype(DType t) {
  switch (t) {
    case DType::uint8:
      return py::dtype::of<uint8_t>();
    case DType::int32:
      return py::dtype::of<int32_t>();
    case DType::int64:
      return py::dtype::of<int64_t>();
    case DType::float32:
      break;
  }
  return py::dtype::of<float>();
}

// A read-only array over `data` that keeps `owner` (the Python env) alive.
py::array view(const py::dtype& dtype, std::vector<py::ssize_t> shape, const void* data, const py::handle& owner) {
  py::array a(dtype, std::move(shape), data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// Observations: one array per field; `drop_batch` for a single env's (batch of one).
py::dict observation_views(const ArrayDict& obs, const py::handle& owner, bool drop_batch) {
  py::dict d;
  for (const Array& a : obs.arrays()) {
    std::vector<py::ssize_t> shape(a.shape.begin() + (drop_batch ? 1 : 0), a.shape.end());
    d[py::str(a.name)] = view(numpy_dtype(a.dtype), std::move(shape), a.bytes.data(), owner);
  }
  return d;
}

// Info fields, by name, with a getter each.
template <class F>
void each_info_field(F&& f) {
  f("env_id", [](const Info& i) -> int64_t { return i.env_id; });
  f("elapsed_step", [](const Info& i) -> int64_t { return i.elapsed_steps; });
  f("episode_seed", [](const Info& i) -> uint64_t { return i.episode_seed; });
  f("success", [](const Info& i) -> bool { return i.success; });
  f("q", [](const Info& i) -> double { return i.q; });
  f("satisfied", [](const Info& i) -> int64_t { return i.satisfied; });
  f("total", [](const Info& i) -> int64_t { return i.total; });
  f("is_grasping", [](const Info& i) -> bool { return i.is_grasping; });
  f("diverged", [](const Info& i) -> bool { return i.diverged; });
  f("grasp_refused", [](const Info& i) -> bool { return i.grasp_refused; });
  f("primitive_status", [](const Info& i) -> int64_t { return i.primitive_status; });
  f("policy_failure", [](const Info& i) -> bool { return i.policy_failure; });
  f("physics_steps", [](const Info& i) -> int64_t { return i.physics_steps; });
}

py::dict info_dict(const Info& info) {
  py::dict d;
  each_info_field([&](const char* name, auto get) { d[name] = get(info); });
  return d;
}

// Gymnasium's vector info: an array per field over the rows.
py::dict info_arrays(std::span<const Info> infos) {
  py::dict d;
  each_info_field([&](const char* name, auto get) {
    using T = decltype(get(Info{}));
    py::array_t<T> a(static_cast<py::ssize_t>(infos.size()));
    auto out = a.template mutable_unchecked<1>();
    for (size_t r = 0; r < infos.size(); ++r) out(static_cast<py::ssize_t>(r)) = get(infos[r]);
    d[name] = a;
  });
  return d;
}

// An action as float32 values, checked against the action size.
std::vector<float> action_values(const py::handle& action, size_t size, const std::string& what) {
  const py::array_t<float, py::array::c_style | py::array::forcecast> a =
      py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(action);
  if (!a) throw Error(what + ": expected numbers");
  if (static_cast<size_t>(a.size()) != size) {
    throw Error(what + ": expected " + std::to_string(size) + " values, got " + std::to_string(a.size()));
  }
  return std::vector<float>(a.data(), a.data() + a.size());
}

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
