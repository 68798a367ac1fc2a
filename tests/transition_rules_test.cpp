#include "tasks/transition_rules.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "base/error.hpp"
#include "tasks/vocabulary.hpp"
#include "test_util.hpp"

namespace chore {
namespace {

const TransitionRules& real_rules() {
  static const std::shared_ptr<const TransitionRules> rules =
      TransitionRules::load(default_tasks_dir() + "/kb/behavior-1k", dialect_knowledge_base(Domain::omnigibson).get());
  return *rules;
}

const TransitionRule& named(const std::string& name) {
  const auto& rules = real_rules().rules();
  const auto it = std::find_if(rules.begin(), rules.end(), [&](const TransitionRule& r) { return r.name == name; });
  if (it == rules.end()) throw Error("no rule " + name);
  return *it;
}

std::vector<std::string> synsets(const std::vector<SynsetCount>& list) {
  std::vector<std::string> out;
  for (const SynsetCount& s : list) out.push_back(s.synset + " x" + std::to_string(s.count));
  return out;
}

using Names = std::vector<std::string>;

// The shipped files, every synset known to BEHAVIOR-1K's knowledge base (the
// load checks it): 2815 rules over the ten families, as bddl's transition_map.
TEST(TransitionRules, ReadsTheKnowledgeBasesFiles) {
  const TransitionRules& rules = real_rules();
  std::map<std::string, int> per_family;
  for (const TransitionRule& r : rules.rules()) ++per_family[to_string(r.family)];
  const std::map<std::string, int> expected = {{"dicing", 416},
                                               {"heat_cook", 32},
                                               {"melting", 26},
                                               {"mixing_stick", 14},
                                               {"single_toggleable_machine", 39},
                                               {"slicing", 207},
                                               {"substance_cooking", 334},
                                               {"substance_watercooking", 6},
                                               {"washer_nonparticleremover", 1651},
                                               {"washer_particleremover", 90}};
  EXPECT_EQ(per_family, expected);
  EXPECT_EQ(rules.rules().size(), 2815u);
}

// Known answers, one per family, as the files state them.
TEST(TransitionRules, KnownAnswersPerFamily) {
  const TransitionRule& apple = named("apple.n.01-slicing");
  EXPECT_EQ(apple.family, TransitionFamily::slicing);
  EXPECT_EQ(synsets(apple.inputs), Names{"apple.n.01 x1"});
  EXPECT_EQ(synsets(apple.outputs), Names{"half__apple.n.01 x2"});

  const TransitionRule& cookies = named("sugar_cookies");
  EXPECT_EQ(cookies.family, TransitionFamily::heat_cook);
  EXPECT_EQ(synsets(cookies.containers), Names{"cookie_sheet.n.01 x1"});
  EXPECT_EQ(synsets(cookies.heat_sources), Names{"oven.n.01 x1"});
  EXPECT_EQ(synsets(cookies.outputs), Names{"sugar_cookie.n.01 x6"});
  ASSERT_EQ(cookies.input_states.size(), 1u);
  EXPECT_EQ(cookies.input_states[0].predicate, "cooked");
  EXPECT_FALSE(cookies.input_states[0].value);
  ASSERT_EQ(cookies.output_states.size(), 1u);
  EXPECT_TRUE(cookies.output_states[0].value);

  // A binary state condition: the filling covers the pastry.
  const TransitionRule& tarts = named("cheese_tarts");
  const auto covered = std::find_if(tarts.input_states.begin(), tarts.input_states.end(),
                                    [](const StateCondition& c) { return c.predicate == "covered"; });
  ASSERT_NE(covered, tarts.input_states.end());
  EXPECT_EQ(covered->synsets, (Names{"pastry.n.01", "cheese_pastry_filling.n.01"}));

  const TransitionRule& smoothie = named("smoothie_0");
  EXPECT_EQ(smoothie.family, TransitionFamily::single_toggleable_machine);
  EXPECT_EQ(synsets(smoothie.machines), Names{"blender.n.01 x1"});
  EXPECT_EQ(synsets(smoothie.inputs), (Names{"ice_cube.n.01 x4", "lemon_juice.n.01 x1", "strawberry.n.01 x3"}));
  EXPECT_EQ(synsets(smoothie.outputs), Names{"smoothie.n.02 x1"});

  EXPECT_EQ(synsets(named("cappuccino").outputs), Names{"cappuccino.n.01 x1"});
  EXPECT_EQ(named("cappuccino").family, TransitionFamily::mixing_stick);
  EXPECT_EQ(synsets(named("bleu.n.01-melting").outputs), Names{"melted__bleu.n.01 x1"});
  EXPECT_EQ(synsets(named("black_bean.n.01-cooking").inputs), (Names{"black_bean.n.01 x1", "cooked__water.n.01 x1"}));
  EXPECT_EQ(synsets(named("apron.n.01-washer-saturate-cover").washed_items), Names{"apron.n.01 x1"});
  EXPECT_EQ(synsets(named("apron.n.01-washer-saturate-cover").machines), Names{"washer.n.03 x1"});

  // Stains need a solvent in the washer; dust goes with water alone, as does
  // what washer.json does not name (OmniGibson's default); rust never.
  const TransitionRules& rules = real_rules();
  EXPECT_EQ(rules.washer_solvents("dust.n.01"), std::vector<std::string>{});
  EXPECT_EQ(rules.washer_solvents("stain.n.01").value_or(std::vector<std::string>{}).size(), 11u);
  EXPECT_EQ(rules.washer_solvents("sand.n.04"), std::vector<std::string>{});
  EXPECT_EQ(rules.washer_solvents("rust.n.01"), std::nullopt);
}

TEST(TransitionRules, IndexesProducersAndConsumers) {
  const TransitionRules& rules = real_rules();
  const auto halves = rules.producing("half__apple.n.01");
  ASSERT_EQ(halves.size(), 1u);
  EXPECT_EQ(halves[0]->name, "apple.n.01-slicing");
  // A half apple is diced, raw or cooked.
  Names dicing;
  for (const TransitionRule* r : rules.consuming("half__apple.n.01")) dicing.push_back(r->name);
  std::sort(dicing.begin(), dicing.end());
  EXPECT_EQ(dicing, (Names{"cooked-half__apple.n.01-dicing", "uncooked-half__apple.n.01-dicing"}));
  EXPECT_TRUE(rules.producing("apple.n.01").empty());
}

// Bad files: a clear error naming the file, the rule and the field.
TEST(TransitionRules, BadFilesNameFileRuleAndField) {
  const auto dir = test::scratch_dir("transition_rules");
  std::filesystem::create_directories(dir / "transition_map");
  const auto write_all = [&](const std::string& slicing) {
    for (const char* family :
         {"dicing", "heat_cook", "melting", "mixing_stick", "single_toggleable_machine", "substance_cooking",
          "substance_watercooking", "washer_nonparticleremover", "washer_particleremover"}) {
      test::write_file(dir / "transition_map" / (std::string(family) + ".json"), "[]");
    }
    test::write_file(dir / "transition_map" / "washer.json", R"({"dust.n.01": []})");
    test::write_file(dir / "transition_map" / "slicing.json", slicing);
  };
  const auto error = [&](const std::string& slicing) {
    write_all(slicing);
    return test::error_of([&] { TransitionRules::load(dir.string()); });
  };
  write_all(R"([{"rule_name": "a", "input_synsets": {"apple.n.01": 1}, "output_synsets": {"half__apple.n.01": 2}}])");
  EXPECT_EQ(TransitionRules::load(dir.string())->rules().size(), 1u);

  EXPECT_NE(error(R"({"rule_name": "a"})").find("slicing.json: expected a list of rules"), std::string::npos);
  EXPECT_NE(error(R"([{"rule_name": "a", "input_synsets": {"apple.n.01": 0}, "output_synsets": {"x.n.01": 2}}])")
                .find("slicing.json: rule 0 'a': 'input_synsets' gives 'apple.n.01' a count"),
            std::string::npos);
  EXPECT_NE(error(R"([{"rule_name": "a", "input_synsets": {"apple.n.01": 1}, "output_synsets": {}}])")
                .find("'output_synsets' is empty"),
            std::string::npos);
  EXPECT_NE(error(R"([{"rule_name": "a", "input_synsets": {"apple.n.01": 1}, "output_synsets": {"x.n.01": 1},
                       "input_states": {"apple.n.01": [["cooked", "yes"]]}}])")
                .find("'input_states' must give 'apple.n.01' a list of [state, bool] pairs"),
            std::string::npos);
  EXPECT_NE(error(R"([{"rule_name": "a", "input_synsets": {"a.n.01": 1}, "output_synsets": {"b.n.01": 1}},
                      {"rule_name": "a", "input_synsets": {"a.n.01": 1}, "output_synsets": {"b.n.01": 1}}])")
                .find("rule 1 'a': a rule of this name came before"),
            std::string::npos);
  EXPECT_NE(error("[1, 2").find("slicing.json"), std::string::npos);
  // With a knowledge base, unknown synsets are named.
  write_all(R"([{"rule_name": "a", "input_synsets": {"aple.n.01": 1}, "output_synsets": {"half__apple.n.01": 2}}])");
  EXPECT_NE(test::error_of([&] {
              TransitionRules::load(dir.string(), dialect_knowledge_base(Domain::omnigibson).get());
            }).find("'input_synsets' unknown synset 'aple.n.01'"),
            std::string::npos);
  std::filesystem::remove(dir / "transition_map" / "melting.json");
  EXPECT_NE(test::error_of([&] { TransitionRules::load(dir.string()); }).find("melting.json"), std::string::npos);
}

}  // namespace
}  // namespace chore
