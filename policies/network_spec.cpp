#include "policies/network_spec.hpp"

#include <string>

#include "base/error.hpp"

namespace chore {

nlohmann::json to_json(const NetworkSpec& s) {
  return {{"height", s.height},           {"width", s.width},
          {"state_size", s.state_size},   {"feature_size", s.feature_size},
          {"frames", s.frames},           {"history", s.history},
          {"num_actions", s.num_actions},
          {"action_size", s.action_size}, {"hidden", s.hidden},
          {"normalize_state", s.normalize_state}};
}

NetworkSpec network_spec_from_json(const nlohmann::json& j) {
  try {
    NetworkSpec s;
    s.height = j.at("height").get<int>();
    s.width = j.at("width").get<int>();
    s.state_size = j.at("state_size").get<int>();
    s.feature_size = j.at("feature_size").get<int>();
    s.frames = j.value("frames", 1);  // checkpoints from before frames were stacked: one
    s.history = j.at("history").get<int>();
    s.num_actions = j.at("num_actions").get<int64_t>();
    s.action_size = j.at("action_size").get<int>();
    s.hidden = j.at("hidden").get<int>();
    s.normalize_state = j.value("normalize_state", true);  // checkpoints from before it was a choice: true
    within("height", s.height, 0, 4096);
    within("width", s.width, 0, 4096);
    within("state_size", s.state_size, 0, 100000);
    within("feature_size", s.feature_size, 1, 100000);
    within("frames", s.frames, 1, 64);
    within("history", s.history, 0, 64);
    within<int64_t>("num_actions", s.num_actions, 0, 1000000);
    within("action_size", s.action_size, 0, 10000);
    within("hidden", s.hidden, 1, 100000);
    return s;
  } catch (const nlohmann::json::exception& e) {
    throw Error(std::string("network spec: ") + e.what());
  } catch (const Error& e) {
    throw Error(std::string("network spec: ") + e.what());
  }
}

NetworkSpec network_spec(const Space& observation, const Space& action, int frames, int history) {
  NetworkSpec s;
  for (const auto& [name, space] : observation.fields) {
    if (name == "rgb") {
      s.height = space.shape[0];
      s.width = space.shape[1];
    } else if (name == "is_grasping" || name == "proprio") {
      s.state_size += static_cast<int>(space.element_count());
    }
  }
  if (action.kind == Space::Kind::discrete) {
    s.num_actions = action.n;
  } else {
    s.action_size = static_cast<int>(action.element_count());
  }
  s.frames = frames;
  s.history = history;
  return s;
}

}  // namespace chore
