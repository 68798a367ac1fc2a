"""chore against Gymnasium itself (issue 55): Gymnasium's own env checker on
chore.Env for both action spaces, from scripts/setup's test venv
(tests/requirements.txt pins the version). Where chore departs from
Gymnasium it is a documented decision, and pinned here: copy=False, EnvPool's
zero copy, returns views the next call writes over, which the checker
refuses."""

import gymnasium
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
