"""chore against Gymnasium itself (issue 55): Gymnasium's own env checker on
chore.Env for both action spaces, from scripts/setup's test venv
(tests/requirements.txt pins the version). Where chore departs from
Gymnasium it is a documented decision, and pinned here: copy=False, EnvPool's
zero copy, returns views the next call writes over, which the checker
refuses."""

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import chore

CASES = [
    ("collect_trash", dict(action_space="primitives", mode="symbolic")),
    ("store_decoration", dict(action_space="primitives", mode="physical", observations=["rgb", "is_grasping"])),
    ("clean_table", dict(action_space="low_level", observations=["rgb", "depth", "proprio", "is_grasping"])),
]


def test_the_checked_gymnasium_is_the_pinned_one():
    assert gymnasium.__version__ == "1.4.0"


@pytest.mark.parametrize("task,options", CASES, ids=[c[0] for c in CASES])
def test_gymnasiums_env_checker_passes(task, options):
    env = chore.make(task, **options)
    assert isinstance(env, gymnasium.Env)
    assert isinstance(env.observation_space, gymnasium.spaces.Dict)
    check_env(env, skip_render_check=True)  # chore renders only through its observations
    env.close()


def test_zero_copy_is_a_documented_departure():
    env = chore.make("collect_trash", action_space="primitives", mode="symbolic", copy=False)
    with pytest.raises(AssertionError, match="share an object"):
        check_env(env, skip_render_check=True)
    env.close()


def test_the_vector_env_is_gymnasiums_in_spaces_seeds_and_autoreset():
    from gymnasium.vector import AutoresetMode
    from gymnasium.vector.utils import batch_space

    with chore.make("collect_trash", num_envs=3, action_space="primitives", mode="symbolic",
                    observations=["rgb", "is_grasping"], max_episode_steps=4) as envs:
        assert isinstance(envs, gymnasium.vector.VectorEnv)
        assert envs.observation_space == batch_space(envs.single_observation_space, 3)
        assert envs.action_space == batch_space(envs.single_action_space, 3)
        assert envs.metadata["autoreset_mode"] is AutoresetMode.NEXT_STEP
        obs, info = envs.reset(seed=[11, None, 13])  # Gymnasium's seed per env
        assert envs.observation_space.contains(obs)
        assert info["episode_seed"][0] == 11 and info["episode_seed"][2] == 13
        again, _ = envs.reset(seed=11)  # an int: env i gets 11 + i
        assert (again["rgb"][0] == obs["rgb"][0]).all()
        with pytest.raises(chore.Error, match="2 seeds for 3 envs"):
            envs.reset(seed=[1, 2])
        # NEXT_STEP: the step after the last one resets that env: reward 0, not terminated or truncated.
        for _ in range(4):
            obs, rewards, terminated, truncated, info = envs.step(envs.action_space.sample())
        assert truncated.all()
        obs, rewards, terminated, truncated, info = envs.step(envs.action_space.sample())
        assert (rewards == 0).all() and not terminated.any() and not truncated.any()
        assert (info["elapsed_step"] == 0).all()
    with chore.make("collect_trash", num_envs=2, action_space="primitives", mode="symbolic",
                    observations=["is_grasping"], max_episode_steps=2, autoreset_mode=AutoresetMode.SAME_STEP) as envs:
        assert envs.metadata["autoreset_mode"] is AutoresetMode.SAME_STEP
        envs.reset(seed=0)
        envs.step(envs.action_space.sample())
        obs, rewards, terminated, truncated, info = envs.step(envs.action_space.sample())
        assert truncated.all() and info["_final_obs"].all() and info["_final_info"].all()
        assert envs.single_observation_space.contains({k: v[0] for k, v in info["final_obs"].items()})
        assert (info["elapsed_step"] == 0).all(), "the returned observation is the next episode's first"


def test_gymnasiums_vector_wrappers_run_over_chore():
    from gymnasium.wrappers import vector as wrappers

    envs = chore.make("collect_trash", num_envs=2, action_space="primitives", mode="symbolic",
                      observations=["rgb", "is_grasping"], max_episode_steps=5, seed=0)
    stats = wrappers.RecordEpisodeStatistics(envs)
    stats.reset(seed=0)
    returns = np.zeros(2)
    for t in range(5):
        _, rewards, terminated, truncated, info = stats.step(stats.action_space.sample())
        returns += rewards
    assert truncated.all() and info["_episode"].all()
    np.testing.assert_allclose(info["episode"]["r"], returns, rtol=1e-6)
    assert list(info["episode"]["l"]) == [5, 5]
    normalized = wrappers.NormalizeObservation(
        wrappers.FlattenObservation(wrappers.FilterObservation(envs, ["is_grasping"])))
    obs, _ = normalized.reset(seed=1)
    assert obs.shape == (2, 1) and obs.dtype == np.float32
    obs, *_ = normalized.step(normalized.action_space.sample())
    assert np.isfinite(obs).all()
    normalized.close()


def test_gymnasiums_wrappers_run_over_a_single_env():
    from gymnasium import wrappers

    options = dict(action_space="primitives", mode="symbolic", observations=["rgb", "is_grasping"],
                   max_episode_steps=3)
    actions = [0, 3, 6]
    with chore.make("collect_trash", **options) as plain:
        plain.reset(seed=4)
        frames = [plain.step(a)[0]["rgb"] for a in actions]
    assert not (frames[0] == frames[1]).all(), "the frames differ, so a stack of views would show"
    env = wrappers.FrameStackObservation(wrappers.RecordEpisodeStatistics(chore.make("collect_trash", **options)),
                                         stack_size=3)
    env.reset(seed=4)
    for a in actions:
        obs, _, terminated, truncated, info = env.step(a)
    assert truncated and info["episode"]["l"] == 3
    # The stack holds each step's own frame: copies, not views a later step wrote over.
    for k in range(3):
        assert (obs["rgb"][k] == frames[k]).all(), k
    env.close()
