"""A random agent on a chore vector env: the smallest complete loop.

    /usr/bin/python3 examples/python/random_agent.py --activity collect_trash --envs 4 --steps 200
"""

import argparse
import time

import numpy as np

import chore


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--activity", default="collect_trash")
    parser.add_argument("--envs", type=int, default=4)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--action-space", default="primitives", choices=["primitives", "low_level"])
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()

    envs = chore.make(args.activity, num_envs=args.envs, num_threads=min(args.threads, args.envs),
                      action_space=args.action_space, observations=["rgb", "proprio"], seed=args.seed)
    envs.reset()
    envs.action_space.seed(args.seed)
    episodes, successes, q_sum = 0, 0, 0.0
    start = time.perf_counter()
    for _ in range(args.steps):
        _, _, terminated, truncated, info = envs.step(envs.action_space.sample())
        ended = terminated | truncated
        episodes += int(ended.sum())
        successes += int(info["success"][ended].sum())
        q_sum += float(info["q"][ended].sum())
    seconds = time.perf_counter() - start
    envs.close()
    print(f"{args.activity}: {args.steps * args.envs / seconds:.0f} env steps/s, {episodes} episodes ended, "
          f"success {successes}/{episodes}, mean Q {q_sum / max(episodes, 1):.3f}")


if __name__ == "__main__":
    main()
