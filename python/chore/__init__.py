"""chore from Python: BEHAVIOR-style household activities as fast RL
environments, in Gymnasium's shape.

    import chore
    envs = chore.make("store_decoration", num_envs=8, num_threads=2, seed=0)
    obs, info = envs.reset(seed=0)
    obs, rewards, terminated, truncated, info = envs.step(envs.action_space.sample())

Observations are NumPy arrays of your own, as Gymnasium's contract has
them. copy=False gives EnvPool's zero copy instead: arrays that view chore's
own buffers, which hold until the next reset/step/recv of the same env
writes over them.
"""

import functools
import os
import pathlib

import numpy as np

# An installed wheel carries the knowledge base, activities and assets
# (pyproject.toml); a build tree's package reads them from the source tree.
_DATA = pathlib.Path(__file__).resolve().parent / "data"
if _DATA.is_dir():
    os.environ.setdefault("CHORE_TASKS", str(_DATA / "tasks"))
    os.environ.setdefault("CHORE_ASSETS", str(_DATA / "assets"))

from . import spaces
from ._chore import Error, Goal, mujoco_version
from .spaces import _gymnasium
from .evaluation import evaluate, format_evaluation, load_policy
from ._chore import Env as _Env
from ._chore import VectorEnv as _VectorEnv

__all__ = ["Env", "VectorEnv", "Error", "Goal", "mujoco_version", "make", "spaces", "evaluate", "format_evaluation", "load_policy"]

_CONFIG_KEYS = ("width", "height", "observations", "max_episode_steps", "reward", "reachable_instances",
                "policy_failure_rule", "policy_failure_repeats", "instances", "instance", "robot", "object_states",
                "cloth")


def _config(task, scene, action_space, mode, observations, options):
    """EnvConfig's fields from make()'s arguments: the task is an activity (a
    name or a .bddl path) or a scene (a scene file or a BEHAVIOR-1K inventory
    scene); scene= sets an activity's scene."""
    unknown = sorted(set(options) - set(_CONFIG_KEYS))
    if unknown:
        raise Error(f"unknown option(s) {', '.join(unknown)} (known: {', '.join(_CONFIG_KEYS)})")
    config = dict(options)
    if task is not None:
        config["task"] = str(task)
    if scene is not None:
        config["scene"] = str(scene)
    config["action_space"] = action_space
    config["mode"] = mode
    if observations is not None:
        if isinstance(observations, str):
            raise Error(f"observations={observations!r}: expected a list of names, e.g. [{observations!r}]")
        config["observations"] = list(observations)
    return config


def _seed(seed):
    if seed is None:
        return None
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)) or not 0 <= seed < 2**63:
        raise Error(f"seed {seed!r}: expected an integer in [0, 2^63)")
    return int(seed)


def _copied(obs):
    return {k: np.array(v) for k, v in obs.items()}


class _Closing:
    """What both envs share: `with chore.make(...) as env:` closes it; no wrappers."""

    @property
    def unwrapped(self):
        return self

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


# Gymnasium's base classes where it is installed (it is not a Debian 12
# package): isinstance checks, its env checker and wrappers accept chore's envs.
_EnvBase = _gymnasium.Env if _gymnasium else object
_VectorEnvBase = _gymnasium.vector.VectorEnv if _gymnasium else object


class Env(_Closing, _EnvBase):
    """One environment with Gymnasium's Env API: reset(seed=, options=) ->
    (obs, info), step(action) -> (obs, reward, terminated, truncated, info)."""

    metadata = {"render_modes": []}
    render_mode = None

    def __init__(self, task=None, *, scene=None, action_space="low_level", mode="physical", observations=None,
                 copy=True, **options):
        self._env = _Env(_config(task, scene, action_space, mode, observations, options))
        self._copy = copy
        self.observation_space = spaces.from_description(self._env.observation_space)
        self.action_space = spaces.from_description(self._env.action_space)
        self.primitive_actions = self._env.primitive_actions
        self.spec = None

    def reset(self, *, seed=None, options=None):
        obs, info = self._env.reset(_seed(seed))
        if _gymnasium:  # Gymnasium's np_random, seeded as its contract says (chore's own streams are in C++)
            super().reset(seed=seed)
        if seed is not None:
            self.action_space.seed(int(seed))
        return (_copied(obs) if self._copy else obs), info

    def step(self, action):
        obs, reward, terminated, truncated, info = self._env.step(action)
        return (_copied(obs) if self._copy else obs), reward, terminated, truncated, info

    def close(self):
        self._env.close()


