// chore's second Python extension (_chore_policies), apart from _chore so that
// `import chore` does not load LibTorch: chore eval's evaluation over seeds
// with a Python callable, the scripted expert or a trained checkpoint as the
// policy, and checkpoints as policies Python can call.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "base/error.hpp"
#include "base/json_file.hpp"
#include "policies/evaluate.hpp"
#include "python/convert.hpp"
#include "training/checkpoint.hpp"

namespace py = pybind11;

namespace chore {
namespace {

using namespace python;

// A Python callable as a chore::Policy: policy(obs, info) -> actions for the
// batch's rows (obs: arrays viewing the batch; info: an array per field);
// policy.reset(env_ids), if it has one, when envs start new episodes.
class CallablePolicy : public Policy {
 public:
  CallablePolicy(py::object callable, size_t action_size) : callable_(std::move(callable)), size_(action_size) {}
  ~CallablePolicy() override {
    py::gil_scoped_acquire gil;
    callable_ = py::object();
  }

  void act(const Batch& batch, std::span<float> actions) override {
    py::gil_scoped_acquire gil;
    const py::object result = callable_(observation_views(*batch.obs, py::none(), false), info_arrays(batch.infos));
    const std::vector<float> values = action_values(result, size_ * batch.size(), "policy");
    std::copy(values.begin(), values.end(), actions.begin());
  }

  void reset(std::span<const int> env_ids) override {
    py::gil_scoped_acquire gil;
    if (py::hasattr(callable_, "reset")) callable_.attr("reset")(std::vector<int>(env_ids.begin(), env_ids.end()));
  }

 private:
  py::object callable_;
  size_t size_;
};

// A loaded checkpoint, callable on a batch of observations.
class CheckpointPolicy {
 public:
  CheckpointPolicy(const std::string& path, bool sample) : path_(path), loaded_(load_policy(path, sample)) {
    Env probe(loaded_.env);  // the spaces it acts in
    observation_space_ = probe.observation_space();
    action_space_ = probe.action_space();
  }

  // Actions for the rows of `obs` (arrays with a leading batch dimension, as a
  // VectorEnv returns them); episode seeds from `info` when given (sampled
  // actions are seeded by them).
  py::array act(const py::dict& obs, const py::object& info) {
    int rows = -1;
    for (const auto& [name, field] : observation_space_.fields) {
      if (!obs.contains(name)) throw Error(path_ + ": the observation lacks '" + name + "'");
      const py::array a = py::array::ensure(obs[py::str(name)], py::array::c_style);
      if (!a || a.ndim() < 1) throw Error(path_ + ": observation '" + name + "': expected a batched array");
      if (rows < 0) rows = static_cast<int>(a.shape(0));
      if (a.shape(0) != rows) throw Error(path_ + ": observation '" + name + "': another batch size");
    }
    if (rows <= 0) throw Error(path_ + ": an empty batch");
    ArrayDict batch_obs(observation_space_, rows);
    for (Array& a : batch_obs.arrays()) {
      const py::array given = py::array::ensure(obs[py::str(a.name)], py::array::c_style);
      if (static_cast<size_t>(given.nbytes()) != a.bytes.size() ||
          given.itemsize() != static_cast<py::ssize_t>(dtype_size(a.dtype))) {
        throw Error(path_ + ": observation '" + a.name + "': expected " + std::to_string(a.bytes.size()) +
                    " bytes of " + dtype_name(a.dtype) + ", got " + std::to_string(given.nbytes()));
      }
      std::memcpy(a.bytes.data(), given.data(), a.bytes.size());
    }
    std::vector<Info> infos(rows);
    std::vector<int> ids(rows);
    for (int r = 0; r < rows; ++r) infos[r].env_id = ids[r] = r;
    if (!info.is_none() && py::dict(info).contains("episode_seed")) {
      const auto seeds = py::array_t<uint64_t, py::array::forcecast>::ensure(py::dict(info)["episode_seed"]);
      if (!seeds || seeds.size() != rows) throw Error(path_ + ": info['episode_seed']: expected one per row");
      for (int r = 0; r < rows; ++r) infos[r].episode_seed = seeds.at(r);
    }
    const std::vector<float> rewards(rows, 0.f);
    const std::vector<uint8_t> flags(rows, 0);
    const Batch batch{&batch_obs, rewards, flags, flags, ids, infos, nullptr, {}};
    const size_t size = std::max<size_t>(1, action_space_.element_count());
    std::vector<float> actions(rows * size);
    {
      py::gil_scoped_release release;
      loaded_.policy->act(batch, actions);
    }
    if (action_space_.kind == Space::Kind::discrete) {
      py::array_t<int64_t> out(rows);
      for (int r = 0; r < rows; ++r) out.mutable_at(r) = static_cast<int64_t>(actions[r]);
      return out;
    }
    py::array_t<float> out({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(size)});
    std::copy(actions.begin(), actions.end(), out.mutable_data());
    return out;
  }

