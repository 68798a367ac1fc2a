"""The peer trainer (issue 53): Stable-Baselines3's PPO, the library iGibson's
and OmniGibson's RL examples use, trained through chore's Python package on
the primitive action space, with Table A.12's settings and chore's network,
so that its Q and learning curves can be set beside chore's own PPO
(training/ppo.cpp) on the same env and seeds.

    scripts/peer_sb3 --activity store_decoration --seed 0 --out DIR [--steps 30000] [--mode symbolic]

Writes into DIR: metrics.csv (chore train's first columns, a row per rollout:
scripts/plot draws it beside chore's runs), model.zip (SB3's), and
eval_seed0.json: episodes 0-99 of evaluation seed 0's stream (env seeds
0-99, as `chore eval --seeds 0-0 --episodes 100`), sampling and greedily.

What is the same as chore's RL-Prim. (docs/baselines.md, the paper's
protocol): the env (observations rgb and is_grasping, 60-primitive episodes,
instance 0 at every reset, no policy-failure rule), the network (chore's
Conv-ReLU-MaxPool trunk and 32-unit state encoder into a 128-d feature, the
heads straight on it, orthogonal initialisation with SB3's gains, which are
chore's), PPO's settings (Table A.12; SB3's defaults elsewhere, which chore
took: 10 epochs, minibatch advantage normalisation, Adam eps 1e-5, gradient
norm 0.5), the value loss (the squared error weighed by Table A.12's c2),
the state as observed, the truncation bootstrap, one env, one thread. What
differs is SB3's own: its images are scaled to [0, 1] (chore normalises each
channel by running statistics, as appendix F.1 says: `--input-norm running`
does as chore does), and its random streams are its own. (The diagnostic
runs of results/peer_diag/sb3_input_norm_running and sb3_as_chore, made with
this script at commit 5d76876, normalised the state too, as chore did then.)
"""

import argparse
import collections
import json
import os
import sys
import time

import gymnasium
import numpy as np
import torch
from torch import nn
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.torch_layers import BaseFeaturesExtractor

import chore

WINDOW = 20  # episodes in a metrics row's means (chore's EpisodeStats::kWindow)
STATUSES = ["success", "precondition_failure", "motion_planning_failure", "grasp_failure", "place_failure"]


class PrimitiveEnv(gymnasium.Env):
    """chore's primitive action space as a gymnasium.Env (SB3 takes nothing
    else). The first reset is seeded; later ones continue the env's stream,
    as chore's trainer does."""

    def __init__(self, activity, mode, seed):
        self.env = chore.make(activity, action_space="primitives", mode=mode, observations=["rgb", "is_grasping"],
                              max_episode_steps=60, instances="fixed", policy_failure_rule="none", copy=True)
        self.observation_space = self.env.observation_space
        self.action_space = self.env.action_space
        self.first_seed = seed

    def reset(self, *, seed=None, options=None):
        if seed is None and self.first_seed is not None:
            seed, self.first_seed = self.first_seed, None
        return self.env.reset(seed=seed)

    def step(self, action):
        return self.env.step(np.asarray([int(action)]))

    def close(self):
        self.env.close()


class RunningNorm(nn.Module):
    """chore's RunningNorm (policies/networks.cpp): a running mean and variance
    per channel (Chan et al.'s parallel update, in float64, from mean 0 and
    variance 1 before any sample), inputs normalised and clipped to +-5."""

    def __init__(self, dims):
        super().__init__()
        self.register_buffer("mean", torch.zeros(dims, dtype=torch.float64))
        self.register_buffer("var", torch.ones(dims, dtype=torch.float64))
        self.register_buffer("count", torch.zeros(1, dtype=torch.float64))

    def update(self, samples):  # (N, dims)
        x = torch.as_tensor(samples, dtype=torch.float64)
        n, count = float(x.shape[0]), float(self.count)
        batch_mean, batch_var = x.mean(0), x.var(0, unbiased=False)
        delta = batch_mean - self.mean
        total = count + n
        self.mean += delta * (n / total)
        self.var.copy_((self.var * count + batch_var * n + delta * delta * (count * n / total)) / total)
        self.count.fill_(total)

    def forward(self, x, dim):
        shape = [1] * x.dim()
        shape[dim] = -1
        std = (self.var.float() + 1e-8).sqrt().view(shape)
        return ((x - self.mean.float().view(shape)) / std).clamp(-5.0, 5.0)


