// A custom policy for the primitive action space: each step it picks, at
// random, one of the actions whose precondition holds now (the action_mask
// observation), so it never wastes a step on an invalid primitive.
// --policy-options "seed=N" seeds it (default 0); each env's stream restarts
// at every episode, so a run is reproducible whatever the thread count.
#include <policies/policy.hpp>

#include <cstdint>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

class MaskedRandomPolicy : public chore::Policy {
 public:
  explicit MaskedRandomPolicy(const chore::PolicySpec& spec) {
    if (spec.action_space->kind != chore::Space::Kind::discrete) {
      throw std::invalid_argument("masked_random needs a Discrete action space (--action-space primitives)");
    }
    bool has_mask = false;
    for (const auto& [name, space] : spec.observation_space->fields) has_mask |= name == "action_mask";
    if (!has_mask) throw std::invalid_argument("masked_random needs the action_mask observation");
    const std::string options = spec.options ? spec.options : "";
    if (!options.empty()) {
      if (options.rfind("seed=", 0) != 0) {
        throw std::invalid_argument("masked_random: unknown options '" + options + "' (known: seed=N)");
      }
      try {
        seed_ = std::stoull(options.substr(5));
      } catch (const std::exception&) {
        throw std::invalid_argument("masked_random: seed=N needs a number, got '" + options + "'");
      }
    }
  }

  void reset(std::span<const int> env_ids) override {
    for (int id : env_ids) rng(id).seed(seed_ + static_cast<uint64_t>(id));
  }

  void act(const chore::Batch& batch, std::span<float> actions) override {
    const chore::Array& mask = (*batch.obs)["action_mask"];
    const int n = mask.shape[1];
    for (int row = 0; row < batch.size(); ++row) {
      const auto* allowed = static_cast<const std::uint8_t*>(mask.item(row));
      std::vector<int> choices;
      for (int a = 0; a < n; ++a) {
        if (allowed[a]) choices.push_back(a);
      }
      // Nothing allowed (rare): any action; the env counts the invalid one.
      std::mt19937_64& r = rng(batch.env_ids[row]);
      actions[row] = static_cast<float>(
          choices.empty() ? 0 : choices[std::uniform_int_distribution<size_t>(0, choices.size() - 1)(r)]);
    }
  }

 private:
  std::mt19937_64& rng(int env_id) {
    while (static_cast<int>(rngs_.size()) <= env_id) rngs_.emplace_back(seed_ + rngs_.size());
    return rngs_[env_id];
  }

  uint64_t seed_ = 0;
  std::vector<std::mt19937_64> rngs_;
};

}  // namespace

CHORE_POLICY_PLUGIN(MaskedRandomPolicy)