  void reset(const std::vector<int>& env_ids) { loaded_.policy->reset(env_ids); }

  // What chore eval makes of it: its env, with overrides, and a policy that
  // acts through this one (which stays usable after).
  PolicySource source(const std::string& activity, const std::string& mode, int max_steps) {
    EnvConfig env = loaded_.env;
    if (!activity.empty()) env.activity = activity;
    if (!mode.empty()) env.primitive_mode = parse_execution_mode(mode);
    if (max_steps > 0) env.max_episode_steps = max_steps;
    struct Forward : Policy {
      Policy* to;
      explicit Forward(Policy* p) : to(p) {}
      void act(const Batch& b, std::span<float> a) override { to->act(b, a); }
      void reset(std::span<const int> ids) override { to->reset(ids); }
    };
    Policy* policy = loaded_.policy.get();
    return {path_, env, [policy](const VectorEnv&) { return std::make_unique<Forward>(policy); }};
  }

  py::dict env() const {
    py::dict d;
    d["activity"] = loaded_.env.activity;
    d["action_space"] = loaded_.env.action_space;
    d["mode"] = to_string(loaded_.env.primitive_mode);
    d["observations"] = loaded_.env.observations;
    d["width"] = loaded_.env.width;
    d["height"] = loaded_.env.height;
    d["max_episode_steps"] = loaded_.env.max_episode_steps;
    return d;
  }
  const std::string& baseline() const { return loaded_.baseline; }
  int64_t steps() const { return loaded_.steps; }
  const Space& observation_space() const { return observation_space_; }
  const Space& action_space() const { return action_space_; }

 private:
  std::string path_;
  LoadedPolicy loaded_;
  Space observation_space_, action_space_;
};

// The report chore eval --json prints, as text (the package parses it).
std::string run_evaluation(const PolicySource& source, uint64_t first, uint64_t last, int episodes, int threads,
                           bool verbose) {
  std::ostringstream log;
  nlohmann::json report;
  {
    py::gil_scoped_release release;
    report = evaluate(source, {first, last, episodes, threads}, verbose ? std::cerr : log);
  }
  return json_text(report);
}

}  // namespace
}  // namespace chore

PYBIND11_MODULE(_chore_policies, m) {
  using namespace chore;
  m.doc() = "chore eval from Python: evaluation over seeds, checkpoints as policies";
  // chore::Error as the same chore.Error the envs raise.
  static const py::object error = py::module_::import("chore._chore").attr("Error");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });

  py::class_<CheckpointPolicy>(m, "CheckpointPolicy")
      .def(py::init<const std::string&, bool>(), py::arg("path"), py::arg("sample") = false)
      .def("__call__", &CheckpointPolicy::act, py::arg("obs"), py::arg("info") = py::none())
      .def("reset", &CheckpointPolicy::reset, py::arg("env_ids"))
      .def_property_readonly("env", &CheckpointPolicy::env)
      .def_property_readonly("baseline", &CheckpointPolicy::baseline)
      .def_property_readonly("steps", &CheckpointPolicy::steps)
      .def_property_readonly("observation_space",
                             [](const CheckpointPolicy& c) { return python::describe(c.observation_space()); })
      .def_property_readonly("action_space",
                             [](const CheckpointPolicy& c) { return python::describe(c.action_space()); });

  m.def(
      "evaluate_callable",
      [](py::object policy, const py::dict& config, uint64_t first, uint64_t last, int episodes, int threads,
         bool verbose) {
        const PolicySource source{"python", python::env_config(config), [policy](const VectorEnv& envs) {
                                    py::gil_scoped_acquire gil;  // evaluate() runs without it
                                    return std::make_unique<CallablePolicy>(
                                        policy, std::max<size_t>(1, envs.single_action_space().element_count()));
                                  }};
        return run_evaluation(source, first, last, episodes, threads, verbose);
      },
      py::arg("policy"), py::arg("config"), py::arg("first"), py::arg("last"), py::arg("episodes"), py::arg("threads"),
      py::arg("verbose"));
  m.def("evaluate_expert", [](const std::string& activity, const std::string& mode, int max_steps, uint64_t first,
                              uint64_t last, int episodes, int threads, bool verbose) {
    return run_evaluation(expert_source(activity, parse_execution_mode(mode), max_steps), first, last, episodes,
                          threads, verbose);
  });
  m.def("evaluate_checkpoint",
        [](CheckpointPolicy& policy, const std::string& activity, const std::string& mode, int max_steps,
           uint64_t first, uint64_t last, int episodes, int threads, bool verbose) {
          return run_evaluation(policy.source(activity, mode, max_steps), first, last, episodes, threads, verbose);
        });
  m.def("format_evaluation",
        [](const std::string& report) { return format_evaluation(nlohmann::json::parse(report)); });
}