class ChoreEncoder(BaseFeaturesExtractor):
    """chore's Encoder (policies/networks.cpp) for SB3: images (3, H, W) as
    SB3 hands them, scaled to [0, 1] by SB3 (input_norm "unit") or, as chore,
    raw and normalised by running statistics (input_norm "running"; ChorePPO
    updates them). The state as observed, as chore's PPO takes it."""

    def __init__(self, observation_space, input_norm="unit"):
        super().__init__(observation_space, features_dim=128)
        self.input_norm = input_norm
        if input_norm == "running":
            self.rgb_norm = RunningNorm(observation_space["rgb"].shape[0])
        self.trunk = nn.Sequential(
            nn.Conv2d(3, 16, 8, stride=4, padding=2), nn.ReLU(), nn.MaxPool2d(2),
            nn.Conv2d(16, 32, 3, padding=1), nn.ReLU(), nn.MaxPool2d(2),
            nn.Conv2d(32, 32, 3, padding=1), nn.ReLU(), nn.MaxPool2d(2), nn.Flatten())
        with torch.no_grad():
            width = self.trunk(torch.zeros((1,) + observation_space["rgb"].shape)).shape[1]
        state = observation_space["is_grasping"].shape[0]
        self.state = nn.Sequential(nn.Linear(state, 32), nn.ReLU())
        self.mlp = nn.Sequential(nn.Linear(width + 32, 128), nn.ReLU())

    def forward(self, obs):
        rgb = self.rgb_norm(obs["rgb"], 1) if self.input_norm == "running" else obs["rgb"]
        return self.mlp(torch.cat([self.trunk(rgb), self.state(obs["is_grasping"])], 1))

    def update_normalizers(self, observations):
        """From a rollout's observations (SB3's buffer, flattened by its update
        to (steps * envs, ...))."""
        rgb = torch.as_tensor(observations["rgb"])
        self.rgb_norm.update(rgb.reshape((-1,) + rgb.shape[-3:]).permute(0, 2, 3, 1).reshape(-1, rgb.shape[-3]))


class ChorePPO(PPO):
    """SB3's PPO; with running input statistics, updated as chore's trainer
    does: after each update, from the rollout it learned from (constant while
    one rollout is acted and learned)."""

    def train(self):
        super().train()
        extractor = self.policy.features_extractor
        if extractor.input_norm == "running":
            extractor.update_normalizers(self.rollout_buffer.observations)


class Metrics(BaseCallback):
    """metrics.csv as chore train writes it, a row per rollout and its
    update: the first columns (episode means over the last 20), then the
    update's entropy, approx-KL and clip fraction as SB3 logged them (chore's
    names). SB3 logs an update after the next rollout has begun, so a row is
    written then (the last one when training ends)."""

    def __init__(self, path):
        super().__init__()
        self.file = open(path, "w")
        self.file.write("env_steps,wall_s,episodes,success_rate,mean_q,mean_return,mean_length,"
                        "entropy,approx_kl,clip_fraction\n")
        self.recent = collections.deque(maxlen=WINDOW)
        self.episodes = 0
        self.ret = 0.0
        self.start = time.monotonic()
        self.pending = None  # the last rollout's columns, waiting for its update's

    def _on_step(self):
        self.ret += float(self.locals["rewards"][0])
        if self.locals["dones"][0]:
            info = self.locals["infos"][0]
            self.recent.append((self.ret, float(info["q"]), int(info["elapsed_step"]), bool(info["success"])))
            self.episodes += 1
            self.ret = 0.0
        return True

    def _on_rollout_end(self):
        r = np.array(self.recent) if self.recent else np.zeros((1, 4))
        self.pending = (f"{self.num_timesteps},{time.monotonic() - self.start:.3f},{self.episodes},"
                        f"{r[:, 3].mean():.6g},{r[:, 1].mean():.6g},{r[:, 0].mean():.6g},{r[:, 2].mean():.6g}")

    def _write_pending(self):
        if self.pending is None:
            return
        logged = self.model.logger.name_to_value
        self.file.write(f"{self.pending},{-logged.get('train/entropy_loss', float('nan')):.6g},"
                        f"{logged.get('train/approx_kl', float('nan')):.6g},"
                        f"{logged.get('train/clip_fraction', float('nan')):.6g}\n")
        self.file.flush()
        self.pending = None

    def _on_rollout_start(self):
        self._write_pending()

    def _on_training_end(self):
        self._write_pending()


