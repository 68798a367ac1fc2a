"""The package where Gymnasium is not installed (Debian's python3 alone, as
`scripts/setup --python` leaves it): chore's own spaces, plain base classes,
the same env semantics. ctest runs this with /usr/bin/python3 and the rest of
the suite with build/test-venv, which has Gymnasium."""

import importlib.util

import numpy as np

import chore


def test_gymnasium_is_absent_here():
    assert importlib.util.find_spec("gymnasium") is None


def test_chores_own_spaces_hold_what_reset_and_step_return():
    with chore.make("collect_trash", observations=["rgb", "proprio", "is_grasping"]) as env:
        assert type(env.observation_space) is chore.spaces.Dict
        assert type(env.action_space) is chore.spaces.Box
        obs, _ = env.reset(seed=0)
        assert env.observation_space.contains(obs)
        env.action_space.seed(0)
        obs, reward, terminated, truncated, _ = env.step(env.action_space.sample())
        assert env.observation_space.contains(obs) and np.isfinite(reward)
        assert obs["rgb"].flags.owndata, "copies by default, with or without Gymnasium"
    with chore.make("collect_trash", num_envs=2, action_space="primitives", mode="symbolic",
                    observations=["action_mask"]) as envs:
        assert type(envs.single_action_space) is chore.spaces.Discrete
        assert type(envs.action_space) is chore.spaces.MultiDiscrete
        assert envs.metadata["autoreset_mode"] == "next_step"
        envs.reset(seed=3)
        envs.action_space.seed(3)
        obs, rewards, _, _, info = envs.step(envs.action_space.sample())
        assert envs.observation_space.contains(obs) and rewards.shape == (2,)
        assert list(info["episode_seed"]) == [3, 4]
