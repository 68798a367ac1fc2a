#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstring>
#include <random>
#include <set>

#include "base/error.hpp"
#include "env/env.hpp"
#include "env/vector_env.hpp"
#include "test_util.hpp"

namespace chore {
namespace {

VectorEnvConfig config(int envs, int threads, int max_steps = 500) {
  VectorEnvConfig c;
  c.env.scene = test::box_room();
  c.env.max_episode_steps = max_steps;
  c.num_envs = envs;
  c.num_threads = threads;
  return c;
}

std::vector<float> random_actions(std::mt19937& rng, int envs) {
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<float> a(envs * kLowLevelActionSize);
  for (float& x : a) x = u(rng);
  return a;
}

// Everything a step returns, as bytes, for exact comparison.
std::vector<unsigned char> snapshot(const Batch& b) {
  std::vector<unsigned char> out;
  for (const Array& a : b.obs->arrays()) out.insert(out.end(), a.bytes.begin(), a.bytes.end());
  auto add = [&](const void* p, size_t n) {
    out.insert(out.end(), static_cast<const unsigned char*>(p), static_cast<const unsigned char*>(p) + n);
  };
  add(b.rewards.data(), b.rewards.size_bytes());
  add(b.terminated.data(), b.terminated.size_bytes());
  add(b.truncated.data(), b.truncated.size_bytes());
  add(b.env_ids.data(), b.env_ids.size_bytes());
  for (const Info& i : b.infos) add(&i.elapsed_steps, sizeof i.elapsed_steps);
  return out;
}

TEST(VectorEnv, ResultsDoNotDependOnTheThreadCount) {
  for (int tiles : {1, 4}) {
    // Short episodes so that autoresets happen inside the comparison.
    VectorEnvConfig c1 = config(4, 1, 6), c2 = config(4, 2, 6);
    c1.render_tiles = c2.render_tiles = tiles;
    VectorEnv one(c1), two(c2);
    EXPECT_EQ(snapshot(one.reset(5)), snapshot(two.reset(5)));
    std::mt19937 rng(3);
    for (int i = 0; i < 12; ++i) {
      const auto actions = random_actions(rng, 4);
      EXPECT_EQ(snapshot(one.step(actions)), snapshot(two.step(actions))) << "step " << i << " tiles " << tiles;
    }
  }
}

// Rendering::batch: one render context for the VectorEnv, env i in tile i of
// one pass. Its results do not depend on the thread count, and are those of
// per-thread rendering that puts env i in tile i too (render_tiles = N), bit
// for bit, through autoresets of both kinds (same_step: the ended episodes'
// last frames drawn before their resets), every image modality (the second
// autoreset with segmentation, normals and flow beside RGB-D).
TEST(VectorEnv, BatchRenderingDrawsWhatPerThreadRenderingDraws) {
  for (const AutoReset autoreset : {AutoReset::next_step, AutoReset::same_step}) {
    VectorEnvConfig per_thread = config(4, 2, 5), one = config(4, 1, 5), two = config(4, 2, 5);
    per_thread.render_tiles = 4;
    one.rendering = two.rendering = Rendering::batch;
    for (VectorEnvConfig* c : {&per_thread, &one, &two}) {
      c->autoreset = autoreset;
      if (autoreset == AutoReset::same_step)
        c->env.observations = {"rgb", "depth", "seg_semantic", "seg_instance", "normal", "flow", "proprio"};
    }
    VectorEnv reference(per_thread), batch_one(one), batch_two(two);
    const auto expected = snapshot(reference.reset(7));
    EXPECT_EQ(snapshot(batch_one.reset(7)), expected);
    EXPECT_EQ(snapshot(batch_two.reset(7)), expected);
    std::mt19937 rng(4);
    for (int i = 0; i < 12; ++i) {
      const auto actions = random_actions(rng, 4);
      const Batch r = reference.step(actions);
      const auto want = snapshot(r);
      const Batch a = batch_one.step(actions), b = batch_two.step(actions);
      EXPECT_EQ(snapshot(a), want) << "step " << i;
      EXPECT_EQ(snapshot(b), want) << "step " << i;
      if (autoreset == AutoReset::same_step && r.truncated[0]) {
        ASSERT_NE(b.final_obs, nullptr);
        for (const Array& f : b.final_obs->arrays()) {
          const Array& g = (*r.final_obs)[f.name];
          EXPECT_EQ(f.bytes, g.bytes) << f.name << ", step " << i;
        }
      }
    }
    // The frames are drawn: not one colour; segments and normals of more
    // than one surface.
    const Batch last = batch_two.step(random_actions(rng, 4));
    const Array& rgb = (*last.obs)["rgb"];
    EXPECT_GT(std::set<unsigned char>(rgb.bytes.begin(), rgb.bytes.end()).size(), 20u);
    if (autoreset == AutoReset::same_step) {
      const Array& seg = (*last.obs)["seg_instance"];
      const auto* ids = reinterpret_cast<const std::int32_t*>(seg.bytes.data());
      EXPECT_GT(std::set<std::int32_t>(ids, ids + seg.bytes.size() / 4).size(), 3u);
      const Array& normal = (*last.obs)["normal"];
      const auto* n = reinterpret_cast<const float*>(normal.bytes.data());
      EXPECT_GT(std::set<float>(n, n + normal.bytes.size() / 4).size(), 3u);
    }
  }
}

// Sixteen envs of StoreDecoration in the apartment, drawn in one batch pass:
// each env's RGB is that of per-thread rendering with the env in the same
// tile, and the sheet of the sixteen views (build/test_output/
// batch_rendering_16_envs.png) shows sixteen instances of the activity.
TEST(VectorEnv, SixteenEnvsOfAnActivityInOneBatchPass) {
  VectorEnvConfig batch, per_thread;
  for (VectorEnvConfig* c : {&batch, &per_thread}) {
    c->env.activity = "store_decoration";
    c->env.width = c->env.height = 128;
    c->env.observations = {"rgb"};
    c->num_envs = 16;
    c->num_threads = 2;
  }
  batch.rendering = Rendering::batch;
  per_thread.render_tiles = 16;
  VectorEnv a(batch), b(per_thread);
  const Batch drawn = a.reset(11), expected = b.reset(11);
  const Array& rgb = (*drawn.obs)["rgb"];
  EXPECT_EQ(rgb.bytes, (*expected.obs)["rgb"].bytes);
  cv::Mat sheet(4 * 128, 4 * 128, CV_8UC3);
  for (int e = 0; e < 16; ++e) {
    const cv::Mat view(128, 128, CV_8UC3, const_cast<std::uint8_t*>(rgb.bytes.data()) + e * 128 * 128 * 3);
    cv::Mat bgr;
    cv::cvtColor(view, bgr, cv::COLOR_RGB2BGR);
    bgr.copyTo(sheet(cv::Rect(e % 4 * 128, e / 4 * 128, 128, 128)));
    // Each view drawn: more than a handful of colours.
    EXPECT_GT(
        std::set<unsigned char>(rgb.bytes.begin() + e * 128 * 128 * 3, rgb.bytes.begin() + (e + 1) * 128 * 128 * 3)
            .size(),
        20u)
        << "env " << e;
  }
  cv::imwrite((test::output_dir() / "batch_rendering_16_envs.png").string(), sheet);
}

// Rendering::batch with send()/recv(): each batch of results drawn in one
// pass as it is returned, env i in tile i whichever batch it comes in: every
// env's frames are those of the synchronous VectorEnv.
TEST(VectorEnv, BatchRenderingOfAsyncBatchesDrawsEachEnvAsTheSyncOneDoes) {
  VectorEnvConfig sync = config(4, 2), async = config(4, 2);
  sync.rendering = async.rendering = Rendering::batch;
  async.batch_size = 2;
  VectorEnv all(sync), halves(async);
  all.reset(3);
  halves.reset(3);
  const std::vector<float> zero(4 * kLowLevelActionSize, 0.f);
  const Batch b = all.step(zero);
  const std::vector<int> ids = {0, 1, 2, 3};
  halves.send(zero, ids);
  for (int k = 0; k < 2; ++k) {
    const Batch h = halves.recv();
    for (int i = 0; i < h.size(); ++i) {
      const int e = h.env_ids[i];
      for (const Array& a : h.obs->arrays()) {
        EXPECT_EQ(std::memcmp(a.item(i), (*b.obs)[a.name].item(e), a.item_bytes()), 0) << a.name << ", env " << e;
      }
    }
  }
}

TEST(VectorEnv, EnvIIsTheSingleEnvSeededWithSeedPlusI) {
  VectorEnv vec(config(3, 2));
  Env env0(config(3, 2).env), env2(config(3, 2).env);
  Batch b = vec.reset(100);
  env0.reset(100);
  env2.reset(102);
  std::mt19937 rng(9);
  for (int i = 0; i < 5; ++i) {
    const auto actions = random_actions(rng, 3);
    b = vec.step(actions);
    auto s0 = env0.step(std::span<const float>(actions).first(kLowLevelActionSize));
    // Env 0 draws in tile 0 as a single env does: everything is identical.
    for (const Array& a : b.obs->arrays()) {
      EXPECT_EQ(std::memcmp(a.item(0), s0.obs[a.name].item(0), a.item_bytes()), 0) << a.name;
    }
    // Env 2 draws in tile 2: the state is identical (images may differ by a
    // rounding level on a few edge pixels, see CameraView::tile).
    auto s2 = env2.step(std::span<const float>(actions).subspan(2 * kLowLevelActionSize, kLowLevelActionSize));
    EXPECT_EQ(std::memcmp((*b.obs)["proprio"].item(2), s2.obs["proprio"].item(0), s2.obs["proprio"].item_bytes()), 0);
  }
}

// Gymnasium's reset(seed=[...]): a seed per env, or none (its stream
// continues). seeds {100, 101, 102} are reset(100) exactly; {7, -, 9} puts
// env 1's stream where it was.
TEST(VectorEnv, ASeedPerEnvResetsEachWithItsOwn) {
  VectorEnv a(config(3, 2)), b(config(3, 2));
  const std::vector<std::optional<uint64_t>> seeds = {100, 101, 102};
  EXPECT_EQ(snapshot(a.reset(100)), snapshot(b.reset(seeds)));
  Env env0(config(3, 2).env), env1(config(3, 2).env);
  env0.reset(7);
  env1.reset(101);
  const uint64_t continued = env1.reset().info.episode_seed;  // env 1's stream, continued once
  const std::vector<std::optional<uint64_t>> some = {7, std::nullopt, 9};
  const Batch r = b.reset(some);
  const Array& proprio = (*r.obs)["proprio"];
  EXPECT_EQ(r.infos[0].episode_seed, 7u);
  EXPECT_EQ(r.infos[2].episode_seed, 9u);
  EXPECT_EQ(std::memcmp(proprio.item(0), env0.reset(7).obs["proprio"].item(0), proprio.item_bytes()), 0);
  EXPECT_EQ(r.infos[1].episode_seed, continued) << "env 1's stream went on";
  const std::vector<std::optional<uint64_t>> two = {1, 2};
  EXPECT_THROW(b.reset(two), Error);
}

TEST(VectorEnv, AsyncRecvReturnsTheFirstBatchReadyWithEnvIds) {
  VectorEnvConfig c = config(4, 2);
  c.batch_size = 2;
  VectorEnv vec(c);
  vec.reset(0);
  EXPECT_THROW(vec.step(std::vector<float>(4 * kLowLevelActionSize)), Error);  // needs batch == N
  std::vector<int> ids = {0, 1, 2, 3};
  vec.send(std::vector<float>(4 * kLowLevelActionSize, 0.f), ids);
  std::set<int> seen;
  for (int k = 0; k < 2; ++k) {
    Batch b = vec.recv();
    ASSERT_EQ(b.size(), 2);
    EXPECT_EQ((*b.obs)["rgb"].shape[0], 2);
    for (int i = 0; i < 2; ++i) {
      seen.insert(b.env_ids[i]);
      EXPECT_EQ(b.infos[i].env_id, b.env_ids[i]);
      EXPECT_EQ(b.infos[i].elapsed_steps, 1);
    }
  }
  EXPECT_EQ(seen, (std::set<int>{0, 1, 2, 3}));
  EXPECT_THROW(vec.recv(), Error);  // nothing in flight: would wait forever
  // Envs go on independently: step env 3 twice more, then the rest once.
  std::vector<int> three = {3};
  vec.send(std::vector<float>(kLowLevelActionSize, 0.f), three);
  EXPECT_THROW(vec.send(std::vector<float>(kLowLevelActionSize, 0.f), three), Error);  // in flight
  std::vector<int> rest = {0, 1};
  vec.send(std::vector<float>(2 * kLowLevelActionSize, 0.f), rest);
  std::vector<int64_t> steps(4, 1);
  for (int k = 0; k < 1; ++k) {
    Batch b = vec.recv();
    for (int i = 0; i < b.size(); ++i) steps[b.env_ids[i]] = b.infos[i].elapsed_steps;
  }
  int done = 0;
  for (int e = 0; e < 4; ++e) done += steps[e] == 2;
  EXPECT_EQ(done, 2);
}

TEST(VectorEnv, NextStepAutoresetResetsOnTheFollowingStep) {
  VectorEnv vec(config(2, 1, 3));
  vec.reset(0);
  std::vector<float> zero(2 * kLowLevelActionSize, 0.f);
  vec.step(zero);
  vec.step(zero);
  Batch b = vec.step(zero);
  EXPECT_TRUE(b.truncated[0] && b.truncated[1]);
  EXPECT_EQ(b.infos[0].elapsed_steps, 3);
  EXPECT_EQ(b.final_obs, nullptr);
  b = vec.step(zero);  // the reset step
  EXPECT_FALSE(b.truncated[0] || b.terminated[0]);
  EXPECT_EQ(b.rewards[0], 0.f);
  EXPECT_EQ(b.infos[0].elapsed_steps, 0);
  EXPECT_EQ(vec.step(zero).infos[0].elapsed_steps, 1);
}

TEST(VectorEnv, SameStepAutoresetKeepsTheFinalObservation) {
  VectorEnvConfig c = config(2, 2, 3);
  c.autoreset = AutoReset::same_step;
  VectorEnv vec(c);
  Env single(c.env);
  vec.reset(0);
  single.reset(1);
  std::vector<float> zero(2 * kLowLevelActionSize, 0.f);
  std::vector<float> one_zero(kLowLevelActionSize, 0.f);
  Batch b = vec.step(zero);
  for (int i = 0; i < 2; ++i) single.step(one_zero);
  b = vec.step(zero);
  b = vec.step(zero);
  auto last = single.step(one_zero);
  EXPECT_TRUE(b.truncated[1]);
  EXPECT_EQ(b.infos[1].elapsed_steps, 0);        // already the new episode
  EXPECT_EQ(b.final_infos[1].elapsed_steps, 3);  // the one that ended
  ASSERT_NE(b.final_obs, nullptr);
  EXPECT_EQ(std::memcmp(b.final_obs->operator[]("proprio").item(1), last.obs["proprio"].item(0),
                        last.obs["proprio"].item_bytes()),
            0);
  // The new episode continues env 1's random stream, as a single env's reset().
  auto next = single.reset();
  EXPECT_EQ(std::memcmp((*b.obs)["proprio"].item(1), next.obs["proprio"].item(0), next.obs["proprio"].item_bytes()), 0);
}

TEST(VectorEnv, BadConfigurationsAndActionsAreClearErrors) {
  auto message = [](const VectorEnvConfig& c) {
    try {
      VectorEnv v(c);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(message(config(0, 1)).find("num_envs must be at least 1"), std::string::npos);
  EXPECT_NE(message(config(2, 3)).find("num_threads must be in 1..2"), std::string::npos);
  VectorEnv vec(config(2, 1));
  EXPECT_THROW(vec.step(std::vector<float>(2 * kLowLevelActionSize)), Error);  // before reset
  vec.reset(0);
  std::vector<float> bad(2 * kLowLevelActionSize, 0.f);
  bad[kLowLevelActionSize + 2] = INFINITY;
  try {
    vec.step(bad);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("for env 1 (index 2)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(vec.step(std::vector<float>(5)), Error);
  // Nothing was sent: the next good step works and counts one step.
  EXPECT_EQ(vec.step(std::vector<float>(2 * kLowLevelActionSize, 0.f)).infos[0].elapsed_steps, 1);
  vec.close();
  vec.close();
  EXPECT_THROW(vec.reset(0), Error);
}

}  // namespace
}  // namespace chore