def evaluate(model, activity, mode, episodes, deterministic):
    """Episodes 0..episodes-1 of evaluation seed 0's stream (env seeds 0..N-1)."""
    env = PrimitiveEnv(activity, mode, None)
    per_episode, failed, ended = [], collections.Counter(), collections.Counter()
    for j in range(episodes):
        torch.manual_seed(j)  # a sampled episode's draws, fixed by the episode
        obs, _ = env.reset(seed=j)
        while True:
            action, _ = model.predict(obs, deterministic=deterministic)
            obs, _, terminated, truncated, info = env.step(action)
            status = int(info["primitive_status"])
            if 0 < status < len(STATUSES):
                failed[STATUSES[status]] += 1
            if terminated or truncated:
                break
        end = "success" if info["success"] else "time_limit" if truncated else "other"
        ended[end] += 1
        per_episode.append({"env_seed": j, "q": float(info["q"]), "success": bool(info["success"]),
                            "length": int(info["elapsed_step"])})
    env.close()
    q = [e["q"] for e in per_episode]
    return {"policy": "greedy" if deterministic else "sampled", "episodes": episodes, "q": {"mean": float(np.mean(q))},
            "success_rate": {"mean": float(np.mean([e["success"] for e in per_episode]))},
            "failed_primitives": dict(failed), "episodes_ended_by": dict(ended), "per_episode": per_episode}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--activity", required=True)
    parser.add_argument("--seed", type=int, required=True)
    parser.add_argument("--steps", type=int, default=30000)
    parser.add_argument("--mode", choices=["symbolic", "physical"], default="symbolic")
    parser.add_argument("--eval-episodes", type=int, default=100)
    # Table A.12's c2. (chore's PPO halved the squared error until issue 53's
    # correction: 0.25 here weighs the value loss as it did.)
    parser.add_argument("--vf-coef", type=float, default=0.5)
    parser.add_argument("--input-norm", choices=["unit", "running"], default="unit",
                        help="unit: SB3's images / 255, the state as it is; running: chore's running statistics")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    torch.set_num_threads(1)
    env = PrimitiveEnv(args.activity, args.mode, args.seed)
    model = ChorePPO("MultiInputPolicy", env, learning_rate=3e-4, n_steps=300, batch_size=64, n_epochs=10, gamma=0.99,
                gae_lambda=0.99, clip_range=0.2, ent_coef=0.0, vf_coef=args.vf_coef, max_grad_norm=0.5,
                normalize_advantage=True, seed=args.seed, device="cpu",
                policy_kwargs={"features_extractor_class": ChoreEncoder,
                               "features_extractor_kwargs": {"input_norm": args.input_norm},
                               "normalize_images": args.input_norm == "unit",
                               "net_arch": {"pi": [], "vf": []}, "share_features_extractor": True})
    start = time.monotonic()
    model.learn(total_timesteps=args.steps, callback=Metrics(os.path.join(args.out, "metrics.csv")))
    train_s = time.monotonic() - start
    model.save(os.path.join(args.out, "model.zip"))
    result = {"activity": args.activity, "seed": args.seed, "steps": args.steps, "mode": args.mode,
              "vf_coef": args.vf_coef, "input_norm": args.input_norm,
              "train_wall_s": train_s, "sb3": sys.modules["stable_baselines3"].__version__,
              "torch": torch.__version__,
              "seed0": evaluate(model, args.activity, args.mode, args.eval_episodes, deterministic=False),
              "seed0_greedy": evaluate(model, args.activity, args.mode, args.eval_episodes, deterministic=True)}
    with open(os.path.join(args.out, "eval_seed0.json"), "w") as f:
        json.dump(result, f, indent=2)
    print(f"{args.activity} seed {args.seed}: trained in {train_s / 60:.1f} min; Q at seed 0 "
          f"sampled {result['seed0']['q']['mean']:.3f}, greedy {result['seed0_greedy']['q']['mean']:.3f}")


if __name__ == "__main__":
    main()
