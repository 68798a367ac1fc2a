// The chore command line under bad input: each case exits 2 with "chore:
// error:" or CLI11's message naming the option, never 1 (an internal
// fault), a signal (an abort from a worker thread), a wrapped number or a
// half-made run folder.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/command_line.hpp"
#include "base/memory.hpp"
#include "test_util.hpp"
#include "training/checkpoint.hpp"

namespace chore {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;  // exit status, or -1 after a signal
  std::string err;  // stderr
};

Outcome run(const std::string& args) {
  // Beside the test's own files: ctest runs the tests of this file in parallel.
  const fs::path err =
      fs::path(test::scratch_dir("bad_input_stderr_" +
                                 std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()))) /
      "stderr.txt";
  const std::string command = std::string(CHORE_BINARY) + " " + args + " > /dev/null 2> " + err.string();
  const int status = std::system(command.c_str());
  std::ifstream in(err);
  Outcome r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, {std::istreambuf_iterator<char>(in), {}}};
  return r;
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
