#include "tasks/transition_rules.hpp"

#include <limits>
#include <set>

#include "base/error.hpp"
#include "base/json_file.hpp"

namespace chore {

const char* to_string(TransitionFamily family) {
  switch (family) {
#define CHORE_TRANSITION_FAMILY_NAME(name) \
  case TransitionFamily::name:             \
    return #name;
    CHORE_TRANSITION_FAMILIES(CHORE_TRANSITION_FAMILY_NAME)
#undef CHORE_TRANSITION_FAMILY_NAME
  }
  return "?";
}

namespace {

constexpr int kMaxCount = 1000;  // of one synset in a rule; the files' largest is 12

// Reads rules of one family's file, `where` naming the rule in errors.
class RuleReader {
 public:
  RuleReader(const nlohmann::json& rule, std::string where, const KnowledgeBase* kb)
      : rule_(rule), where_(std::move(where)), kb_(kb) {}

  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    throw Error(where_ + ": '" + field + "' " + message);
  }

  std::string synset(const std::string& field, const std::string& name) const {
    if (name.empty()) fail(field, "names an empty synset");
    if (kb_) {
      const std::string why = kb_->unknown(name);
      if (!why.empty()) fail(field, why);
    }
    return name;
  }

  // {synset: count}; null or absent: none.
  std::vector<SynsetCount> counts(const char* field) const {
    std::vector<SynsetCount> out;
    if (!rule_.contains(field) || rule_[field].is_null()) return out;
    const nlohmann::json& v = rule_[field];
    if (!v.is_object()) fail(field, "must be an object of synset counts");
    for (const auto& item : v.items()) {
      const nlohmann::json& n = item.value();
      if (!n.is_number_integer() || n.get<int64_t>() < 1 || n.get<int64_t>() > kMaxCount) {
        fail(field, "gives '" + item.key() + "' a count that is not an integer in 1.." + std::to_string(kMaxCount));
      }
      out.push_back({synset(field, item.key()), static_cast<int>(n.get<int64_t>())});
    }
    return out;
  }

