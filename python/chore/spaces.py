"""Spaces as Gymnasium has them: gymnasium.spaces objects when Gymnasium is
importable, else local classes with the same attributes and methods
(shape, dtype, low, high, n, nvec, spaces, sample, contains, seed), so code written
against Gymnasium's spaces runs either way."""

from collections import OrderedDict

import numpy as np

try:  # Gymnasium is not a Debian 12 package: scripts/setup's test venv has it
    import gymnasium as _gymnasium
    import gymnasium.spaces as _gym_spaces
    import gymnasium.vector  # noqa: F401 (chore's VectorEnv derives from its VectorEnv)
except ImportError:
    _gymnasium = _gym_spaces = None


class _Space:
    """What the local spaces share: a seedable random stream, `x in space`."""

    _rng = None

    def seed(self, seed=None):
        self._rng = np.random.default_rng(seed)
        return [seed]

    @property
    def np_random(self):
        if self._rng is None:
            self._rng = np.random.default_rng()
        return self._rng

    def __contains__(self, x):
        return self.contains(x)


class Box(_Space):
    """Gymnasium's Box: values in [low, high] of one shape and dtype."""

    def __init__(self, low, high, shape, dtype):
        self.dtype = np.dtype(dtype)
        self.shape = tuple(shape)
        self.low = np.full(self.shape, low, dtype=self.dtype)
        self.high = np.full(self.shape, high, dtype=self.dtype)


    def sample(self):
        if self.dtype.kind in "ui":
            return self.np_random.integers(self.low, self.high, endpoint=True, dtype=self.dtype)
        low = np.where(np.isfinite(self.low), self.low, -1.0)
        high = np.where(np.isfinite(self.high), self.high, 1.0)
        return self.np_random.uniform(low, high).astype(self.dtype)

    def contains(self, x):
        x = np.asarray(x)
        return (x.shape == self.shape and np.can_cast(x.dtype, self.dtype)
                and bool(np.all(x >= self.low)) and bool(np.all(x <= self.high)))


    def __repr__(self):
        return f"Box({self.low.flat[0] if self.low.size else ''}, {self.high.flat[0] if self.high.size else ''}, {self.shape}, {self.dtype})"


class Discrete(_Space):
    """Gymnasium's Discrete: integers 0 .. n-1."""

    def __init__(self, n):
        self.n = np.int64(n)
        self.start = np.int64(0)
        self.shape = ()
        self.dtype = np.dtype(np.int64)


    def sample(self):
        return np.int64(self.np_random.integers(self.n))

    def contains(self, x):
        if isinstance(x, (int, np.integer)):
            return 0 <= int(x) < self.n
        x = np.asarray(x)
        return x.shape == () and x.dtype.kind in "ui" and 0 <= int(x) < self.n


    def __repr__(self):
        return f"Discrete({self.n})"


class MultiDiscrete(_Space):
    """Gymnasium's MultiDiscrete: integers 0 .. nvec[i]-1 per element."""

    def __init__(self, nvec):
        self.nvec = np.asarray(nvec, dtype=np.int64)
        self.start = np.zeros_like(self.nvec)
        self.shape = self.nvec.shape
        self.dtype = np.dtype(np.int64)


    def sample(self):
        return self.np_random.integers(self.nvec).astype(self.dtype)

    def contains(self, x):
        x = np.asarray(x)
        return x.shape == self.shape and x.dtype.kind in "ui" and bool(np.all((x >= 0) & (x < self.nvec)))


    def __repr__(self):
        return f"MultiDiscrete({self.nvec})"


class Dict(_Space):
    """Gymnasium's Dict: named spaces, in a fixed order."""

    def __init__(self, spaces):
        self.spaces = OrderedDict(spaces)
        self.shape = None
        self.dtype = None

    def seed(self, seed=None):
        seeds = np.random.SeedSequence(seed).spawn(len(self.spaces))
        for space, s in zip(self.spaces.values(), seeds):
            space.seed(int(s.generate_state(1)[0]))
        return [seed]

    def sample(self):
        return OrderedDict((k, s.sample()) for k, s in self.spaces.items())

    def contains(self, x):
        return (isinstance(x, dict) and set(x) == set(self.spaces)
                and all(self.spaces[k].contains(v) for k, v in x.items()))


    def __getitem__(self, key):
        return self.spaces[key]

    def keys(self):
        return self.spaces.keys()

    def __repr__(self):
        return "Dict(" + ", ".join(f"{k}: {s}" for k, s in self.spaces.items()) + ")"


def from_description(d):
    """The space a description from the extension module describes."""
    kinds = _gym_spaces if _gym_spaces is not None else None
    if d["kind"] == "box":
        if kinds:
            return kinds.Box(d["low"], d["high"], d["shape"], np.dtype(d["dtype"]))
        return Box(d["low"], d["high"], d["shape"], d["dtype"])
    if d["kind"] == "discrete":
        return kinds.Discrete(d["n"]) if kinds else Discrete(d["n"])
    fields = [(name, from_description(f)) for name, f in d["fields"]]
    return kinds.Dict(OrderedDict(fields)) if kinds else Dict(fields)


def batched(space, n):
    """The space of n stacked values of `space` (Gymnasium's batch_space)."""
    if _gym_spaces is not None:
        from gymnasium.vector.utils import batch_space
        return batch_space(space, n)
    if isinstance(space, Box):
        b = Box(0, 0, (n,) + space.shape, space.dtype)
        b.low = np.broadcast_to(space.low, b.shape).copy()
        b.high = np.broadcast_to(space.high, b.shape).copy()
        return b
    if isinstance(space, Discrete):
        return MultiDiscrete(np.full(n, space.n))
    return Dict([(k, batched(s, n)) for k, s in space.spaces.items()])
