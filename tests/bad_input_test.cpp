// The chore command line under bad input: each case exits 2 with "chore:
// error:" or CLI11's message naming the option, never 1 (an internal
// fault), a signal (an abort from a worker thread), a wrapped number or a
// half-made run folder.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/command_line.hpp"
#include "app/train_command.hpp"
#include "base/memory.hpp"
#include "base/utf8.hpp"
#include "test_util.hpp"
#include "training/checkpoint.hpp"

namespace chore {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;       // exit status, or -1 after a signal (137: killed at the time limit)
  std::string err, out;  // stderr, stdout
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

Outcome run(const std::string& args) {
  // Beside the test's own files: ctest runs the tests of this file in parallel.
  const fs::path dir = test::scratch_dir("bad_input_stderr_" +
                                         std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  // A hang (a FIFO read) ends at the time limit as a failure, not the suite's.
  const std::string command = "timeout -s KILL 300 " + std::string(CHORE_BINARY) + " " + args + " > " +
                              (dir / "stdout.txt").string() + " 2> " + (dir / "stderr.txt").string();
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(dir / "stderr.txt"), read_text(dir / "stdout.txt")};
}

void expect_error(const std::string& args, const std::string& message) {
  const Outcome r = run(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
  EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
}

TEST(BadInput, NumbersOutsideTheirRangeAreErrorsNamingIt) {
  expect_error("expert --activity store_decoration --seed -5", "--seed: '-5' is not an integer in [0, 1000000000000]");
  expect_error("train --activity store_decoration --baseline rl-prim --steps 1e20 --out x",
               "--steps: '1e20' is not an integer in [1, 10000000000]");
  expect_error("train --activity store_decoration --baseline rl-prim --steps abc --out x",
               "--steps: 'abc' is not an integer in [1, 10000000000]");
  expect_error("eval --expert --activity store_decoration --seeds 18446744073709551615",
               "--seeds '18446744073709551615': expected a seed or a range A-B of seeds in [0, 1000000000000]");
  expect_error("video --expert --activity store_decoration --out x.mp4 --fps inf",
               "--fps: 'inf' is not a number in [0.1, 240]");
}

TEST(BadInput, FailuresOfDependenciesAndWorkersAreErrors) {
  const fs::path dir = test::scratch_dir("cli_failures");
  // A chore::Error in a worker thread reaches the command, not std::terminate.
  expect_error("expert --activity '' --episodes 2 --threads 2", "chore: error: env config:");
  // std::filesystem: --out is a file.
  std::ofstream(dir / "a_file") << "x";
  expect_error("train --activity collect_trash --baseline rl-prim --out " + (dir / "a_file").string(),
               "chore: error: train: --out " + (dir / "a_file").string() + ": cannot make the folder");
  // OpenCV: no writer for the extension.
  expect_error("observe --activity store_decoration --out " + (dir / "x.jpgx").string(),
               "chore: error: observe: --out '" + (dir / "x.jpgx").string() + "' must end in .png");
  // torch: a setting it would refuse deep inside; and nothing of the run is left.
  expect_error("train --activity collect_trash --baseline rl-prim --set ppo.lr=-1 --out " + (dir / "lr").string(),
               "chore: error: --set ppo.lr=-1: ppo.lr = -1 is outside [1e-12, 1]");
  EXPECT_FALSE(fs::exists(dir / "lr"));
  expect_error("train --activity no_such_activity --baseline rl-prim --out " + (dir / "unknown").string(),
               "chore: error: unknown activity 'no_such_activity'");
  EXPECT_FALSE(fs::exists(dir / "unknown"));
}

// Files that are not files, text that is not UTF-8, tokens and paths longer
// than anyone writes, and a table of the wrong shape (issue 54): each is an
// error naming it, never a hang, a crash or "internal error".
TEST(BadInput, SpecialFilesAreRefusedBeforeTheyAreRead) {
  const fs::path dir = test::scratch_dir("cli_special_files");
  expect_error("activity check /dev/zero", "chore: error: /dev/zero: not a file (a character device)");
  const fs::path fifo = dir / "metrics.csv";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_error("plot " + fifo.string() + " --out " + (dir / "p.png").string(),
               "chore: error: " + fifo.string() + ": not a file (a FIFO); expected a metrics.csv");
  expect_error("plot " + std::string(40000, 'r') + "_seed1/metrics.csv --out " + (dir / "p.png").string(),
               "chore: error: ");
}

TEST(BadInput, TextThatIsNotUtf8IsEscapedInEveryOutput) {
  const fs::path dir = test::scratch_dir("cli_utf8");
  fs::remove_all(dir / "corpus");
  fs::create_directories(dir / "corpus");
  const fs::path bddl = dir / "corpus" / "bad_\xFF_name.bddl";
  std::ofstream(bddl) << "(define (problem p\xFE\xFF)\n  (:domain omnigibson)\n  (:objects x\xC0\x80.n.01_1 - \xFF)\n";
  const Outcome check = run("activity check '" + bddl.string() + "'");
  EXPECT_EQ(check.status, 2) << check.err;
  EXPECT_EQ(check.err, valid_utf8(check.err)) << check.err;
  EXPECT_NE(check.err.find("bad_\\xFF_name.bddl"), std::string::npos) << check.err;
  const Outcome coverage = run("activity coverage " + (dir / "corpus").string() + " --json");
  ASSERT_EQ(coverage.status, 0) << coverage.err;
  EXPECT_EQ(coverage.out, valid_utf8(coverage.out));
  const nlohmann::json report = nlohmann::json::parse(coverage.out);  // throws on invalid UTF-8
  EXPECT_NE(report.dump().find("bad_\\\\xFF_name"), std::string::npos) << report.dump();
}

TEST(BadInput, LongTokensAreErrorsNotStackOverflows) {
  // std::regex recursed along a match: a 40,000-character token in :init
  // overflowed the stack where activity coverage read the failure's cause.
  const fs::path dir = test::scratch_dir("cli_long_token");
  fs::remove_all(dir / "corpus");
  fs::create_directories(dir / "corpus");
  std::ofstream(dir / "corpus" / "long.bddl")
      << "(define (problem long_token)\n  (:domain omnigibson)\n  (:objects apple.n.01_1 - apple.n.01)\n"
      << "  (:init (ontop apple.n.01_1 " << std::string(40000, 'k') << ".n.01_1))\n  (:goal (not (cooked apple.n.01_1))))\n";
  const Outcome coverage = run("activity coverage " + (dir / "corpus").string() + " --json");
  ASSERT_EQ(coverage.status, 0) << coverage.err;
  const nlohmann::json report = nlohmann::json::parse(coverage.out);
  EXPECT_NE(report.dump().find("long_token"), std::string::npos) << report.dump().substr(0, 2000);
}

TEST(BadInput, ATableOfTheWrongShapeIsAnErrorAndIsKept) {
  const fs::path out = test::scratch_dir("cli_table_shape");
  std::ofstream(out / "baselines.json") << "[1, 2]\n";
  expect_error("reproduce --report-only --activities collect_trash --methods rl-prim --seeds 0 --mode symbolic "
               "--no-videos --out " + out.string(),
               "chore: error: " + (out / "baselines.json").string() + ": not as chore writes it");
  EXPECT_EQ(read_text(out / "baselines.json"), "[1, 2]\n");
}

// The agent in roles the samplers and checkers do not give it (issue 54: a
// crash in object_aabb, an out-of-range index) is an error naming the
// literal, at `activity check` and before the simulator gets it.
TEST(BadInput, TheAgentPlaysOnlyTheRolesChoreGivesIt) {
  const fs::path dir = test::scratch_dir("cli_agent_roles");
  const std::string base = read_text(fs::path(CHORE_TEST_DATA) / "../../tasks/activities/collect_trash.bddl");
  const std::string start = "(onfloor agent.n.01_1 floor.n.01_1)";
  const struct {
    std::string name, init, goal;
  } cases[] = {
      {"on_the_agent", "(ontop bottle.n.01_1 agent.n.01_1)", ""},
      {"inside_the_agent", "(inside cup.n.01_1 agent.n.01_1)", ""},
      {"agent_open", "(open agent.n.01_1)", ""},
      {"agent_on_itself", "(ontop agent.n.01_1 agent.n.01_1)", ""},
      {"goal_next_to", "", "(nextto agent.n.01_1 ashcan.n.01_1)"},
  };
  for (const auto& c : cases) {
    std::string text = base;
    text.replace(text.find(start), start.size(), start + " " + c.init);
    if (!c.goal.empty()) text.replace(text.find("(and"), 4, "(and " + c.goal);
    const fs::path file = dir / (c.name + ".bddl");
    std::ofstream(file) << text;
    const std::string literal = c.init.empty() ? c.goal : c.init;
    const std::string section = c.init.empty() ? ": :goal: " : ": :init: ";
    expect_error("activity check " + file.string(), file.string() + section + literal + ": 'agent.n.01_1' is the agent");
    expect_error("activity sample " + file.string() + " --out " + (dir / "x.png").string(), "is the agent");
  }
  // What the corpora write stays good: the agent on the floor, in :init and in :goal.
  std::string good = base;
  good.replace(good.find("(and"), 4, "(and (onfloor agent.n.01_1 floor.n.01_1)");
  std::ofstream(dir / "good.bddl") << good;
  const Outcome r = run("activity check " + (dir / "good.bddl").string());
  EXPECT_EQ(r.status, 0) << r.err;
}

// A state :init sets on an object of which no kind keeps it is refused on
// the problem's text, at `activity check` and before instantiation, naming
// the literal and the state (issue 54): the sampler never receives it.
TEST(BadInput, InitialStatesNoKindOfTheObjectKeepsAreRefusedOnTheText) {
  const fs::path dir = test::scratch_dir("cli_initial_states");
  const auto activity = [&](const std::string& name, const std::string& objects, const std::string& init) {
    const fs::path file = dir / (name + ".bddl");
    std::ofstream(file) << "(define (problem " << name << "-0) (:domain omnigibson)\n"
                        << " (:objects " << objects << " floor.n.01_1 - floor.n.01 agent.n.01_1 - agent.n.01)\n"
                        << " (:init " << init << " (ontop agent.n.01_1 floor.n.01_1) (inroom floor.n.01_1 kitchen))\n"
                        << " (:goal (and (not (ontop ?agent.n.01_1 ?floor.n.01_1)))))\n";
    return file.string();
  };
  const struct {
    std::string name, objects, literal, missing;
  } cases[] = {
      {"soaked_foil", "aluminum_foil.n.01_1 - aluminum_foil.n.01 water.n.06_1 - water.n.06",
       "(saturated aluminum_foil.n.01_1 water.n.06_1)", "SoakedLevel"},
      {"apple_on_fire", "apple.n.01_1 - apple.n.01", "(on_fire apple.n.01_1)", "an ignition temperature"},
      {"toggled_foil", "aluminum_foil.n.01_1 - aluminum_foil.n.01", "(toggled_on aluminum_foil.n.01_1)",
       "ToggledState"},
  };
  for (const auto& c : cases) {
    const std::string file = activity(c.name, c.objects, c.literal);
    expect_error("activity check " + file, file + ": :init: " + c.literal + ": no kind of");
    expect_error("activity check " + file, c.missing);
    expect_error("activity sample " + file + " --out " + (dir / "x.png").string(), c.literal);
  }
  // Negations hold on what keeps no such state; an abstract synset passes when one of its kinds keeps it.
  for (const std::string& init : {std::string("(not (saturated aluminum_foil.n.01_1 water.n.06_1))"),
                                  std::string("(saturated fiber.n.01_1 water.n.06_1)")}) {
    const std::string file = activity("good", "aluminum_foil.n.01_1 - aluminum_foil.n.01 fiber.n.01_1 - fiber.n.01 "
                                              "water.n.06_1 - water.n.06", init);
    const Outcome r = run("activity check " + file);
    EXPECT_EQ(r.status, 0) << init << ": " << r.err;
  }
}

// chore never writes over or removes a file it did not make (issue 54): a new
// run refuses a folder of other files and leaves them as they were; a folder
// it marked as its own (a run stopped before its first checkpoint) is taken
// up again; a checkpoint's temporary file left by a killed writer goes at the
// next start.
TEST(BadInput, TrainNeverWritesOverFilesItDidNotMake) {
  const fs::path dir = test::scratch_dir("cli_run_folders");
  const fs::path theirs = dir / "theirs";
  fs::remove_all(theirs);
  fs::create_directories(theirs);
  std::ofstream(theirs / "config.json") << "{\"mine\": true}\n";
  std::ofstream(theirs / "metrics.csv") << "a,b\n1,2\n";
  const std::string train = "train --activity collect_trash --baseline rl-prim --mode symbolic --steps 60 "
                            "--checkpoint-every 30 --out ";
  expect_error(train + theirs.string(), "chore: error: train: --out " + theirs.string() +
                                            ": a folder of other files (");
  EXPECT_EQ(read_text(theirs / "config.json"), "{\"mine\": true}\n");
  EXPECT_EQ(read_text(theirs / "metrics.csv"), "a,b\n1,2\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(theirs), {}), 2);

  // A run of chore's that stopped before its first checkpoint: its own files, taken up again.
  const fs::path ours = dir / "ours";
  fs::remove_all(ours);
  fs::create_directories(ours);
  mark_run_folder(ours);
  std::ofstream(ours / "config.json") << "{}\n";
  std::ofstream(ours / "train.log") << "the first attempt\n";
  Outcome r = run(train + ours.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(ours / "checkpoint.pt"));
  EXPECT_EQ(read_text(ours / "train.log"), "the first attempt\n");

  // A writer killed mid-write left its temporary file; the next start removes it, not a live one's.
  std::ofstream(ours / "checkpoint.pt.tmp.999999999.0") << "half";
  std::ofstream(ours / ("checkpoint.pt.tmp." + std::to_string(::getpid()) + ".0")) << "writing";
  r = run("train --resume " + ours.string() + " --steps 90");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(ours / "checkpoint.pt.tmp.999999999.0"));
  EXPECT_TRUE(fs::exists(ours / ("checkpoint.pt.tmp." + std::to_string(::getpid()) + ".0")));
}

// Buffers whose size a setting requests are checked against the machine's
// memory before allocation (torch's allocator would fail with a backtrace, or
// the kernel kill the process): each names the setting. The sizes asked here
// (49-120 GB) are past this machine's and CI's memory.
TEST(BadInput, BuffersBeyondMemoryAreErrorsNamingTheSetting) {
  EXPECT_THROW(check_fits_in_memory(2.0 * physical_memory_bytes(), "x"), Error);
  EXPECT_NO_THROW(check_fits_in_memory(1e6, "x"));
  ASSERT_LT(physical_memory_bytes(), 49e9) << "the sizes below assume a machine of under 49 GB";
  const fs::path dir = test::scratch_dir("cli_memory");
  expect_error(
      "train --activity store_decoration --baseline rl-vmc --set sac.buffer=1000000 --out " + (dir / "sac").string(),
      "chore: error: sac.buffer = 1000000: its replay buffer needs 98.6 GB, more than this machine's");
  EXPECT_FALSE(fs::exists(dir / "sac"));
  expect_error(
      "train --activity store_decoration --baseline rl-prim --set ppo.buffer=1000000 --out " + (dir / "ppo").string(),
      "chore: error: ppo.buffer = 1000000: a rollout of its observations needs 49.2 GB");
  expect_error("bench --sections vector --envs 256 --width 4096 --height 4096 --scenes studio",
               "chore: error: vector env of 256 envs at 4096x4096: the buffer of its batched observations needs");
}

// --resume keeps the run's checkpoint interval, and a metrics row that is not
// a number (a damaged file) is dropped, not a crash.
TEST(BadInput, ResumeKeepsEverySettingOfTheRun) {
  const fs::path dir = test::scratch_dir("cli_resume") / "run";
  const std::string fast =
      "--activity collect_trash --baseline rl-prim --mode symbolic --observations proprio is_grasping "
      "--episode-steps 16 --seed 1 ";
  ASSERT_EQ(run("train " + fast + "--steps 600 --checkpoint-every 600 --out " + dir.string()).status, 0);
  EXPECT_TRUE(fs::exists(dir / "checkpoint_600.pt"));
  std::ofstream(dir / "metrics.csv", std::ios::app) << "garbage,1,2,3,4,5,6,7,8,9,10,11,12,13,14,15\n";
  const Outcome resumed = run("train --resume " + dir.string() + " --steps 1800");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  // Every 600 steps (PPO's rollouts are 300), not the default 3000's one checkpoint at the end.
  EXPECT_TRUE(fs::exists(dir / "checkpoint_1200.pt"));
  EXPECT_TRUE(fs::exists(dir / "checkpoint_1800.pt"));
  std::ifstream metrics(dir / "metrics.csv");
  const std::string text{std::istreambuf_iterator<char>(metrics), {}};
  EXPECT_EQ(text.find("garbage"), std::string::npos);
  expect_error("train --resume " + dir.string() + " --checkpoint-every 100",
               "checkpointed every 600 steps; --resume continues it as it was");
}

// The hand-made seeds of the checkpoint and command-line fuzz targets
// (tests/fuzz/corpus/*/seed_*) must be valid, or the campaigns would start
// from nothing but errors.
std::vector<std::string> fuzz_seeds(const std::string& target) {
  std::vector<std::string> seeds;
  for (const auto& entry : fs::directory_iterator(test::data_path("../fuzz/corpus/" + target))) {
    if (entry.path().filename().string().starts_with("seed_")) {
      std::ifstream in(entry.path(), std::ios::binary);
      seeds.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
  }
  return seeds;
}

// One command line, words split at spaces.
ParsedCommandLine parse_words(CommandLineParser& parser, const std::string& line) {
  std::vector<std::string> args = {"chore"};
  std::istringstream words(line);
  for (std::string w; words >> w;) args.push_back(w);
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  return parser.parse(static_cast<int>(argv.size()), argv.data(), out, err);
}

// The fuzz target parses every input with one parser: each parse must start
// from the defaults, whatever the one before it set or failed on.
TEST(BadInput, AParserReusedStartsEachParseFromTheDefaults) {
  CommandLineParser reused;
  ParsedCommandLine p = parse_words(reused, "train --activity a --steps 5 --seed 7 --set ppo.lr=0.1");
  ASSERT_TRUE(p.command);
  EXPECT_EQ(p.command->train.steps, 5);
  EXPECT_EQ(p.command->train.seed, 7u);
  EXPECT_EQ(p.command->train.settings.size(), 1u);
  p = parse_words(reused, "train --activity b");
  ASSERT_TRUE(p.command);
  EXPECT_EQ(p.command->command, Command::train);
  EXPECT_FALSE(p.command->train.steps);
  EXPECT_EQ(p.command->train.seed, 0u);
  EXPECT_TRUE(p.command->train.settings.empty());
  EXPECT_EQ(p.command->train.activity, "b");

  p = parse_words(reused, "eval --expert --activity a --seeds 3-4 --json");
  ASSERT_TRUE(p.command);
  EXPECT_EQ(p.command->eval.first_seed, 3u);
  EXPECT_TRUE(p.command->json);
  EXPECT_EQ(parse_words(reused, "eval --expert --seeds x").exit_status, 2);
  p = parse_words(reused, "eval --expert --activity a");
  ASSERT_TRUE(p.command);
  EXPECT_EQ(p.command->eval.first_seed, 0u);
  EXPECT_EQ(p.command->eval.last_seed, 0u);
  EXPECT_FALSE(p.command->json);
  EXPECT_TRUE(p.command->policy.expert);

  p = parse_words(reused, "expert --activity a --mode symbolic");
  ASSERT_TRUE(p.command);
  EXPECT_EQ(p.command->expert.mode, ExecutionMode::symbolic);
  EXPECT_EQ(parse_words(reused, "--help").exit_status, 0);
  p = parse_words(reused, "expert --activity a");
  ASSERT_TRUE(p.command);
  EXPECT_EQ(p.command->command, Command::expert);  // not the earlier eval's, nor --help's
  EXPECT_EQ(p.command->expert.mode, ExecutionMode::physical);
}

TEST(BadInput, TheFuzzSeedsOfCheckpointsAndCommandLinesAreValid) {
  for (std::string bytes : fuzz_seeds("checkpoint")) {
    const uint64_t checksum = checkpoint_checksum(bytes);
    bytes.append(reinterpret_cast<const char*>(&checksum), sizeof checksum);  // as checkpoint_fuzz.cpp does
    const LoadedPolicy loaded = load_policy(parse_checkpoint(bytes, "seed"));
    EXPECT_TRUE(loaded.policy);
    EXPECT_EQ(loaded.env.activity, "clean_table");
  }
  int metas = 0;
  for (std::string bytes : fuzz_seeds("checkpoint_file")) {  // the same files with three of their tensors
    const uint64_t checksum = checkpoint_checksum(bytes);
    bytes.append(reinterpret_cast<const char*>(&checksum), sizeof checksum);
    const CheckpointMeta meta = read_checkpoint_meta(parse_checkpoint(bytes, "seed"));
    EXPECT_EQ(meta.config.env.activity, "clean_table");
    EXPECT_EQ(meta.network.state_size, 1);  // is_grasping alone
    EXPECT_EQ(parse_checkpoint(bytes, "seed").tensors.size(), 3u);
    metas += 1;
  }
  EXPECT_EQ(metas, 2);
  int commands = 0;
  for (const std::string& text : fuzz_seeds("cli")) {
    std::vector<std::string> args = {"chore"};
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) args.push_back(line);
    std::vector<const char*> argv;
    for (const std::string& a : args) argv.push_back(a.c_str());
    std::ostringstream out, err;
    const ParsedCommandLine parsed = parse_command_line(static_cast<int>(argv.size()), argv.data(), out, err);
    commands += parsed.command.has_value();
    EXPECT_TRUE(parsed.command) << text << err.str();
  }
  EXPECT_GE(commands, 10);
}

}  // namespace
}  // namespace chore
