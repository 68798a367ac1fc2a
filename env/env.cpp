#include "env/env.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "analogs/activity_scenes.hpp"
#include "base/error.hpp"
#include "env/env_impl.hpp"
#include "env/observations.hpp"
#include "env/rewards.hpp"
#include "env/task_plan.hpp"
#include "primitives/primitive.hpp"
#include "tasks/intermediates.hpp"
#include "tasks/vocabulary.hpp"
#include "world/model_cache.hpp"

namespace chore {
namespace {

constexpr double kActionDt = Env::kPhysicsSubsteps / 120.0;
constexpr double kBaseSpeed = 0.5, kTurnSpeed = 1.0;  // m/s, rad/s at |action| = 1
constexpr double kTorsoSpeed = 0.1, kJointSpeed = 1.0;
// derive_seed's stream of a fixed instance's draws (EnvConfig::instances).
constexpr uint64_t kFixedInstanceStream = 7;
bool wants(const EnvConfig& c, const std::string& name) {
  return std::find(c.observations.begin(), c.observations.end(), name) != c.observations.end();
}

}  // namespace

EnvAssets load_assets(const EnvConfig& config) {
  std::string scene = config.scene;
  if (scene.empty() && !config.activity.empty()) scene = activity_scene(config.activity);
  SceneOptions options;
  options.robot = config.robot;
  options.cloth = config.cloth;
  EnvAssets assets;
  // A scene of BEHAVIOR-1K's inventories, or none named for an activity of
  // either dialect: its analog, with the objects the activity needs.
  const bool inventory = std::any_of(shipped_scene_inventories().begin(), shipped_scene_inventories().end(),
                                     [&](const SceneInventory& s) { return s.name == scene; });
  std::optional<Problem> problem;
  if (!config.activity.empty() && (inventory || scene.empty())) {
    problem = load_bddl(resolve_activity_path(config.activity));
    // The scene holds what the rules make on the way, as the activity binds it.
    declare_intermediates(*problem, *dialect_knowledge_base(problem->domain), behavior_transition_rules());
  }
  if (problem) {
    const SceneInventory& chosen = activity_inventory(*problem, scene);
    assets.scene = Scene::build(activity_scene_analog(*problem, chosen, *CategoryModels::shipped()).file, options);
  } else if (inventory) {  // the model `chore scene build` keeps
    options.model_cache = default_model_cache_dir();
    assets.scene =
        Scene::build(generate_scene_analog(find_scene_inventory(scene), *CategoryModels::shipped(), 0).file, options);
  } else {
    assets.scene = Scene::load(scene.empty() ? "apartment" : scene, options);
  }
  if (!config.activity.empty()) {
    assets.activity = Activity::load(config.activity, *assets.scene);
    if (config.robot) assets.needed_actions = actions_a_plan_needs(*assets.activity, *assets.scene);
  }
  return assets;
}

Env::Env(const EnvConfig& config) : Env(config, load_assets(config)) {}

Env::Env(const EnvConfig& config, const EnvAssets& assets) : impl_(std::make_unique<Impl>(config, assets)) {}

Env::~Env() = default;

const Space& Env::observation_space() const {
  return impl_->observation_space_;
}
const Space& Env::action_space() const {
  return impl_->action_space_;
}
const std::vector<PrimitiveAction>& Env::primitive_actions() const {
  return impl_->primitive_actions_;
}
const EnvConfig& Env::config() const {
  return impl_->config_;
}
void Env::release_thread() {
  if (impl_->renderer_) impl_->renderer_->release_thread();
}
void Env::close() {
  impl_->close();
}
bool Env::closed() const {
  return impl_->closed_;
}
const Segmentation& Env::segmentation() const {
  return impl_->sensors_->segmentation(*impl_->world_);
}
std::string Env::out_of_reach() {
  impl_->check_open();
  return impl_->first_out_of_reach(impl_->episode_seed_);
}
const PrimitiveResult& Env::last_primitive() const {
  return impl_->last_primitive_;
}
const Activity* Env::activity() const {
  return impl_->activity_.get();
}
const World& Env::world() const {
  return *impl_->world_;
}

Env::ResetResult Env::reset(std::optional<uint64_t> seed) {
  Info info = impl_->reset_state(seed);
  impl_->observe();
  return {impl_->obs_, info};
}

Env::StepResult Env::step(std::span<const float> action) {
  Env::Impl::Outcome out = impl_->advance(action);
  impl_->observe();
  return {impl_->obs_, out.reward, out.terminated, out.truncated, out.info};
}

Env::Impl::Impl(const EnvConfig& config, const EnvAssets& assets)
    : config_(config), scene_(assets.scene), activity_(assets.activity) {
  if (config_.width <= 0 || config_.height <= 0) {
    throw Error("env config: image size " + std::to_string(config_.width) + "x" + std::to_string(config_.height) +
                " must be positive");
  }
  if (config_.max_episode_steps <= 0) throw Error("env config: max_episode_steps must be positive");
  if (config_.instances != "resample" && config_.instances != "fixed") {
    throw Error("env config: unknown instances '" + config_.instances + "' (known: resample, fixed)");
  }
  if (scene_->has_robot() != config_.robot) {
    throw Error("env config: scene '" + scene_->name() + "' was compiled " +
                (scene_->has_robot() ? "with" : "without") + " a robot, the config says otherwise");
  }
  std::vector<std::pair<std::string, Space>> fields;
  for (const std::string& name : config_.observations) {
    const Modality* m = nullptr;
    try {
      m = &find_modality(name);
    } catch (const Error& e) {
      throw Error(std::string("env config: ") + e.what());
    }
    if (!config_.robot && m->needs_robot) throw Error("env config: observation '" + name + "' needs the robot");
    if (m->needs_primitives && config_.action_space != "primitives") {
      throw Error("env config: observation '" + name + "' needs the primitive action space (action_space is '" +
                  config_.action_space + "')");
    }
  }
  try {
    reward_ = &find_reward(config_.reward);
  } catch (const Error& e) {
    throw Error(std::string("env config: ") + e.what());
  }
  if (reward_->needs_robot && !config_.robot) {
    throw Error("env config: the " + config_.reward + " reward needs the robot");
  }
  try {
    validate(config_.lidar);
    validate(config_.noise);
    validate(config_.randomization);
  } catch (const Error& e) {
    throw Error(std::string("env config: ") + e.what());
  }
  world_ = std::make_unique<World>(scene_);
  sensors_ = std::make_unique<Sensors>(config_.width, config_.height, config_.lidar, config_.noise);
  world_->set_lighting(config_.lighting);
  world_->set_state_updates(config_.object_states);
  if (activity_) activity_->configure(*world_);
  if (config_.action_space == "low_level") {
    action_space_ = Space::box({config_.robot ? kLowLevelActionSize : 0}, DType::float32, -1, 1);
  } else if (config_.action_space == "primitives") {
    if (!activity_ || !config_.robot) {
      throw Error("env config: the primitive action space needs an activity and the robot");
    }
    if (config_.policy_failure_repeats < 1) throw Error("env config: policy_failure_repeats must be >= 1");
    const std::string& rule = config_.policy_failure_rule;
    if (rule != "none" && rule != "precondition" && rule != "paper") {
      throw Error("env config: unknown policy_failure_rule '" + rule + "' (known: none, precondition, paper)");
    }
    primitive_actions_ = chore::primitive_actions(*activity_, *world_, config_.primitive_mode);
    action_space_ = Space::discrete(static_cast<int64_t>(primitive_actions_.size()));
  } else {
    throw Error("env config: unknown action space '" + config_.action_space + "' (known: low_level, primitives)");
  }
  if (activity_ && config_.robot) {
    // What a plan for the goal acts on, not every object the action space
    // names: a distractor out of reach is an action that fails, not a task
    // that cannot be done. (What lies inside a container is checked with the
    // containers push opens pulled open: first_out_of_reach.)
    for (const PrimitiveAction& a : chore::primitive_actions(*activity_, *world_, config_.primitive_mode)) {
      if (primitive_touches(a.type) && (!assets.needed_actions || assets.needed_actions->count(to_string(a))))
        reach_checks_.push_back(a);
    }
  }
  // A fixed order, whatever the config's: the layout of batched buffers.
  const ObservationSource source = observation_source();
  for (const Modality& m : modalities()) {
    if (wants(config_, m.name)) fields.push_back({m.name, m.space(source)});
  }
  observation_space_ = Space::dict(std::move(fields));
  obs_ = ArrayDict(observation_space_, 1);
}

Env::Impl::~Impl() = default;

void Env::Impl::check_open() const {
  if (closed_) throw Error("env: used after close()");
}

void Env::Impl::close() {
  if (closed_) return;
  renderer_.reset();
  world_.reset();
  closed_ = true;
}

Info Env::Impl::make_info(const Score* score) const {
  Info info;
  info.elapsed_steps = elapsed_;
  info.episode_seed = episode_seed_;
  info.diverged = diverged_;
  info.is_grasping = world_->grasped_object() >= 0;
  info.primitive_status = last_primitive_status_;
  info.primitive_counts = primitive_counts_;
  if (score) {
    info.success = score->success;
    info.q = score->q;
    info.satisfied = static_cast<int>(score->satisfied);
    info.total = static_cast<int>(score->total);
  }
  return info;
}

Info Env::Impl::reset_state(std::optional<uint64_t> seed) {
  check_open();
  if (seed) rng_.seed(*seed);
  episode_seed_ = seed ? *seed : episode_seed_ + 1;
  // The instance (the robot's start pose, then the activity's objects):
  // drawn from the episode's stream, or with fixed instances from a stream of
  // the instance's own.
  Rng fixed_instance(derive_seed(config_.instance, kFixedInstanceStream));
  Rng& instance_rng = config_.instances == "fixed" ? fixed_instance : rng_;
  Pose2 start = scene_->robot_start();
  start.x += config_.start_jitter * uniform(instance_rng, -1, 1);
  start.y += config_.start_jitter * uniform(instance_rng, -1, 1);
  start.yaw += 10 * config_.start_jitter * uniform(instance_rng, -1, 1);
  world_->reset(start);
  sensors_->reset(seed);
  if (config_.randomization.any()) world_->randomize_appearance(config_.randomization, sensors_->rng());
  elapsed_ = 0;
  episode_over_ = false;
  diverged_ = false;
  primitive_counts_ = {};
  last_primitive_status_ = last_invalid_action_ = -1;
  invalid_repeats_ = 0;
  if (!activity_) return make_info();
  if (!sample_options_.prefer && world_->robot()) sample_options_.prefer = arm_reach_preference(*world_);
  std::string out_of_reach;
  for (int attempt = 0; attempt < kInstanceAttempts; ++attempt) {
    if (attempt > 0) world_->reset(start);
    activity_->instantiate(*world_, instance_rng, sample_options_);
    if (!config_.reachable_instances) break;
    out_of_reach = first_out_of_reach(instance_rng());
    if (out_of_reach.empty()) break;
  }
  if (!out_of_reach.empty()) {
    throw Error("env: no instance of activity '" + activity_->name() + "' in " + std::to_string(kInstanceAttempts) +
                " samples had what a plan for its goal acts on within the robot's reach; the last: " + out_of_reach +
                " (EnvConfig::reachable_instances = false, `--set env.reachable_instances=false` for chore train,"
                " accepts such instances)");
  }
  const Activity::Evaluation goal = activity_->evaluate(*world_);
  potential_ = goal.potential;
  return make_info(&goal.score);
}

std::string Env::Impl::first_out_of_reach(uint64_t seed) {
  std::vector<PrimitiveType> types;
  std::vector<int> objects;
  for (const PrimitiveAction& a : reach_checks_) types.push_back(a.type), objects.push_back(a.object);
  const ReachProblem problem = chore::first_out_of_reach(*world_, types, objects, seed);
  return problem.index < 0 ? "" : to_string(reach_checks_[problem.index]) + ": " + problem.reason;
}

Env::Impl::Outcome Env::Impl::advance(std::span<const float> action) {
  check_open();
  if (episode_over_) throw Error("env: step() after the episode ended; call reset() first");
  const size_t expected = action_space_.element_count();
  if (action.size() != expected) {
    throw Error("env: action has " + std::to_string(action.size()) + " values, expected " + std::to_string(expected));
  }
  for (size_t i = 0; i < action.size(); ++i) {
    if (!std::isfinite(action[i])) {
      throw Error("env: action[" + std::to_string(i) + "] is " + std::to_string(action[i]));
    }
  }
  World::StepReport report;
  const int64_t physics_steps =
      primitive_actions_.empty() ? act_low_level(action, report) : act_primitive(action, report);
  ++elapsed_;
  diverged_ = report.diverged;
  Outcome out;
  std::optional<Score> score;
  const double potential_before = potential_;
  if (activity_ && !report.diverged) {
    const Activity::Evaluation goal = activity_->evaluate(*world_);
    score = goal.score;
    potential_ = goal.potential;
    out.terminated = score->success;
  }
  if (!report.diverged) out.reward = reward_->reward({config_, *world_, potential_before, potential_});
  // The seed's policy failure: the same invalid action repeated ends the episode.
  const bool policy_failure =
      config_.policy_failure_rule != "none" && invalid_repeats_ >= config_.policy_failure_repeats;
  out.terminated = out.terminated || policy_failure;
  out.truncated = !out.terminated && (report.diverged || elapsed_ >= config_.max_episode_steps);
  out.info = make_info(score ? &*score : nullptr);
  out.info.grasp_refused = report.grasp_refused;
  out.info.policy_failure = policy_failure;
  out.info.physics_steps = physics_steps;
  episode_over_ = out.terminated || out.truncated;
  return out;
}

int64_t Env::Impl::act_low_level(std::span<const float> action, World::StepReport& report) {
  if (const Robot* r = world_->robot()) {
    auto a = [&](int i) { return std::clamp(static_cast<double>(action[i]), -1.0, 1.0); };
    World& w = *world_;
    w.command_base_velocity(a(0) * kBaseSpeed, a(1) * kBaseSpeed, a(2) * kTurnSpeed);
    // Velocity commands integrate from the current target, not the measured
    // position, so a zero action holds a joint where it was commanded.
    auto integrate = [&](const RobotJoint& j, double velocity) {
      w.command_position(j, w.commanded_position(j) + velocity * kActionDt);
    };
    integrate(r->torso, a(3) * kTorsoSpeed);
    for (int i = 0; i < Robot::kArmJoints; ++i) integrate(r->arm[i], a(4 + i) * kJointSpeed);
    const double finger = (a(11) + 1.0) / 2.0 * Robot::kGripperOpen;
    w.command_position(r->gripper_left, finger);
    w.command_position(r->gripper_right, finger);
    integrate(r->head_pan, a(12) * kJointSpeed);
    integrate(r->head_tilt, a(13) * kJointSpeed);
  }
  report = world_->step(kPhysicsSubsteps);
  return kPhysicsSubsteps;
}

int64_t Env::Impl::act_primitive(std::span<const float> action, World::StepReport& report) {
  const float value = action[0];
  if (value != std::floor(value) || value < 0 || value >= static_cast<float>(primitive_actions_.size())) {
    throw Error("env: primitive action " + std::to_string(value) + " is not an integer in [0, " +
                std::to_string(primitive_actions_.size()) + ")");
  }
  const int index = static_cast<int>(value);
  const PrimitiveAction& a = primitive_actions_[index];
  PrimitiveOptions options;
  options.mode = config_.primitive_mode;
  last_primitive_ = execute_primitive(*world_, a.type, a.object, rng_(), options);
  const PrimitiveResult& result = last_primitive_;
  report.diverged = result.diverged;
  report.grasp_refused = result.grasp_refused;
  last_primitive_status_ = static_cast<int>(result.status);
  ++primitive_counts_[last_primitive_status_];
  const bool paper = config_.policy_failure_rule == "paper";
  if (result.status == PrimitiveStatus::precondition_failure || (paper && result.status != PrimitiveStatus::success)) {
    invalid_repeats_ = index == last_invalid_action_ ? invalid_repeats_ + 1 : 1;
    last_invalid_action_ = index;
  } else {
    invalid_repeats_ = 0;
    last_invalid_action_ = -1;
  }
  return result.physics_steps;
}

SensorFrame Env::Impl::sensor_frame(ArrayDict& obs, int index) const {
  SensorFrame f;
  for (const Modality& m : modalities()) {
    if (m.bind && obs.contains(m.name)) m.bind(f, obs[m.name].item(index));
  }
  return f;
}

ObservationSource Env::Impl::observation_source() const {
  return {config_, *world_, *sensors_, primitive_actions_};
}

std::vector<CameraView> Env::Impl::camera_views(ArrayDict& obs, int index) {
  check_open();
  return sensors_->views(*world_, sensor_frame(obs, index));
}

void Env::Impl::finish_observation(ArrayDict& obs, int index) {
  check_open();
  sensors_->finish(*world_, sensor_frame(obs, index));
  write_state(obs, index);
}

void Env::Impl::write_state(ArrayDict& obs, int index) const {
  const ObservationSource source = observation_source();
  for (const Modality& m : modalities()) {
    if (m.write && obs.contains(m.name)) m.write(source, obs[m.name].item(index));
  }
}

void Env::Impl::observe() {
  std::vector<CameraView> views = camera_views(obs_, 0);
  if (!views.empty()) {
    if (!renderer_) {
      renderer_ = std::make_unique<Renderer>(world_->model(), config_.width, config_.height);
    }
    renderer_->render(views);
  }
  finish_observation(obs_, 0);
}

}  // namespace chore