class VectorEnv(_Closing, _VectorEnvBase):
    """num_envs environments stepped by num_threads C++ workers with
    Gymnasium's VectorEnv API (env i is seeded seed + i), and EnvPool's
    send(actions, env_ids) / recv() when batch_size < num_envs. Autoreset as
    Gymnasium's NEXT_STEP or SAME_STEP (metadata["autoreset_mode"]); with
    SAME_STEP, info["final_obs"] and info["final_info"] hold the ended
    episodes' last observations (rows where info["_final_obs"] is True).
    rendering: "per_thread" (each worker draws its envs in a render context
    of its own) or "batch" (one context draws every env of a batch in one
    pass, on the calling thread)."""

    def __init__(self, task=None, *, scene=None, num_envs=1, num_threads=1, batch_size=None,
                 action_space="low_level", mode="physical", observations=None, autoreset_mode="next_step",
                 rendering="per_thread", seed=None, copy=True, **options):
        autoreset_mode = getattr(autoreset_mode, "name", autoreset_mode)  # gymnasium.vector.AutoresetMode
        autoreset_mode = str(autoreset_mode).lower()
        config = _config(task, scene, action_space, mode, observations, options)
        self._envs = _VectorEnv(config, int(num_envs), int(num_threads), int(batch_size or 0), autoreset_mode,
                                str(rendering))
        self._copy = copy
        self._seed = _seed(seed)
        self.num_envs = self._envs.num_envs
        self.batch_size = self._envs.batch_size
        self.metadata = {"autoreset_mode": _autoreset_mode(autoreset_mode)}
        self.single_observation_space = spaces.from_description(self._envs.single_observation_space)
        self.single_action_space = spaces.from_description(self._envs.single_action_space)
        self.observation_space = spaces.batched(self.single_observation_space, self.num_envs)
        self.action_space = spaces.batched(self.single_action_space, self.num_envs)
        self.primitive_actions = self._envs.primitive_actions
        self.closed = False

    def reset(self, *, seed=None, options=None):
        """seed: an int (env i gets seed + i), a list of one int or None per
        env (Gymnasium's), or None (each env's stream continues; make's seed=
        seeds the first reset)."""
        if seed is None:
            seed = self._seed
        self._seed = None  # make(seed=) seeds the first reset only
        if isinstance(seed, (list, tuple)):
            if len(seed) != self.num_envs:
                raise Error(f"seed: {len(seed)} seeds for {self.num_envs} envs")
            seeds = [None if s is None else _seed(s) for s in seed]
        else:
            first = _seed(seed)
            seeds = [None if first is None else first + i for i in range(self.num_envs)]
        obs, info = self._envs.reset(seeds)
        if seeds[0] is not None:
            self.action_space.seed(seeds[0])
        return self._obs(obs), _with_masks(info)

    def step(self, actions):
        return self._results(self._envs.step(self._actions(actions, self.num_envs)))

    def send(self, actions, env_ids=None):
        """Starts those envs stepping (all when env_ids is None)."""
        ids = np.arange(self.num_envs, dtype=np.int32) if env_ids is None else np.asarray(env_ids)
        if ids.ndim != 1 or ids.dtype.kind not in "ui":
            raise Error("send: env_ids: expected a list of integer env ids")
        self._envs.send(self._actions(actions, len(ids)), ids.astype(np.int32))

    def recv(self):
        """The first batch_size envs to finish: (obs, rewards, terminated,
        truncated, info), info["env_id"] saying whose each row is."""
        return self._results(self._envs.recv())

    def close(self, **kwargs):
        if not self.closed:
            self._envs.close()
            self.closed = True

    def _actions(self, actions, rows):
        a = np.asarray(actions)
        if a.dtype.kind not in "uif":
            raise Error(f"actions of dtype {a.dtype}: expected numbers")
        if a.dtype.kind == "f" and not np.all(np.isfinite(a)):
            raise Error("actions: NaN or infinite values")
        size = int(np.prod(self.single_action_space.shape)) if self.single_action_space.shape else 1
        if a.size != rows * size or (a.ndim > 0 and a.shape[0] != rows):
            raise Error(f"actions of shape {a.shape}: expected {rows} rows of {size}")
        return np.ascontiguousarray(a, dtype=np.float32).reshape(rows * size)

    def _obs(self, obs):
        return _copied(obs) if self._copy else obs

    def _results(self, results):
        obs, rewards, terminated, truncated, info = results
        if "final_obs" in info:
            ended = terminated | truncated
            info["_final_obs"] = ended
            info["_final_info"] = ended.copy()
        if self._copy:
            if "final_obs" in info:
                info["final_obs"] = _copied(info["final_obs"])
            rewards, terminated, truncated = rewards.copy(), terminated.copy(), truncated.copy()
        return self._obs(obs), rewards, terminated, truncated, _with_masks(info)


def _with_masks(info):
    """Gymnasium's vector info: beside each field, "_field" says which rows
    have it (every row has chore's fields)."""
    every_row = _all_rows(len(info["env_id"]))
    for key in [k for k in info if not k.startswith("_") and k not in ("final_obs", "final_info")]:
        info["_" + key] = every_row
    return info


@functools.lru_cache(maxsize=None)
def _all_rows(rows):
    """One read-only mask of True per batch size, shared by every field and step."""
    mask = np.ones(rows, dtype=bool)
    mask.flags.writeable = False
    return mask


def _autoreset_mode(name):
    try:  # Gymnasium's own enum where it is importable
        from gymnasium.vector import AutoresetMode
        return AutoresetMode.NEXT_STEP if name == "next_step" else AutoresetMode.SAME_STEP
    except ImportError:
        return name


def make(task=None, *, num_envs=None, **kwargs):
    """EnvPool's entry point: a VectorEnv of num_envs envs, or a single Env
    when num_envs is None. kwargs: scene, num_threads, batch_size,
    observations, action_space ("low_level" | "primitives"), mode ("physical"
    | "symbolic"), autoreset_mode ("next_step" | "same_step"), rendering
    ("per_thread" | "batch"), seed, copy, and
    the env options width, height, max_episode_steps, reward,
    reachable_instances, policy_failure_rule ("none" | "precondition" |
    "paper"), policy_failure_repeats, instances ("resample" | "fixed"),
    instance, robot, object_states, cloth."""
    if num_envs is None:
        for vector_only in ("num_threads", "batch_size", "autoreset_mode", "rendering", "seed"):
            if vector_only in kwargs:
                raise Error(f"make: {vector_only} needs num_envs")
        return Env(task, **kwargs)
    return VectorEnv(task, num_envs=num_envs, **kwargs)
