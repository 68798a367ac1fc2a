"""chore.evaluate and checkpoints as policies: the reports chore eval prints."""

import glob
import json
import os
import subprocess

import numpy as np
import pytest

import chore

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CHECKPOINT = os.path.join(ROOT, "results", "clean_table_dry_rag", "runs", "physical", "clean_table", "rl-prim_seed0",
                          "checkpoint.pt")


def cli_report(*args):
    out = subprocess.run([os.environ["CHORE_BINARY"], "eval", *args, "--json"], check=True, capture_output=True,
                         text=True).stdout
    reports = json.loads(out)  # one per policy
    assert len(reports) == 1
    return reports[0]


def without_timing(report):
    return {k: v for k, v in report.items() if k not in ("wall_seconds", "policy")}


def test_the_expert_scores_as_chore_eval_scores_it():
    report = chore.evaluate("expert", "store_decoration", seeds="0-1", episodes=2, threads=2, mode="symbolic")
    assert report["success_rate"]["mean"] == 1.0
    cli = cli_report("--expert", "--activity", "store_decoration", "--seeds", "0-1", "--episodes", "2", "--threads",
                     "2", "--mode", "symbolic")
    assert without_timing(report) == without_timing(cli)
    assert "success rate" in chore.format_evaluation(report)


def test_the_expert_plans_an_activity_its_script_does_not_know():
    steak = os.path.join(ROOT, "tests", "data", "bddl", "behavior-1k", "cook_a_steak.bddl")
    report = chore.evaluate("expert", steak, episodes=2, mode="symbolic")
    assert report["success_rate"]["mean"] == 1.0  # the steak cooked on the stove, by the planner's expert


def test_a_python_callable_is_a_policy():
    calls = []

    class MaskedRandom:
        def __init__(self):
            self.rng = np.random.default_rng(0)

        def __call__(self, obs, info):
            calls.append(obs["action_mask"].shape)
            return np.array([self.rng.choice(np.flatnonzero(row)) for row in obs["action_mask"]])

        def reset(self, env_ids):
            calls.append(("reset", tuple(env_ids)))

    report = chore.evaluate(MaskedRandom(), "store_decoration", seeds=range(3, 4), episodes=2, mode="symbolic",
                            observations=["action_mask"], max_steps=8)
    assert len(report["per_episode"]) == 2
    assert all(e["length"] <= 8 for e in report["per_episode"])
    assert ("reset", (0,)) in calls and (1, 7) in calls


def test_a_policy_that_raises_stops_the_evaluation_with_its_error():
    def broken(obs, info):
        raise ValueError("no idea")

    with pytest.raises(ValueError, match="no idea"):
        chore.evaluate(broken, "store_decoration", episodes=1, mode="symbolic", observations=["action_mask"])
    with pytest.raises(chore.Error, match="expected 1 values"):
        chore.evaluate(lambda obs, info: np.zeros(3), "store_decoration", episodes=1, mode="symbolic",
                       observations=["action_mask"])


def test_a_checkpoint_is_a_policy_and_evaluates_as_the_cli_evaluates_it():
    policy = chore.load_policy(CHECKPOINT)
    assert policy.baseline == "rl-prim" and policy.env["activity"] == "clean_table"
    with chore.make(policy.env["activity"], num_envs=2, action_space=policy.env["action_space"],
                    observations=policy.env["observations"], mode="symbolic") as envs:
        obs, info = envs.reset(seed=0)
        actions = policy(obs, info)
        assert actions.shape == (2,) and envs.action_space.contains(actions)
        assert np.array_equal(actions, policy(obs, info)), "greedy: the same observation, the same action"
    report = chore.evaluate(policy, seeds=0, episodes=2, mode="symbolic", max_steps=10)
    cli = cli_report("--checkpoint", CHECKPOINT, "--seeds", "0-0", "--episodes", "2", "--mode", "symbolic",
                     "--max-steps", "10")
    assert without_timing(report) == without_timing(cli)
    with pytest.raises(chore.Error, match="lacks 'rgb'"):
        policy({"is_grasping": np.zeros((1, 1), np.float32)})


def test_a_bad_checkpoint_is_a_chore_error(tmp_path):
    bad = tmp_path / "checkpoint.pt"
    bad.write_bytes(b"not a checkpoint")
    with pytest.raises(chore.Error, match="checkpoint"):
        chore.load_policy(bad)