  // {"a" or "a,b": [[predicate, bool], ...]}; null or absent: none.
  std::vector<StateCondition> states(const char* field) const {
    std::vector<StateCondition> out;
    if (!rule_.contains(field) || rule_[field].is_null()) return out;
    const nlohmann::json& v = rule_[field];
    if (!v.is_object()) fail(field, "must be an object of state lists");
    for (const auto& item : v.items()) {
      std::vector<std::string> synsets;
      const std::string& key = item.key();
      for (size_t start = 0;;) {
        const size_t comma = key.find(',', start);
        synsets.push_back(synset(field, key.substr(start, comma - start)));
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
      if (synsets.size() > 2) fail(field, "relates more than two synsets in '" + key + "'");
      if (!item.value().is_array()) fail(field, "must give '" + key + "' a list of [state, bool] pairs");
      for (const nlohmann::json& pair : item.value()) {
        if (!pair.is_array() || pair.size() != 2 || !pair[0].is_string() || !pair[1].is_boolean()) {
          fail(field, "must give '" + key + "' a list of [state, bool] pairs");
        }
        out.push_back({pair[0].get<std::string>(), synsets, pair[1].get<bool>()});
      }
    }
    return out;
  }

 private:
  const nlohmann::json& rule_;
  std::string where_;
  const KnowledgeBase* kb_;
};

}  // namespace

std::shared_ptr<const TransitionRules> TransitionRules::load(const std::string& dir, const KnowledgeBase* kb) {
  std::shared_ptr<TransitionRules> out(new TransitionRules());
  std::set<std::string> names;
#define CHORE_TRANSITION_FAMILY_VALUE(name) TransitionFamily::name,
  for (const TransitionFamily family : {CHORE_TRANSITION_FAMILIES(CHORE_TRANSITION_FAMILY_VALUE)}) {
#undef CHORE_TRANSITION_FAMILY_VALUE
    const std::string path = dir + "/transition_map/" + to_string(family) + ".json";
    const nlohmann::json file = read_json_file(path);
    if (!file.is_array()) throw Error(path + ": expected a list of rules");
    for (size_t i = 0; i < file.size(); ++i) {
      const nlohmann::json& r = file[i];
      std::string where = path + ": rule " + std::to_string(i);
      if (!r.is_object() || !r.contains("rule_name") || !r["rule_name"].is_string()) {
        throw Error(where + ": expected an object with a 'rule_name'");
      }
      TransitionRule rule{family, r["rule_name"].get<std::string>()};
      where += " '" + rule.name + "'";
      if (!names.insert(rule.name).second) throw Error(where + ": a rule of this name came before");
      const RuleReader read(r, where, kb);
      rule.inputs = read.counts("input_synsets");
      rule.outputs = read.counts("output_synsets");
      rule.input_states = read.states("input_states");
      rule.output_states = read.states("output_states");
      rule.containers = read.counts("container");
      rule.heat_sources = read.counts("heat_source");
      rule.machines = read.counts("machine");
      rule.washed_items = read.counts("washed_item");
      if (r.contains("timesteps") && !r["timesteps"].is_null()) {
        const nlohmann::json& t = r["timesteps"];
        if (!t.is_number_integer() || t.get<int64_t>() < 0 || t.get<int64_t>() > std::numeric_limits<int>::max()) {
          read.fail("timesteps", "must be null or a count of steps");
        }
        rule.timesteps = static_cast<int>(t.get<int64_t>());
      }
      if (rule.outputs.empty()) read.fail("output_synsets", "is empty: the rule makes nothing");
      if (rule.inputs.empty() && rule.washed_items.empty())
        read.fail("input_synsets", "is empty: nothing to transform");
      const size_t index = out->rules_.size();
      for (const SynsetCount& s : rule.outputs) out->producing_.emplace(s.synset, index);
      for (const SynsetCount& s : rule.inputs) out->consuming_.emplace(s.synset, index);
      out->rules_.push_back(std::move(rule));
    }
  }

  const std::string washer = dir + "/transition_map/washer.json";
  const nlohmann::json solvents = read_json_file(washer);
  if (!solvents.is_object()) throw Error(washer + ": expected an object of substances");
  for (const auto& item : solvents.items()) {
    const RuleReader read(solvents, washer, kb);
    std::optional<std::vector<std::string>>& list = out->washer_solvents_[read.synset(item.key(), item.key())];
    if (item.value().is_null()) continue;  // a substance the washer never removes
    if (!item.value().is_array()) read.fail(item.key(), "must list solvents (or be null)");
    list.emplace();
    for (const nlohmann::json& s : item.value()) {
      if (!s.is_string()) read.fail(item.key(), "must list solvents by synset");
      list->push_back(read.synset(item.key(), s.get<std::string>()));
    }
  }
  return out;
}

std::optional<std::vector<std::string>> TransitionRules::washer_solvents(const std::string& substance) const {
  const auto it = washer_solvents_.find(substance);
  return it == washer_solvents_.end() ? std::vector<std::string>{} : it->second;
}

namespace {

std::vector<const TransitionRule*> lookup(const std::vector<TransitionRule>& rules,
                                          const std::multimap<std::string, size_t>& index, const std::string& synset) {
  std::vector<const TransitionRule*> out;
  const auto [begin, end] = index.equal_range(synset);
  for (auto it = begin; it != end; ++it) out.push_back(&rules[it->second]);
  return out;
}

}  // namespace

std::vector<const TransitionRule*> TransitionRules::producing(const std::string& synset) const {
  return lookup(rules_, producing_, synset);
}

std::vector<const TransitionRule*> TransitionRules::consuming(const std::string& synset) const {
  return lookup(rules_, consuming_, synset);
}

const TransitionRules& behavior_transition_rules() {
  static const std::shared_ptr<const TransitionRules> rules = TransitionRules::load();
  return *rules;
}

}  // namespace chore
