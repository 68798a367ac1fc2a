"""chore eval from Python: a policy over seeds, the same report as
`chore eval --json` (policies/evaluate.hpp: episode j of seed s is the env
reset with seed s * 1000000 + j; success, Q and length as mean and std over
seeds). LibTorch loads with the first call, not with `import chore`."""

import json

from ._chore import Error


def _policies():
    from . import _chore_policies
    return _chore_policies


def load_policy(path, sample=False):
    """A checkpoint written by `chore train`, as a policy: call it with a
    batch of observations (arrays with a leading batch dimension, as a
    VectorEnv returns them) for a batch of actions; greedy, or with sample=True
    drawn as in training (seeded by info["episode_seed"]). Its .env says the
    env it was trained in (make(**...) rebuilds it)."""
    return _policies().CheckpointPolicy(str(path), bool(sample))


def _seed_range(seeds):
    if isinstance(seeds, str):
        first, sep, last = seeds.partition("-")
        if not sep or not first.isdigit() or not last.isdigit():
            raise Error(f"seeds {seeds!r}: expected A-B")
        return int(first), int(last)
    if isinstance(seeds, range):
        if seeds.step != 1 or len(seeds) == 0:
            raise Error(f"seeds {seeds!r}: expected a non-empty range of step 1")
        return seeds.start, seeds.stop - 1
    if isinstance(seeds, int):
        return seeds, seeds
    first, last = seeds
    return int(first), int(last)


def evaluate(policy, activity=None, *, seeds=(0, 0), episodes=10, threads=1, action_space="primitives", mode=None,
             observations=None, max_steps=None, verbose=False):
    """Evaluates `policy` on `activity` over seeds (A-B, a range, (A, B) or
    one seed), `episodes` per seed, on a vector env of `threads` envs; returns
    the report chore eval --json prints (a dict). The policy is "expert" (the
    scripted expert where it knows the goal, the paper's three activities;
    the task planner's expert on any other activity), a checkpoint from load_policy (in the env it was trained
    in; activity, mode and max_steps override it), or a callable
    policy(obs, info) -> actions for a batch of rows (obs and info as a
    VectorEnv returns them; optional policy.reset(env_ids) when envs start new
    episodes). verbose: chore's per-seed progress lines on stderr."""
    first, last = _seed_range(seeds)
    if first < 0 or last < first:
        raise Error(f"seeds {first}-{last}: expected 0 <= A <= B")
    p = _policies()
    common = (first, last, int(episodes), int(threads), bool(verbose))
    if isinstance(policy, str):
        if policy != "expert":
            raise Error(f"policy {policy!r}: expected 'expert', a checkpoint policy or a callable")
        if activity is None:
            raise Error("evaluate: the expert needs an activity")
        report = p.evaluate_expert(str(activity), mode or "physical", int(max_steps or 60), *common)
    elif isinstance(policy, p.CheckpointPolicy):
        report = p.evaluate_checkpoint(policy, str(activity or ""), mode or "", int(max_steps or 0), *common)
    elif callable(policy):
        if activity is None:
            raise Error("evaluate: a callable policy needs an activity")
        primitives = action_space == "primitives"
        config = {"activity": str(activity), "action_space": action_space, "mode": mode or "physical",
                  "max_episode_steps": int(max_steps or (60 if primitives else 500))}
        if observations is not None:
            config["observations"] = list(observations)
        elif primitives:
            config["observations"] = ["rgb", "depth", "proprio", "is_grasping", "action_mask"]
        report = p.evaluate_callable(policy, config, *common)
    else:
        raise Error(f"policy {policy!r}: expected 'expert', a checkpoint policy or a callable")
    return json.loads(report)


def format_evaluation(report):
    """The human-readable report chore eval prints."""
    return _policies().format_evaluation(json.dumps(report))
