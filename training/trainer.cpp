#include "training/trainer.hpp"

#include <algorithm>

#include "base/error.hpp"
#include "base/json_file.hpp"
#include "base/random.hpp"
#include "base/registry.hpp"

namespace chore {

const char* const kMetricsHeader = "env_steps,wall_s,episodes,success_rate,mean_q,mean_return,mean_length";

namespace {

const Baseline& find_baseline(const std::string& name) {
  return find_by_name(baselines(), name, "baseline");
}

}  // namespace

TrainConfig baseline_config(const std::string& baseline, const std::string& activity) {
  TrainConfig c;
  c.baseline = baseline;
  c.env.activity = activity;
  find_baseline(baseline).setup(c);
  return c;
}

namespace {

// The sensor settings by name (absent from checkpoints older than them: defaults).
template <class Config, class Visit>  // Config: EnvConfig or const EnvConfig
void sensor_fields(Config& c, Visit visit) {
  visit("lidar", "beams", c.lidar.beams);
  visit("lidar", "fov", c.lidar.fov);
  visit("lidar", "range", c.lidar.range);
  auto& n = c.noise;
  for (auto [name, value] : {std::pair{"rgb_exposure", &n.rgb_exposure},
                             {"rgb_black_level", &n.rgb_black_level},
                             {"rgb_shot_noise", &n.rgb_shot_noise},
                             {"rgb_read_noise", &n.rgb_read_noise},
                             {"depth_noise", &n.depth_noise},
                             {"depth_noise_quadratic", &n.depth_noise_quadratic},
                             {"depth_edge", &n.depth_edge},
                             {"depth_max", &n.depth_max},
                             {"lidar_noise", &n.lidar_noise},
                             {"lidar_dropout", &n.lidar_dropout}}) {
    visit("noise", name, *value);
  }
  auto& r = c.randomization;
  visit("randomization", "light_intensity", r.light_intensity);
  visit("randomization", "light_color", r.light_color);
  visit("randomization", "surface_color", r.surface_color);
}

}  // namespace

nlohmann::json to_json(const EnvConfig& c) {
  nlohmann::json sensors;
  sensor_fields(c, [&](const char* group, const char* name, const auto& value) { sensors[group][name] = value; });
  nlohmann::json j = {{"activity", c.activity},
                      {"scene", c.scene},
                      {"width", c.width},
                      {"height", c.height},
                      {"observations", c.observations},
                      {"lighting", c.lighting == Lighting::full ? "full" : "lamps_only"},
                      {"max_episode_steps", c.max_episode_steps},
                      {"robot", c.robot},
                      {"object_states", c.object_states},
                      {"cloth", c.cloth},
                      {"start_jitter", c.start_jitter},
                      {"action_space", c.action_space},
                      {"primitive_mode", to_string(c.primitive_mode)},
                      {"policy_failure_repeats", c.policy_failure_repeats},
                      {"policy_failure_rule", c.policy_failure_rule},
                      {"instances", c.instances},
                      {"reachable_instances", c.reachable_instances},
                      {"instance", c.instance},
                      {"reward", c.reward},
                      {"reach_target", c.reach_target}};
  j.update(sensors);
  return j;
}

EnvConfig env_config_from_json(const nlohmann::json& j) {
  try {
    EnvConfig c;
    c.activity = j.at("activity").get<std::string>();
    c.scene = j.at("scene").get<std::string>();
    c.width = j.at("width").get<int>();
    c.height = j.at("height").get<int>();
    c.observations = j.at("observations").get<std::vector<std::string>>();
    const std::string lighting = j.at("lighting").get<std::string>();
    if (lighting != "full" && lighting != "lamps_only") throw Error("unknown lighting '" + lighting + "'");
    c.lighting = lighting == "full" ? Lighting::full : Lighting::lamps_only;
    c.max_episode_steps = j.at("max_episode_steps").get<int>();
    c.robot = j.at("robot").get<bool>();
    c.object_states = j.at("object_states").get<bool>();
    c.cloth = j.at("cloth").get<bool>();
    c.start_jitter = j.at("start_jitter").get<double>();
    c.action_space = j.at("action_space").get<std::string>();
    c.primitive_mode = parse_execution_mode(j.at("primitive_mode").get<std::string>());
    c.policy_failure_repeats = j.at("policy_failure_repeats").get<int>();
    // Runs written before the rule was a setting ran chore's.
    c.policy_failure_rule = j.value("policy_failure_rule", std::string("precondition"));
    // ...and drew an instance at every reset.
    c.instances = j.value("instances", std::string("resample"));
    c.instance = j.value("instance", uint64_t{0});
    // ...and had what the primitives act on within reach.
    c.reachable_instances = j.value("reachable_instances", true);
    c.reward = j.at("reward").get<std::string>();
    c.reach_target = j.at("reach_target").get<std::array<double, 3>>();
    sensor_fields(c, [&](const char* group, const char* name, auto& value) {
      if (j.contains(group) && j[group].contains(name)) value = j[group][name].get<std::decay_t<decltype(value)>>();
    });
    return c;
  } catch (const nlohmann::json::exception& e) {
    throw Error(std::string("env config: ") + e.what());
  }
}

nlohmann::json to_json(const TrainConfig& c) {
  const PpoConfig& p = c.ppo;
  const SacConfig& s = c.sac;
  return {{"baseline", c.baseline},
          {"env", to_json(c.env)},
          {"num_envs", c.num_envs},
          {"threads", c.threads},
          {"seed", c.seed},
          {"total_steps", c.total_steps},
          {"checkpoint_every", c.checkpoint_every},
          {"ppo",
           {{"lr", p.lr},
            {"buffer", p.buffer},
            {"batch", p.batch},
            {"epochs", p.epochs},
            {"gamma", p.gamma},
            {"gae_lambda", p.gae_lambda},
            {"clip", p.clip},
            {"entropy_coef", p.entropy_coef},
            {"value_coef", p.value_coef},
            {"max_grad_norm", p.max_grad_norm},
            {"frames", p.frames},
            {"history", p.history},
            {"normalize_advantage", p.normalize_advantage},
            {"target_kl", p.target_kl},
            {"sync_fraction", p.sync_fraction}}},
          {"sac",
           {{"lr", s.lr},
            {"buffer", s.buffer},
            {"batch", s.batch},
            {"gamma", s.gamma},
            {"tau", s.tau},
            {"learning_starts", s.learning_starts},
            {"initial_alpha", s.initial_alpha},
            {"hidden", s.hidden},
            {"report_every", s.report_every}}}};
}

namespace {

// Every value `given` holds that `read` holds too must be equal there: a
// number that does not fit its field (an int of 2^32 + 1, an int of 1.5)
// would otherwise be changed on the way in, silently.
void check_read_back(const nlohmann::json& given, const nlohmann::json& read, const std::string& path) {
  if (given.is_object() && read.is_object()) {
    for (const auto& [key, value] : given.items()) {
      if (read.contains(key)) check_read_back(value, read.at(key), path.empty() ? key : path + "." + key);
    }
  } else if (given != read) {
    throw Error(path + " = " + json_text(given) + " does not fit the setting (it would read as " + json_text(read) +
                ")");
  }
}

// The ranges a run's settings must lie in, whether from --set or a
// checkpoint: past them torch fails deep inside (a negative learning rate) or
// an allocation is absurd (a replay buffer of 10^12 transitions).
void validate(const TrainConfig& c) {
  const PpoConfig& p = c.ppo;
  const SacConfig& s = c.sac;
  find_baseline(c.baseline);
  within("num_envs", c.num_envs, 1, 256);
  within("threads", c.threads, 1, 64);
  within<uint64_t>("seed", c.seed, 0, kMaxSeed);
  within<int64_t>("total_steps", c.total_steps, 1, 10000000000);
  within<int64_t>("checkpoint_every", c.checkpoint_every, 1, 10000000000);
  within("ppo.lr", p.lr, 1e-12, 1.0);
  within("ppo.buffer", p.buffer, 1, 1000000);
  within("ppo.batch", p.batch, 1, 1000000);
  within("ppo.epochs", p.epochs, 1, 1000);
  within("ppo.gamma", p.gamma, 0.0, 1.0);
  within("ppo.gae_lambda", p.gae_lambda, 0.0, 1.0);
  within("ppo.clip", p.clip, 1e-9, 1e3);
  within("ppo.entropy_coef", p.entropy_coef, 0.0, 1e3);
  within("ppo.value_coef", p.value_coef, 0.0, 1e3);
  within("ppo.max_grad_norm", p.max_grad_norm, 1e-9, 1e6);
  within("ppo.frames", p.frames, 1, 64);
  within("ppo.history", p.history, 0, 64);
  within("ppo.target_kl", p.target_kl, 0.0, 1e3);
  within("ppo.sync_fraction", p.sync_fraction, 0.0, 1.0);
  within("sac.lr", s.lr, 1e-12, 1.0);
  within("sac.buffer", s.buffer, 1, 1000000);
  within("sac.batch", s.batch, 1, 100000);
  within("sac.gamma", s.gamma, 0.0, 1.0);
  within("sac.tau", s.tau, 1e-9, 1.0);
  within("sac.learning_starts", s.learning_starts, 0, 1000000000);
  within("sac.initial_alpha", s.initial_alpha, 1e-9, 1e3);
  within("sac.hidden", s.hidden, 1, 4096);
  within("sac.report_every", s.report_every, 1, 1000000000);
}

}  // namespace

TrainConfig train_config_from_json(const nlohmann::json& j) {
  try {
    TrainConfig c;
    c.baseline = j.at("baseline").get<std::string>();
    c.env = env_config_from_json(j.at("env"));
    c.num_envs = j.at("num_envs").get<int>();
    c.threads = j.at("threads").get<int>();
    c.seed = j.at("seed").get<uint64_t>();
    c.total_steps = j.at("total_steps").get<int64_t>();
    c.checkpoint_every = j.value("checkpoint_every", int64_t{3000});  // runs saved before it was kept: the default
    const nlohmann::json& p = j.at("ppo");
    c.ppo = {p.at("lr").get<double>(), p.at("buffer").get<int>(), p.at("batch").get<int>(), p.at("epochs").get<int>(),
             p.at("gamma").get<double>(), p.at("gae_lambda").get<double>(), p.at("clip").get<double>(),
             p.at("entropy_coef").get<double>(), p.at("value_coef").get<double>(), p.at("max_grad_norm").get<double>(),
             // Runs saved before these fields existed saw one frame, normalised, never stopped early and waited for
             // every rank.
             p.value("frames", 1), p.at("history").get<int>(), p.value("normalize_advantage", true),
             p.value("target_kl", 0.0), p.value("sync_fraction", 0.0)};
    const nlohmann::json& s = j.at("sac");
    c.sac = {s.at("lr").get<double>(),
             s.at("buffer").get<int>(),
             s.at("batch").get<int>(),
             s.at("gamma").get<double>(),
             s.at("tau").get<double>(),
             s.at("learning_starts").get<int>(),
             s.at("initial_alpha").get<double>(),
             s.at("hidden").get<int>(),
             s.at("report_every").get<int>()};
    check_read_back(j, to_json(c), "");
    validate(c);
    return c;
  } catch (const nlohmann::json::exception& e) {
    throw Error(std::string("train config: ") + e.what());
  }
}

TrainConfig with_setting(const TrainConfig& config, const std::string& key_equals_value) {
  const size_t eq = key_equals_value.find('=');
  if (eq == std::string::npos) throw Error("--set " + key_equals_value + ": expected KEY=VALUE");
  const std::string key = key_equals_value.substr(0, eq);
  const std::string text = key_equals_value.substr(eq + 1);
  nlohmann::json tree = to_json(config);
  nlohmann::json* field = &tree;
  for (size_t begin = 0; begin <= key.size();) {
    const size_t end = std::min(key.find('.', begin), key.size());
    const std::string name = key.substr(begin, end - begin);
    if (!field->is_object() || !field->contains(name)) throw Error("--set " + key + ": no such setting");
    field = &(*field)[name];
    begin = end + 1;
  }
  if (field->is_object()) throw Error("--set " + key + ": a group of settings; name one inside it");
  nlohmann::json value = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (value.is_discarded() && field->is_string()) value = text;  // a bare word for a string
  const bool same_type = value.type() == field->type() || (field->is_number_float() && value.is_number()) ||
                         (field->is_number_unsigned() && value.is_number_integer() && value.get<int64_t>() >= 0) ||
                         (field->is_number_integer() && value.is_number_unsigned());
  if (!same_type) {
    throw Error("--set " + key + ": '" + text + "' is not a " + field->type_name() + " like " + field->dump());
  }
  *field = value;
  try {
    return train_config_from_json(tree);
  } catch (const Error& e) {
    throw Error("--set " + key_equals_value + ": " + e.what());
  }
}

void EpisodeStats::record(const Batch& batch) {
  for (int i = 0; i < batch.size(); ++i) {
    double& ret = returns_[batch.env_ids[i]];
    ret += batch.rewards[i];
    if (!batch.terminated[i] && !batch.truncated[i]) continue;
    const Info& info = batch.final_obs ? batch.final_infos[i] : batch.infos[i];
    recent_.push_back({ret, info.q, info.elapsed_steps, info.success});
    if (recent_.size() > kWindow) recent_.pop_front();
    ++episodes_;
    ret = 0;
  }
}

MetricsRow EpisodeStats::row(int64_t env_steps, double wall_s) const {
  MetricsRow row;
  row.env_steps = env_steps;
  row.wall_s = wall_s;
  row.episodes = episodes_;
  for (const Episode& e : recent_) {
    row.success_rate += e.success;
    row.mean_q += e.q;
    row.mean_return += e.ret;
    row.mean_length += static_cast<double>(e.length);
  }
  if (!recent_.empty()) {
    const double n = static_cast<double>(recent_.size());
    row.success_rate /= n, row.mean_q /= n, row.mean_return /= n, row.mean_length /= n;
  }
  return row;
}

nlohmann::json EpisodeStats::to_json() const {
  nlohmann::json recent = nlohmann::json::array();
  for (const Episode& e : recent_) recent.push_back({e.ret, e.q, e.length, e.success});
  return {{"episodes", episodes_}, {"recent", recent}};
}

void EpisodeStats::load(const nlohmann::json& j) {
  episodes_ = j.at("episodes").get<int64_t>();
  recent_.clear();
  for (const nlohmann::json& e : j.at("recent")) {
    recent_.push_back({e.at(0).get<double>(), e.at(1).get<double>(), e.at(2).get<int64_t>(), e.at(3).get<bool>()});
  }
}

VectorEnvConfig vector_env_config(const TrainConfig& config) {
  return {.env = config.env,
          .num_envs = config.num_envs,
          .num_threads = std::min(config.threads, config.num_envs),
          .autoreset = AutoReset::same_step};
}

nlohmann::json run_meta(const TrainConfig& config, const nlohmann::json& network, const RunProgress& progress,
                        const EpisodeStats& stats) {
  return {{"config", to_json(config)},
          {"network", network},
          {"steps", progress.steps},
          {"wall_s", progress.wall_s},
          {"episodes", stats.to_json()}};
}

RunProgress load_run_meta(const nlohmann::json& meta, EpisodeStats& stats) {
  stats.load(meta.at("episodes"));
  return {meta.at("steps").get<int64_t>(), meta.at("wall_s").get<double>()};
}

}  // namespace chore
