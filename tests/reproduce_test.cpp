// `chore reproduce`: a small table (one activity, one method, two seeds,
// symbolic primitives) run through the real chore executable, its report
// checked against the runs' own evaluations, then resumed after parts of it
// are lost and broken.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "app/baselines_report.hpp"
#include "app/reproduce.hpp"

namespace chore {
namespace {
namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

nlohmann::json read_json(const fs::path& path) {
  return nlohmann::json::parse(read_text(path));
}

// Runs `chore reproduce` on the small table (`cells`: its methods and seeds);
// returns its exit status, its log in `log`.
int reproduce_small_table(const fs::path& out, std::string& log, bool videos = false, const std::string& extra = "",
                          const std::string& cells = " --methods rl-prim --seeds 0 1") {
  const fs::path log_file = out.string() + ".log";
  const std::string command = std::string(CHORE_BINARY) + " reproduce --activities collect_trash" + cells +
                              " --steps 60 --mode symbolic --eval-episodes 2 --generalisation-seeds 100-101" +
                              (videos ? "" : " --no-videos") + extra + " --out " + out.string() + " 2> " +
                              log_file.string();
  const int status = std::system(command.c_str());
  log = read_text(log_file);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(Reproduce, PaperTableA13) {
  EXPECT_DOUBLE_EQ(paper_q("rl-prim", "collect_trash").mean, 0.49);
  EXPECT_DOUBLE_EQ(paper_q("rl-prim-hist", "clean_table").mean, 0.88);
  EXPECT_DOUBLE_EQ(paper_q("rl-prim-hist", "clean_table").std, 0.02);
  EXPECT_DOUBLE_EQ(paper_q("rl-vmc", "store_decoration").mean, 0.0);
  EXPECT_TRUE(std::isnan(paper_q("rl-prim", "some_other_activity").mean));
}

TEST(Reproduce, ReportsTheRunsOwnEvaluationsAndResumesWhatIsMissing) {
  const fs::path out = fs::path(CHORE_TEST_OUTPUT) / ("reproduce_" + std::to_string(getpid()));
  fs::remove_all(out);
  fs::create_directories(out.parent_path());
  std::string log;
  ASSERT_EQ(reproduce_small_table(out, log), 0) << log;

  const fs::path runs = out / "runs" / "symbolic" / "collect_trash";
  const nlohmann::json table = read_json(out / "baselines.json");
  ASSERT_EQ(table["runs"].size(), 2u);
  ASSERT_EQ(table["rows"].size(), 1u);
  EXPECT_TRUE(table["missing"].empty());
  EXPECT_TRUE(table["failures"].empty());

  // Each run's numbers are its own evaluation's; the row is their mean and
  // population std over the training seeds.
  double q[2];
  for (int s = 0; s < 2; ++s) {
    const nlohmann::json& run = table["runs"][s];
    EXPECT_EQ(run["seed"], s);
    const nlohmann::json eval = read_json(runs / ("rl-prim_seed" + std::to_string(s)) / "eval_seed0.json")[0];
    EXPECT_EQ(eval["episodes_per_seed"], 2);
    EXPECT_EQ(eval["per_episode"].size(), 2u);
    q[s] = eval["q"]["mean"].get<double>();
    EXPECT_DOUBLE_EQ(run["q_seed0"].get<double>(), q[s]);
    const nlohmann::json fresh = read_json(runs / ("rl-prim_seed" + std::to_string(s)) / "eval_generalisation.json")[0];
    EXPECT_EQ(fresh["per_seed"].size(), 2u);  // seeds 100 and 101, one episode each
    EXPECT_DOUBLE_EQ(run["q_generalisation"].get<double>(), fresh["q"]["mean"].get<double>());
  }
  const nlohmann::json& row = table["rows"][0];
  EXPECT_EQ(row["runs"], 2);
  EXPECT_NEAR(row["q_seed0"]["mean"].get<double>(), (q[0] + q[1]) / 2, 1e-12);
  EXPECT_NEAR(row["q_seed0"]["std"].get<double>(), std::abs(q[0] - q[1]) / 2, 1e-12);
  EXPECT_DOUBLE_EQ(row["paper_q"]["mean"].get<double>(), 0.49);
  const std::string md = read_text(out / "baselines.md");
  EXPECT_NE(md.find("(paper 0.49 ± 0.04)"), std::string::npos) << md;
  EXPECT_NE(md.find("| RL-Prim. |"), std::string::npos) << md;
  EXPECT_NE(md.find("| policy failure (not applied) |"), std::string::npos) << "the default rule\n" << md;
  // Greedy beside sampled, over the same episodes; the first ten sampled
  // episodes' Q (here both of them).
  for (int s = 0; s < 2; ++s) {
    const fs::path dir = runs / ("rl-prim_seed" + std::to_string(s));
    const nlohmann::json greedy = read_json(dir / "eval_seed0_greedy.json")[0];
    EXPECT_EQ(greedy["per_episode"].size(), 2u);
    EXPECT_EQ(greedy["seeds"], read_json(dir / "eval_seed0.json")[0]["seeds"]);
    EXPECT_DOUBLE_EQ(table["runs"][s]["q_seed0_greedy"].get<double>(), greedy["q"]["mean"].get<double>());
    EXPECT_DOUBLE_EQ(table["runs"][s]["q_seed0_first10"].get<double>(), q[s]);
  }
  EXPECT_NE(md.find("## Success score Q at evaluation seed 0, acting greedily"), std::string::npos) << md;
  // The scripted expert on the same episodes, beside the policies' failures.
  const nlohmann::json& expert = table["expert"]["collect_trash"];
  EXPECT_EQ(expert["episodes"], 2);
  EXPECT_GT(expert["primitives"].get<int>(), 0);
  EXPECT_NE(md.find("| CollectTrash | scripted expert |"), std::string::npos) << md;
  // Set against itself (as a study's variant against its reference): a run
  // here beats a run there half the time, and the runs cannot tell.
  const fs::path compared = out.string() + "_compared";
  fs::remove_all(compared);
  fs::copy(out, compared, fs::copy_options::recursive);
  ASSERT_EQ(reproduce_small_table(compared, log, false, " --report-only --compare-with " + out.string()), 0) << log;
  const nlohmann::json compared_table = read_json(compared / "baselines.json");
  const nlohmann::json& against = compared_table["comparisons"];
  ASSERT_EQ(against.size(), 1u) << against;
  EXPECT_DOUBLE_EQ(against[0]["probability_of_improvement"]["point"].get<double>(), 0.5);
  EXPECT_EQ(against[0]["other_method"], "rl-prim");
  EXPECT_NE(read_text(compared / "baselines.md").find("| CollectTrash | RL-Prim. |"), std::string::npos);
  EXPECT_EQ(reproduce_small_table(compared, log, false, " --report-only --compare-method rl-prim=rl-prim-hist"), 2);
  EXPECT_NE(log.find("--compare-method needs --compare-with"), std::string::npos) << log;
  EXPECT_GT(fs::file_size(out / "curves" / "collect_trash.png"), 1000u);
  // Interval estimates over the runs: the statistic itself, and a bootstrap
  // interval around it within the runs' range; the performance profile drawn.
  const nlohmann::json& mean = row["q_seed0_intervals"]["mean"];
  EXPECT_NEAR(mean["point"].get<double>(), (q[0] + q[1]) / 2, 1e-12);
  EXPECT_DOUBLE_EQ(mean["lo"].get<double>(), std::min(q[0], q[1]));  // both runs drawn alike: 1/4 of resamples
  EXPECT_DOUBLE_EQ(mean["hi"].get<double>(), std::max(q[0], q[1]));
  EXPECT_NEAR(row["q_seed0_intervals"]["iqm"]["point"].get<double>(), (q[0] + q[1]) / 2, 1e-12);  // n < 4
  EXPECT_TRUE(table["orderings"].empty()) << "one method: nothing to order";
  EXPECT_NE(md.find("## Interval estimates of Q at evaluation seed 0"), std::string::npos) << md;
  EXPECT_GT(fs::file_size(out / "profiles" / "collect_trash.png"), 1000u);

  // Seed 1 loses its evaluations (a stop before they ended): the next
  // invocation leaves seed 0 alone and evaluates seed 1's trained policy again,
  // from its checkpoint, without training it again.
  const fs::path seed0 = runs / "rl-prim_seed0", seed1 = runs / "rl-prim_seed1";
  const auto seed0_written = fs::last_write_time(seed0 / "cell.json");
  const std::string metrics = read_text(seed1 / "metrics.csv");
  fs::remove(seed1 / "cell.json");
  fs::remove(seed1 / "eval_seed0.json");
  ASSERT_EQ(reproduce_small_table(out, log), 0) << log;
  EXPECT_NE(log.find("collect_trash rl-prim seed 0: done already"), std::string::npos) << log;
  EXPECT_NE(log.find("collect_trash rl-prim seed 1: training"), std::string::npos) << log;
  EXPECT_EQ(fs::last_write_time(seed0 / "cell.json"), seed0_written);
  EXPECT_EQ(read_text(seed1 / "metrics.csv"), metrics);  // resumed at its end: nothing trained
  EXPECT_DOUBLE_EQ(read_json(out / "baselines.json")["runs"][1]["q_seed0"].get<double>(), q[1]);

  // A run that cannot go on (its checkpoint broken) is reported and left out;
  // the exit status says so, the other run is still in the table.
  fs::remove(seed1 / "cell.json");
  std::ofstream(seed1 / "checkpoint.pt", std::ios::trunc) << "garbage";
  EXPECT_EQ(reproduce_small_table(out, log), 1) << log;
  EXPECT_NE(log.find("seed 1: FAILED"), std::string::npos) << log;
  EXPECT_NE(log.find("not a chore checkpoint"), std::string::npos) << log;
  const nlohmann::json partial = read_json(out / "baselines.json");
  EXPECT_EQ(partial["runs"].size(), 1u);
  EXPECT_EQ(partial["missing"][0], "collect_trash rl-prim seed 1");
  EXPECT_EQ(partial["failures"].size(), 1u);
  EXPECT_NE(read_text(out / "baselines.md").find("(1 of 2 seeds)"), std::string::npos);

  // With videos: the run left (seed 0) gets collect_trash's; the video an
  // earlier invocation made of another activity stays in the report while its
  // file and its run are here, and goes once its run has been moved away.
  const fs::path other_run = out / "runs" / "symbolic" / "store_decoration" / "rl-prim-hist_seed2";
  fs::create_directories(other_run);
  std::ofstream(other_run / "cell.json") << "{}";
  fs::create_directories(out / "videos");
  std::ofstream(out / "videos" / "store_decoration.mp4") << "an earlier video";
  nlohmann::json with_other = partial;
  with_other["videos"] = {{"store_decoration",
                           {{"file", (out / "videos" / "store_decoration.mp4").string()},
                            {"method", "rl-prim-hist"},
                            {"run", other_run.string()},
                            {"seed", 2}}},
                          {"clean_table",
                           {{"file", (out / "videos" / "store_decoration.mp4").string()},
                            {"method", "rl-prim"},
                            {"run", (out / "moved_away").string()},
                            {"seed", 1}}}};
  std::ofstream(out / "baselines.json", std::ios::trunc) << with_other.dump();
  EXPECT_EQ(reproduce_small_table(out, log, true), 1) << log;
  nlohmann::json videos = read_json(out / "baselines.json")["videos"];
  EXPECT_EQ(videos["store_decoration"]["seed"], 2);
  EXPECT_FALSE(videos.contains("clean_table")) << videos;
  EXPECT_EQ(videos["collect_trash"]["run"], seed0.string());
  EXPECT_GT(fs::file_size(out / "videos" / "collect_trash.mp4"), 1000u);

  // A done run's cell.json damaged by hand: an error naming the file and the
  // field (it was a JSON type error reaching "internal error"), and the file
  // is left as it was.
  nlohmann::json damaged = read_json(seed0 / "cell.json");
  damaged["seed0"]["q"]["mean"] = "high";
  std::ofstream(seed0 / "cell.json", std::ios::trunc) << damaged.dump();
  EXPECT_EQ(reproduce_small_table(out, log), 2) << log;
  EXPECT_NE(log.find("chore: error: " + (seed0 / "cell.json").string() + ".seed0.q.mean"), std::string::npos) << log;
  EXPECT_EQ(read_json(seed0 / "cell.json"), damaged);
  fs::remove_all(out);
}

// --set reaches the new runs of the methods it is for (ppo.* the PPO ones),
// is part of what a done cell must match, and a checkpoint trained with other
// settings is not resumed as if it were this table's.
TEST(Reproduce, SettingsReachTheirMethodsRunsAndGuardResuming) {
  const fs::path out = fs::path(CHORE_TEST_OUTPUT) / ("reproduce_settings_" + std::to_string(getpid()));
  fs::remove_all(out);
  fs::create_directories(out.parent_path());
  const std::string settings =
      " --set ppo.epochs=2 --set sac.lr=0.001 --set env.policy_failure_rule=paper --set env.policy_failure_repeats=2";
  std::string log;
  ASSERT_EQ(reproduce_small_table(out, log, false, settings), 0) << log;
  const fs::path seed1 = out / "runs" / "symbolic" / "collect_trash" / "rl-prim_seed1";
  const nlohmann::json config = read_json(seed1 / "config.json");
  EXPECT_EQ(config["ppo"]["epochs"], 2);
  EXPECT_EQ(config["env"]["policy_failure_rule"], "paper");
  EXPECT_DOUBLE_EQ(config["sac"]["lr"].get<double>(), 3e-4);  // SAC's setting is not RL-Prim.'s
  EXPECT_EQ(read_json(seed1 / "cell.json")["spec"]["settings"],
            nlohmann::json({"ppo.epochs=2", "env.policy_failure_rule=paper", "env.policy_failure_repeats=2"}));
  const nlohmann::json protocol = read_json(out / "baselines.json")["protocol"];
  EXPECT_EQ(protocol["settings"], nlohmann::json({"ppo.epochs=2", "sac.lr=0.001", "env.policy_failure_rule=paper",
                                                  "env.policy_failure_repeats=2"}));
  EXPECT_EQ(protocol["policy_failure"], nlohmann::json({{"rule", "paper"}, {"repeats", 2}}));
  const std::string md = read_text(out / "baselines.md");
  EXPECT_NE(md.find("`ppo.epochs=2`"), std::string::npos) << md;
  // The failure table names the rule the runs ran under.
  EXPECT_NE(md.find("| policy failure (same failed primitive 2x) |"), std::string::npos) << md;

  // Without the settings the cells are not done, and their checkpoints are
  // other runs than the ones asked for: refused, exit 2, nothing run.
  fs::remove(seed1 / "cell.json");
  const std::string metrics = read_text(seed1 / "metrics.csv");
  EXPECT_EQ(reproduce_small_table(out, log), 2) << log;
  EXPECT_NE(log.find("rl-prim_seed0/checkpoint.pt is a run with other settings (env/policy_failure_repeats, "
                     "env/policy_failure_rule, ppo/epochs)"),
            std::string::npos)
      << log;
  EXPECT_EQ(read_text(seed1 / "metrics.csv"), metrics);
  // With them seed 1 is resumed (nothing left to train) and evaluated again.
  ASSERT_EQ(reproduce_small_table(out, log, false, settings), 0) << log;
  EXPECT_EQ(read_text(seed1 / "metrics.csv"), metrics);
  EXPECT_TRUE(fs::exists(seed1 / "cell.json"));
  fs::remove_all(out);
}

// --seeds-for gives one method its own training seeds (RL-VMC may stay at
// three while the primitive methods run more): its runs are the table's, none
// is missing, and the report says which seeds each method has.
TEST(Reproduce, AMethodMayHaveItsOwnSeeds) {
  const fs::path out = fs::path(CHORE_TEST_OUTPUT) / ("reproduce_seeds_for_" + std::to_string(getpid()));
  fs::remove_all(out);
  fs::create_directories(out.parent_path());
  std::string log;
  const std::string cells = " --methods rl-prim rl-prim-hist --seeds 0 --seeds-for rl-prim=0-1";
  ASSERT_EQ(reproduce_small_table(out, log, false, "", cells), 0) << log;
  const nlohmann::json table = read_json(out / "baselines.json");
  EXPECT_EQ(table["runs"].size(), 3u);
  EXPECT_TRUE(table["missing"].empty()) << table["missing"];
  EXPECT_EQ(table["protocol"]["training_seeds_by_method"],
            nlohmann::json({{"rl-prim", {0, 1}}, {"rl-prim-hist", {0}}}));
  ASSERT_EQ(table["rows"].size(), 2u);
  EXPECT_EQ(table["rows"][0]["runs"], 2);
  EXPECT_EQ(table["rows"][1]["runs"], 1);
  EXPECT_TRUE(fs::exists(out / "runs" / "symbolic" / "collect_trash" / "rl-prim_seed1" / "cell.json"));
  EXPECT_FALSE(fs::exists(out / "runs" / "symbolic" / "collect_trash" / "rl-prim-hist_seed1"));
  ASSERT_EQ(table["orderings"].size(), 1u);  // RL-Prim.Hist. against RL-Prim., one run against two
  EXPECT_EQ(table["orderings"][0]["verdict"], "too few runs to tell");
  const std::string md = read_text(out / "baselines.md");
  EXPECT_NE(md.find("training seeds 0 (RL-Prim.: 0 1);"), std::string::npos) << md;
  EXPECT_EQ(md.find(" seeds)"), std::string::npos) << "no cell is short of its seeds:\n" << md;
  EXPECT_NE(md.find("- Code: commit "), std::string::npos) << md;

  // --report-only trains nothing and names the commit as the report's, not the runs'.
  const fs::path seed1 = out / "runs" / "symbolic" / "collect_trash" / "rl-prim_seed1";
  const auto written = fs::last_write_time(seed1 / "cell.json");
  ASSERT_EQ(reproduce_small_table(out, log, false, " --report-only", cells), 0) << log;
  EXPECT_EQ(log.find("training"), std::string::npos) << log;
  EXPECT_EQ(fs::last_write_time(seed1 / "cell.json"), written);
  EXPECT_EQ(read_json(out / "baselines.json")["runs"].size(), 3u);
  EXPECT_NE(read_text(out / "baselines.md").find("- Report written at commit "), std::string::npos);

  // Bad --seeds-for: exit 2 naming it, nothing run.
  const fs::path other = out / "other";
  for (const auto& [bad, message] : std::vector<std::pair<std::string, std::string>>{
           {" --seeds-for rl-vmc=0", "--seeds-for rl-vmc: not one of the table's --methods"},
           {" --seeds-for rl-prim", "--seeds-for 'rl-prim': expected METHOD=SEEDS"},
           {" --seeds-for rl-prim=0 --seeds-for rl-prim=1", "--seeds-for rl-prim: given twice"},
           {" --seeds-for rl-prim=3-1", "--seeds-for rl-prim '3-1': B is below A"}}) {
    EXPECT_EQ(reproduce_small_table(other, log, false, bad), 2) << bad << "\n" << log;
    EXPECT_NE(log.find(message), std::string::npos) << bad << "\n" << log;
    EXPECT_FALSE(fs::exists(other / "runs")) << bad;
  }
  fs::remove_all(out);
}

}  // namespace
}  // namespace chore
