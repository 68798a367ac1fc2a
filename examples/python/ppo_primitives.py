"""PPO over action primitives on a chore vector env, CleanRL-style: one file,
read top to bottom. The policy sees which primitives can run now
(action_mask), whether the robot holds something, and its own last few
primitives (as RL-Prim.Hist keeps a history: the mask alone does not say what
is done already), and picks one; invalid primitives are masked out of its
distribution.

    /usr/bin/python3 examples/python/ppo_primitives.py --activity store_decoration --mode symbolic \
        --total-steps 20000 --out ppo.pt
"""

import argparse
import time

import numpy as np
import torch
import torch.nn as nn

import chore


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--activity", default="store_decoration")
    p.add_argument("--mode", default="symbolic", choices=["symbolic", "physical"])
    p.add_argument("--envs", type=int, default=8)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--total-steps", type=int, default=20000)
    p.add_argument("--rollout", type=int, default=64, help="steps per env per update")
    p.add_argument("--episode-steps", type=int, default=30)
    p.add_argument("--lr", type=float, default=2.5e-3)
    p.add_argument("--gamma", type=float, default=0.99)
    p.add_argument("--gae-lambda", type=float, default=0.95)
    p.add_argument("--epochs", type=int, default=4)
    p.add_argument("--minibatches", type=int, default=4)
    p.add_argument("--clip", type=float, default=0.2)
    p.add_argument("--entropy", type=float, default=0.01)
    p.add_argument("--history", type=int, default=4, help="last primitives the policy sees")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--out", default="", help="where to save the trained agent (torch.save of its state dict)")
    return p.parse_args(argv)


def features(obs, history):
    """What the agent sees: the action mask, the grasp flag and the one-hot
    history of its last primitives (rows: envs), as floats."""
    # chore's arrays are read-only views of its buffers: torch.tensor copies them.
    mask = torch.tensor(obs["action_mask"], dtype=torch.float32)
    grasping = torch.tensor(obs["is_grasping"], dtype=torch.float32).reshape(len(mask), -1)
    return torch.cat([mask, grasping, history.flatten(1)], dim=1), mask.bool()


def remember(history, actions, ended):
    """Shifts each env's history by its action; an ended episode's is cleared."""
    history = torch.roll(history, 1, dims=1)
    history[:, 0] = nn.functional.one_hot(actions, history.shape[2]).float()
    history[torch.as_tensor(ended)] = 0
    return history


class Agent(nn.Module):
    def __init__(self, inputs, actions):
        super().__init__()
        self.critic = nn.Sequential(nn.Linear(inputs, 64), nn.Tanh(), nn.Linear(64, 64), nn.Tanh(), nn.Linear(64, 1))
        self.actor = nn.Sequential(nn.Linear(inputs, 64), nn.Tanh(), nn.Linear(64, 64), nn.Tanh(),
                                   nn.Linear(64, actions))

    def value(self, x):
        return self.critic(x).squeeze(-1)

    def distribution(self, x, mask):
        logits = self.actor(x).masked_fill(~mask, -1e8)  # primitives that cannot run now are never drawn
        return torch.distributions.Categorical(logits=logits)



class Player:
    """The trained agent as a chore.evaluate policy: greedy actions, a history
    per env, cleared when chore says an env starts a new episode."""

    def __init__(self, agent, envs, actions, history):
        self.agent, self.history = agent, torch.zeros(envs, history, actions)

    def reset(self, env_ids):
        self.history[env_ids] = 0

    def __call__(self, obs, info):
        ids = torch.as_tensor(info["env_id"], dtype=torch.long)
        with torch.no_grad():
            x, mask = features(obs, self.history[ids])
            a = self.agent.distribution(x, mask).probs.argmax(-1)
        self.history[ids] = remember(self.history[ids], a, np.zeros(len(ids), bool))
        return a.numpy()


