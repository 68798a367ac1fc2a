// The ranks of a data-parallel run: where a process learns its rank, and
// c10d's Gloo collectives between two ranks over loopback (two threads of
// this process), with a rank that never comes or goes away.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "base/error.hpp"
#include "test_util.hpp"
#include "training/distributed.hpp"

namespace chore {
namespace {

TEST(Distributed, TheRankComesFromTorchrunsOrSlurmsVariables) {
  EXPECT_EQ(rank_from_environment(std::map<std::string, std::string>{}).world_size, 1);
  const RankInfo torchrun =
      rank_from_environment({{"WORLD_SIZE", "4"}, {"RANK", "3"}, {"MASTER_ADDR", "node7"}, {"MASTER_PORT", "1234"}});
  EXPECT_EQ(torchrun.source, "torchrun");
  EXPECT_EQ(torchrun.world_size, 4);
  EXPECT_EQ(torchrun.rank, 3);
  EXPECT_EQ(torchrun.master_addr, "node7");
  EXPECT_EQ(torchrun.master_port, 1234);
  // srun's: rank 0 is where srun ran, the port apart per job.
  const RankInfo slurm = rank_from_environment({{"SLURM_NTASKS", "2"},
                                                {"SLURM_PROCID", "1"},
                                                {"SLURM_LAUNCH_NODE_IPADDR", "10.0.0.5"},
                                                {"SLURM_JOB_ID", "4321"}});
  EXPECT_EQ(slurm.source, "slurm");
  EXPECT_EQ(slurm.world_size, 2);
  EXPECT_EQ(slurm.rank, 1);
  EXPECT_EQ(slurm.master_addr, "10.0.0.5");
  EXPECT_EQ(slurm.master_port, 29500 + 321);
  const auto error = [](const std::map<std::string, std::string>& env) {
    try {
      rank_from_environment(env);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error({{"WORLD_SIZE", "2"}, {"MASTER_ADDR", "a"}}), "distributed: WORLD_SIZE is set but RANK is not");
  EXPECT_EQ(error({{"WORLD_SIZE", "2"}, {"RANK", "2"}, {"MASTER_ADDR", "a"}}),
            "distributed: RANK='2' is not a whole number in [0, 1]");
  EXPECT_EQ(error({{"WORLD_SIZE", "2"}, {"RANK", "0"}}), "distributed: WORLD_SIZE=2 but MASTER_ADDR is not set");
  EXPECT_EQ(error({{"WORLD_SIZE", "2"}, {"RANK", "0"}, {"MASTER_ADDR", "a"}, {"MASTER_PORT", "http"}}),
            "distributed: MASTER_PORT='http' is not a whole number in [1, 65535]");
  EXPECT_EQ(
      error({{"SLURM_NTASKS", "2"}, {"SLURM_PROCID", "0"}}),
      "distributed: Slurm runs 2 tasks but neither MASTER_ADDR nor SLURM_LAUNCH_NODE_IPADDR says where rank 0 is");
}

// Two ranks: the mean of what each holds, rank 0's broadcast, and whether
// they hold the same.
TEST(Distributed, TwoRanksOverLoopbackAverageBroadcastAndCompare) {
  const int port = test::free_port();
  float means[2][3];
  bool same_before[2], same_after[2];
  const auto rank = [&](int r) {
    Ranks ranks({r, 2, "127.0.0.1", port, "torchrun"}, std::chrono::seconds(20));
    const torch::Tensor a = torch::tensor({1.f + r, 10.f * r}), b = torch::full({1}, 3.f * r);
    ranks.mean({a, b});
    means[r][0] = a[0].item<float>(), means[r][1] = a[1].item<float>(), means[r][2] = b[0].item<float>();
    const torch::Tensor w = torch::full({4}, static_cast<float>(r));
    same_before[r] = ranks.same({w});
    ranks.broadcast({w});
    same_after[r] = ranks.same({w});
    EXPECT_EQ(w[3].item<float>(), 0.f) << "rank 0's values everywhere";
  };
  std::thread one(rank, 1);
  rank(0);
  one.join();
  for (int r = 0; r < 2; ++r) {
    EXPECT_FLOAT_EQ(means[r][0], 1.5f);
    EXPECT_FLOAT_EQ(means[r][1], 5.f);
    EXPECT_FLOAT_EQ(means[r][2], 1.5f);
    EXPECT_FALSE(same_before[r]);
    EXPECT_TRUE(same_after[r]);
  }
}

// A rank that never comes: the other fails within the timeout, saying so.
TEST(Distributed, ARankThatNeverComesFailsTheOthersWithinTheTimeout) {
  const auto start = std::chrono::steady_clock::now();
  try {
    Ranks ranks({0, 2, "127.0.0.1", test::free_port(), "torchrun"}, std::chrono::milliseconds(1500));
    FAIL() << "met a rank that does not exist";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("distributed: rank 0 of 2 (127.0.0.1:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("did not meet within 1500 ms"), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(15));
}

// A rank that goes away after meeting: the all-reduce of the other fails
// within the timeout, a chore::Error, never a hang.
TEST(Distributed, ARankThatGoesAwayFailsTheOthersCollective) {
  const int port = test::free_port();
  std::string error;
  std::thread zero([&] {
    Ranks ranks({0, 2, "127.0.0.1", port, "torchrun"}, std::chrono::milliseconds(3000));
    ranks.mean({torch::ones({8})});  // both here
    try {
      ranks.mean({torch::ones({8})});  // rank 1 is gone
    } catch (const Error& e) {
      error = e.what();
    }
  });
  {
    Ranks ranks({1, 2, "127.0.0.1", port, "torchrun"}, std::chrono::milliseconds(3000));
    ranks.mean({torch::ones({8})});
  }
  const auto start = std::chrono::steady_clock::now();
  zero.join();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(15));
  EXPECT_NE(error.find("distributed: rank 0 of 2"), std::string::npos) << error;
  EXPECT_NE(error.find("all-reduce failed"), std::string::npos) << error;
}

}  // namespace
}  // namespace chore
