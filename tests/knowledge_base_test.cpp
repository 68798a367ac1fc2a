#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <set>

#include "base/error.hpp"
#include "tasks/knowledge_base.hpp"
#include "tasks/vocabulary.hpp"
#include "test_util.hpp"

namespace chore {
namespace {

using States = std::vector<ExtendedState>;
using Names = std::set<std::string>;

// The shipped knowledge base (tasks/kb), loaded once for the suite.
const KnowledgeBase& real_kb() {
  static const std::shared_ptr<const KnowledgeBase> kb = KnowledgeBase::load();
  return *kb;
}

std::shared_ptr<const KnowledgeBase> small_kb() {
  return KnowledgeBase::load(test::data_path("kb_small"));
}

Names names(const std::vector<std::string>& list) {
  return Names(list.begin(), list.end());
}

Names property_names(const KnowledgeBase& kb, const std::string& synset) {
  Names out;
  for (const auto& entry : kb.properties(synset)) out.insert(entry.first);
  return out;
}

// A scratch knowledge base directory with the given file texts.
std::string write_kb(const std::string& name, const std::string& hierarchy, const std::string& properties) {
  const auto dir = test::scratch_dir(name);
  test::write_file(dir / "hierarchy_owned.json", hierarchy);
  test::write_file(dir / "synsets_to_filtered_properties.json", properties);
  return dir.string();
}

// Each dialect names synsets of its own release: BEHAVIOR-1K's knowledge base
// (3,481 synsets, substances such as stain.n.01, text parameters such as what
// slicing makes) for omnigibson files, BEHAVIOR-100's for igibson ones.
TEST(KnowledgeBase, EachDialectHasItsRelease) {
  const auto b1k = dialect_knowledge_base(Domain::omnigibson);
  const auto b100 = dialect_knowledge_base(Domain::igibson);
  EXPECT_EQ(b1k->synsets().size(), 3481u);
  EXPECT_TRUE(b1k->contains("stain.n.01"));
  EXPECT_FALSE(b100->contains("stain.n.01"));
  EXPECT_EQ(b1k->text_parameter("apple.n.01", "sliceable", "sliceable_derivative_synset"), "half__apple.n.01");
  EXPECT_EQ(b1k->text_parameter("sink.n.01", "particleSource", "conditions"),
            R"({"water.n.06":[["toggled_on",true]]})");
  EXPECT_EQ(b1k->parameter("apple.n.01", "cookable", "cook_temperature"), 58.0);
  EXPECT_TRUE(b1k->is_a("apple.n.01", "edible_fruit.n.01"));
  EXPECT_EQ(dialect_knowledge_base(Domain::omnigibson), b1k);  // loaded once
  // insource: a sink is a source of water in both releases, an apple of nothing.
  EXPECT_TRUE(b1k->is_source_of("sink.n.01", "water.n.06"));
  EXPECT_FALSE(b1k->is_source_of("sink.n.01", "stain.n.01"));
  EXPECT_FALSE(b1k->is_source_of("apple.n.01", "water.n.06"));
  EXPECT_TRUE(b100->is_source_of("sink.n.01", "water.n.06"));
  EXPECT_FALSE(b100->is_source_of("nonsense.n.01", "water.n.06"));
}

TEST(KnowledgeBase, CountsSynsetsOfBothFiles) {
  // 756 synsets in the hierarchy (393 of them non-leaves) plus 824 only in the
  // properties file.
  const std::vector<std::string> all = real_kb().synsets();
  EXPECT_EQ(all.size(), 1580u);
  const auto leaves = std::count_if(all.begin(), all.end(), [](const std::string& s) { return real_kb().is_leaf(s); });
  EXPECT_EQ(leaves, 1187);
  EXPECT_TRUE(real_kb().parents("entity.n.01").empty());
  EXPECT_EQ(real_kb().children("entity.n.01"), (std::vector<std::string>{"abstraction.n.06", "physical_entity.n.01"}));
}

TEST(KnowledgeBase, LeafPropertiesComeFromThePropertiesFile) {
  EXPECT_EQ(property_names(real_kb(), "apple.n.01"), (Names{"breakable", "burnable", "cookable", "dustyable",
                                                            "freezable", "perishable", "sliceable", "stainable"}));
  // A synset outside the hierarchy is a root and a leaf.
  EXPECT_TRUE(real_kb().is_leaf("wardrobe.n.01"));
  EXPECT_TRUE(real_kb().parents("wardrobe.n.01").empty());
  EXPECT_EQ(property_names(real_kb(), "wardrobe.n.01"), (Names{"burnable", "dustyable", "openable", "stainable"}));
}

TEST(KnowledgeBase, NonLeafPropertiesAreTheIntersectionOfItsLeaves) {
  auto kb = small_kb();
  // berry = cherry & grape; fruit = apple & pear & berry; the file's own
  // "toggleable" for fruit.n.01 is ignored.
  EXPECT_EQ(kb->properties("berry.n.01"),
            (Properties{{"burnable", {{"burn_temperature", 200.0}}}, {"cookable", {{"cook_temperature", 70.0}}}}));
  // Burn temperatures differ (apple 200, pear 250), so only the property survives.
  EXPECT_EQ(kb->properties("fruit.n.01"), (Properties{{"burnable", {}}, {"cookable", {{"cook_temperature", 70.0}}}}));
  EXPECT_EQ(property_names(*kb, "container.n.01"), (Names{"breakable"}));
  EXPECT_EQ(property_names(*kb, "crockery.n.01"), (Names{"breakable", "stainable"}));
  EXPECT_TRUE(kb->properties("root.n.01").empty());
  // Real data: fruit.n.01's own entry (freezable, perishable, sliceable) loses
  // to what all its leaves share.
  EXPECT_EQ(property_names(real_kb(), "fruit.n.01"), (Names{"burnable", "cookable", "perishable"}));
}

TEST(KnowledgeBase, RepeatedSynsetsMergeTheirParents) {
  auto kb = small_kb();
  EXPECT_EQ(kb->synsets().size(), 12u);
  EXPECT_EQ(kb->parents("bowl.n.01"), (std::vector<std::string>{"container.n.01", "crockery.n.01"}));
  EXPECT_EQ(kb->ancestors("bowl.n.01"), (std::vector<std::string>{"container.n.01", "crockery.n.01", "root.n.01"}));
  EXPECT_EQ(kb->children("crockery.n.01"), (std::vector<std::string>{"bowl.n.01"}));
  EXPECT_TRUE(kb->is_leaf("jar.n.01"));
  EXPECT_TRUE(kb->ancestors("jar.n.01").empty());
  EXPECT_EQ(names(real_kb().parents("apple.n.01")), (Names{"edible_fruit.n.01", "pome.n.01"}));
}

TEST(KnowledgeBase, IsAFollowsTheRealHierarchy) {
  const KnowledgeBase& kb = real_kb();
  EXPECT_EQ(names(kb.ancestors("pumpkin.n.02")), (Names{"vegetable.n.01", "produce.n.01", "food.n.02", "solid.n.01",
                                                        "matter.n.03", "physical_entity.n.01", "entity.n.01"}));
  EXPECT_TRUE(kb.is_a("pumpkin.n.02", "pumpkin.n.02"));
  EXPECT_TRUE(kb.is_a("pumpkin.n.02", "vegetable.n.01"));
  EXPECT_TRUE(kb.is_a("pumpkin.n.02", "entity.n.01"));
  EXPECT_FALSE(kb.is_a("pumpkin.n.02", "fruit.n.01"));
  EXPECT_FALSE(kb.is_a("vegetable.n.01", "pumpkin.n.02"));
  EXPECT_TRUE(kb.is_a("apple.n.01", "fruit.n.01"));  // through both parents
  EXPECT_FALSE(kb.is_a("wardrobe.n.01", "entity.n.01"));
}

TEST(KnowledgeBase, ExtendedStatesFollowTableA5) {
  using S = ExtendedState;
  const KnowledgeBase& kb = real_kb();
  // cookable, burnable, freezable, sliceable, breakable, dustyable, stainable
  EXPECT_EQ(kb.extended_states("apple.n.01"),
            (States{S::temperature, S::max_temperature, S::covered_level, S::sliced_state, S::broken_state}));
  // soakable, burnable, breakable, stainable, cleaningTool
  EXPECT_EQ(kb.extended_states("rag.n.01"),
            (States{S::temperature, S::max_temperature, S::soaked_level, S::covered_level, S::broken_state}));
  // toggleable, waterSource, dustyable, stainable
  EXPECT_EQ(kb.extended_states("sink.n.01"), (States{S::covered_level, S::toggled_state}));
  // breakable, dustyable, stainable
  EXPECT_EQ(kb.extended_states("cup.n.01"), (States{S::covered_level, S::broken_state}));
  // freezable, liquid
  EXPECT_EQ(kb.extended_states("water.n.06"), (States{S::temperature}));
  EXPECT_STREQ(to_string(S::soaked_level), "soaked_level");
}

TEST(KnowledgeBase, ParametersAreRealNumbers) {
  const KnowledgeBase& kb = real_kb();
  EXPECT_DOUBLE_EQ(kb.parameter("newspaper.n.03", "burnable", "burn_temperature").value(), 232.77777777777777);
  EXPECT_DOUBLE_EQ(kb.parameter("pumpkin.n.02", "cookable", "cook_temperature").value(), 204.44444444444446);
  EXPECT_DOUBLE_EQ(kb.parameter("stove.n.01", "heatSource", "temperature").value(), 500.0);
  EXPECT_EQ(kb.parameter("stove.n.01", "heatSource", "requires_toggled_on"), 1.0);
  EXPECT_EQ(kb.parameter("stove.n.01", "heatSource", "requires_closed"), 0.0);
  EXPECT_EQ(kb.parameter("oven.n.01", "heatSource", "distance_threshold"), std::nullopt);
  EXPECT_EQ(kb.parameter("handle.n.01", "burnable", "burn_temperature"), std::nullopt);
  EXPECT_EQ(kb.parameter("apple.n.01", "soakable", "anything"), std::nullopt);
  // apple and pear agree, so their parent pome.n.01 keeps the value.
  EXPECT_DOUBLE_EQ(kb.parameter("pome.n.01", "cookable", "cook_temperature").value(), 100.0);
}

// OmniGibson's particleRemover rule, from BEHAVIOR-1K's data: a sponge takes
// ink off saturated with any of eleven solvents, mud saturated with water,
// dust as it is; emery paper takes incisions off as it is and cannot take
// dust (null); a rag cannot take rust (null); sand, which no condition names,
// by the rag's default for visual substances (as it is).
TEST(KnowledgeBase, ARemoverTakesASubstanceOffAsItsConditionsSay) {
  const auto b1k = dialect_knowledge_base(Domain::omnigibson);
  const auto ink = b1k->remover_solvents("sponge.n.01", "ink.n.01");
  ASSERT_TRUE(ink.has_value());
  EXPECT_EQ(ink->size(), 11u);
  EXPECT_NE(std::find(ink->begin(), ink->end(), "rubbing_alcohol.n.01"), ink->end());
  EXPECT_EQ(b1k->remover_solvents("sponge.n.01", "mud.n.03"), std::vector<std::string>{"water.n.06"});
  EXPECT_EQ(b1k->remover_solvents("sponge.n.01", "dust.n.01"), std::vector<std::string>{});
  EXPECT_EQ(b1k->remover_solvents("emery_paper.n.01", "incision.n.01"), std::vector<std::string>{});
  EXPECT_EQ(b1k->remover_solvents("emery_paper.n.01", "dust.n.01"), std::nullopt);
  EXPECT_EQ(b1k->remover_solvents("rag.n.01", "rust.n.01"), std::nullopt);
  EXPECT_EQ(b1k->remover_solvents("rag.n.01", "sand.n.04"), std::vector<std::string>{});
  EXPECT_EQ(b1k->remover_solvents("apple.n.01", "dust.n.01"), std::nullopt);  // no particleRemover
}

TEST(KnowledgeBase, PredicateHelpersReadTheData) {
  const KnowledgeBase& kb = real_kb();
  EXPECT_TRUE(kb.is_liquid("water.n.06"));
  EXPECT_TRUE(kb.is_substance("water.n.06"));
  EXPECT_FALSE(kb.is_substance("apple.n.01"));
  EXPECT_TRUE(kb.is_cleaning_tool("rag.n.01"));
  // towel.n.01's own entry lacks cleaningTool, but all four of its towels have it.
  EXPECT_TRUE(kb.is_cleaning_tool("towel.n.01"));
  EXPECT_FALSE(kb.is_cleaning_tool("cup.n.01"));
  EXPECT_TRUE(kb.is_slicer("knife.n.01"));
  EXPECT_TRUE(kb.is_openable("wardrobe.n.01"));
  EXPECT_FALSE(kb.is_openable("apple.n.01"));
}

TEST(KnowledgeBase, UnknownSynsetNamesOtherSenses) {
  const KnowledgeBase& kb = real_kb();
  EXPECT_FALSE(kb.contains("apple.n.99"));
  const std::string e = test::error_of([&] { kb.properties("apple.n.99"); });
  EXPECT_NE(e.find("unknown synset 'apple.n.99'"), std::string::npos) << e;
  EXPECT_NE(e.find("apple.n.01"), std::string::npos) << e;
  EXPECT_EQ(test::error_of([&] { kb.is_leaf("foo.n.99"); }), "unknown synset 'foo.n.99'");
  EXPECT_EQ(test::error_of([&] { kb.is_a("apple.n.01", "frut.n.01"); }), "unknown synset 'frut.n.01'");
}

TEST(KnowledgeBase, MalformedFileGivesFileLineAndColumn) {
  const std::string dir = write_kb("kb_malformed", R"({"name": "a.n.01"})", "{\n  \"a.n.01\": {\n    oops\n}\n");
  const std::string e = test::error_of([&] { KnowledgeBase::load(dir); });
  EXPECT_NE(e.find("synsets_to_filtered_properties.json:3:"), std::string::npos) << e;
}

TEST(KnowledgeBase, BadFieldsAreNamed) {
  const std::string one_leaf = R"({"name": "a.n.01"})";
  std::string e = test::error_of([&] {
    KnowledgeBase::load(write_kb("kb_bad_param", one_leaf, R"({"a.n.01": {"cookable": {"cook_temperature": "hot"}}})"));
  });
  EXPECT_NE(e.find("synsets_to_filtered_properties.json: a.n.01.cookable.cook_temperature: expected a number"),
            std::string::npos)
      << e;
  e = test::error_of(
      [&] { KnowledgeBase::load(write_kb("kb_no_name", R"({"name": "a.n.01", "children": [{}]})", "{}")); });
  EXPECT_NE(e.find("hierarchy_owned.json.children[0]: missing field 'name'"), std::string::npos) << e;
  e = test::error_of([&] { KnowledgeBase::load(write_kb("kb_unannotated", one_leaf, "{}")); });
  EXPECT_NE(e.find("leaf 'a.n.01' has no entry"), std::string::npos) << e;
  // b is a's child in one place and its parent in another.
  e = test::error_of([&] {
    KnowledgeBase::load(write_kb("kb_cycle",
                                 R"({"name": "r.n.01", "children": [
                                      {"name": "a.n.01", "children": [{"name": "b.n.01"}]},
                                      {"name": "b.n.01", "children": [{"name": "a.n.01"}]}]})",
                                 "{}"));
  });
  EXPECT_NE(e.find("hierarchy has a cycle"), std::string::npos) << e;
}

TEST(KnowledgeBase, TasksDirComesFromTheEnvironment) {
  const char* before = std::getenv("CHORE_TASKS");
  const std::string saved = before ? before : "";
  setenv("CHORE_TASKS", "/some/where", 1);
  EXPECT_EQ(default_tasks_dir(), "/some/where");
  unsetenv("CHORE_TASKS");
  EXPECT_TRUE(default_tasks_dir().ends_with("tasks")) << default_tasks_dir();
  if (before) setenv("CHORE_TASKS", saved.c_str(), 1);
}

}  // namespace
}  // namespace chore