def train(args):
    torch.manual_seed(args.seed)
    torch.set_num_threads(1)
    envs = chore.make(args.activity, num_envs=args.envs, num_threads=min(args.threads, args.envs),
                      action_space="primitives", mode=args.mode, observations=["action_mask", "is_grasping"],
                      max_episode_steps=args.episode_steps, seed=args.seed)
    n_actions = envs.single_action_space.n
    obs, _ = envs.reset()
    history = torch.zeros(args.envs, args.history, n_actions)
    x, mask = features(obs, history)
    agent = Agent(x.shape[1], n_actions)
    optimizer = torch.optim.Adam(agent.parameters(), lr=args.lr, eps=1e-5)

    T, N = args.rollout, args.envs
    xs = torch.zeros(T, N, x.shape[1])
    masks = torch.zeros(T, N, n_actions, dtype=torch.bool)
    actions = torch.zeros(T, N, dtype=torch.long)
    logprobs, rewards, dones, values = (torch.zeros(T, N) for _ in range(4))
    done = torch.zeros(N)
    updates = max(1, args.total_steps // (T * N))
    start, episodes, successes = time.perf_counter(), 0, 0
    for update in range(updates):
        for t in range(T):
            xs[t], masks[t], dones[t] = x, mask, done
            with torch.no_grad():
                d = agent.distribution(x, mask)
                a = d.sample()
                logprobs[t], values[t] = d.log_prob(a), agent.value(x)
            actions[t] = a
            obs, reward, terminated, truncated, info = envs.step(a.numpy())
            rewards[t] = torch.tensor(reward)
            ended = terminated | truncated
            done = torch.as_tensor(ended, dtype=torch.float32)
            episodes += int(ended.sum())
            successes += int(info["success"][ended].sum())
            history = remember(history, a, ended)
            x, mask = features(obs, history)
        # Generalised advantage estimation, bootstrapped from the last value.
        with torch.no_grad():
            advantages = torch.zeros(T, N)
            next_value, next_done, last = agent.value(x), done, torch.zeros(N)
            for t in reversed(range(T)):
                nonterminal = 1.0 - next_done
                delta = rewards[t] + args.gamma * next_value * nonterminal - values[t]
                last = delta + args.gamma * args.gae_lambda * nonterminal * last
                advantages[t] = last
                next_value, next_done = values[t], dones[t]
            returns = advantages + values
        # Clipped surrogate updates over shuffled minibatches.
        b_x, b_mask, b_a = xs.reshape(T * N, -1), masks.reshape(T * N, -1), actions.reshape(-1)
        b_logp, b_adv, b_ret = logprobs.reshape(-1), advantages.reshape(-1), returns.reshape(-1)
        size = T * N // args.minibatches
        for _ in range(args.epochs):
            for idx in torch.randperm(T * N).split(size):
                d = agent.distribution(b_x[idx], b_mask[idx])
                ratio = (d.log_prob(b_a[idx]) - b_logp[idx]).exp()
                adv = (b_adv[idx] - b_adv[idx].mean()) / (b_adv[idx].std() + 1e-8)
                policy_loss = torch.max(-adv * ratio, -adv * ratio.clamp(1 - args.clip, 1 + args.clip)).mean()
                value_loss = 0.5 * ((agent.value(b_x[idx]) - b_ret[idx]) ** 2).mean()
                loss = policy_loss + 0.5 * value_loss - args.entropy * d.entropy().mean()
                optimizer.zero_grad()
                loss.backward()
                nn.utils.clip_grad_norm_(agent.parameters(), 0.5)
                optimizer.step()
        steps = (update + 1) * T * N
        print(f"update {update + 1}/{updates}: {steps} steps, {steps / (time.perf_counter() - start):.0f} steps/s, "
              f"success {successes}/{episodes} episodes so far", flush=True)
    envs.close()
    return agent, n_actions


def main(argv=None):
    args = parse_args(argv)
    agent, n_actions = train(args)
    threads = 2
    report = chore.evaluate(Player(agent, threads, n_actions, args.history), args.activity, seeds="0-4", episodes=4,
                            threads=threads, mode=args.mode, observations=["action_mask", "is_grasping"],
                            max_steps=args.episode_steps)
    print(chore.format_evaluation(report))
    if args.out:
        torch.save(agent.state_dict(), args.out)
    return report


if __name__ == "__main__":
    main()
