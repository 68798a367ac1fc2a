#include "python/convert.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <filesystem>

#include "analogs/scene_analogs.hpp"
#include "base/error.hpp"
#include "tasks/activity.hpp"
#include "world/scene.hpp"

namespace chore::python {
namespace {

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

// A scene file (a .json path, or assets/scenes/NAME.json) or an inventory scene.
bool is_scene(const std::string& name) {
  namespace fs = std::filesystem;
  if (name.ends_with(".json")) return fs::exists(name);
  if (fs::exists(fs::path(default_assets_dir()) / "scenes" / (name + ".json"))) return true;
  const auto& inventories = shipped_scene_inventories();
  return std::any_of(inventories.begin(), inventories.end(), [&](const SceneInventory& s) { return s.name == name; });
}

}  // namespace

EnvConfig env_config(const py::dict& d) {
  EnvConfig c;
  const auto text = [](const py::handle& v, const std::string& key) {
    if (!py::isinstance<py::str>(v)) throw Error("config '" + key + "': expected a string");
    return v.cast<std::string>();
  };
  const auto integer = [](const py::handle& v, const std::string& key, long lo, long hi) {
    if (!py::isinstance<py::int_>(v) || py::isinstance<py::bool_>(v))
      throw Error("config '" + key + "': expected an integer");
    int overflow = 0;
    const long long n = PyLong_AsLongLongAndOverflow(v.ptr(), &overflow);
    if (overflow || n < lo || n > hi) {
      throw Error("config '" + key + "' = " + py::str(v).cast<std::string>() + ": expected " + std::to_string(lo) +
                  ".." + std::to_string(hi));
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
    if (key == "task") {  // an activity, else a scene
      const std::string task = text(v, key);
      try {
        resolve_activity_path(task);
        c.activity = task;
      } catch (const Error& not_activity) {
        if (!is_scene(task)) throw Error("'" + task + "' is neither an activity nor a scene: " + not_activity.what());
        if (d.contains("scene")) throw Error("'" + task + "' is a scene, and scene= names another");
        c.scene = task;
      }
    } else if (key == "activity") {
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
    } else if (key == "policy_failure_rule") {
      c.policy_failure_rule = text(v, key);
    } else if (key == "policy_failure_repeats") {
      c.policy_failure_repeats = integer(v, key, 1, 1 << 30);
    } else if (key == "instances") {
      c.instances = text(v, key);
    } else if (key == "instance") {
      c.instance = static_cast<uint64_t>(integer(v, key, 0, 1 << 30));
    } else if (key == "robot") {
      c.robot = flag(v, key);
    } else if (key == "object_states") {
      c.object_states = flag(v, key);
    } else if (key == "cloth") {
      c.cloth = flag(v, key);
    } else {
      throw Error("config: unknown key '" + key +
                  "' (known: task, activity, scene, width, height, observations, action_space, mode, "
                  "max_episode_steps, reward, reachable_instances, policy_failure_rule, policy_failure_repeats, instances, "
                  "instance, robot, object_states, cloth)");
    }
  }
  return c;
}

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

}  // namespace chore::python
