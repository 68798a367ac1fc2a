"""The Python examples: the PPO one learns, the random agent runs."""

import importlib.util
import os
import subprocess
import sys

import numpy as np

import chore

EXAMPLES = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "examples",
                        "python")


def load(name):
    spec = importlib.util.spec_from_file_location(name, os.path.join(EXAMPLES, name + ".py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_ppo_learns_store_decoration_above_a_random_policy():
    ppo = load("ppo_primitives")
    trained = ppo.main(["--total-steps", "12288", "--seed", "0"])

    class MaskedRandom:
        def __init__(self):
            self.rng = np.random.default_rng(0)

        def __call__(self, obs, info):
            return np.array([self.rng.choice(np.flatnonzero(m)) for m in obs["action_mask"]])

    random = chore.evaluate(MaskedRandom(), "store_decoration", seeds="0-4", episodes=4, threads=2, mode="symbolic",
                            observations=["action_mask", "is_grasping"], max_steps=30)
    assert trained["success_rate"]["mean"] >= random["success_rate"]["mean"] + 0.3, (trained["success_rate"],
                                                                                     random["success_rate"])
    assert trained["q"]["mean"] > random["q"]["mean"]


def test_the_random_agent_runs():
    out = subprocess.run([sys.executable, os.path.join(EXAMPLES, "random_agent.py"), "--envs", "2", "--threads", "1",
                          "--steps", "20", "--action-space", "low_level"], check=True, capture_output=True,
                         text=True).stdout
    assert out.startswith("collect_trash: ") and "env steps/s" in out
