"""chore's BDDL against BEHAVIOR's own bddl package (issue 55), file for file.

Run by ctest with the interpreter of a venv that holds one bddl release:
bddl 3.6.0 (OmniGibson's, build/test-venv) judges the omnigibson dialect of
BEHAVIOR-1K's files, bddl 1.0.1 (iGibson 2.0's, build/bddl1-venv) the igibson
dialect of BEHAVIOR-100's. The files: the package's own activity definitions
(bddl 3.6.0 ships 1016 BEHAVIOR-1K activities, 816 of them the corpus's) and
the directories given, each file of the release's dialect once.

For each file:
- it parses and grounds in both, or fails in both;
- the goal's ground options are the same literals in the same order (bddl's
  get_ground_state_options against chore.Goal.options);
- on sampled truth values of the goal's atoms, success, which top-level
  conditions hold, and Q (the best fraction of an option's literals satisfied,
  bddl's get_reward) agree. The states: nothing true, the closed-world reading
  of :init (the literals chore's instances are sampled to hold), each of the
  first five options made true, and perturbations of these (each atom flipped
  with probability 1/4), from a generator seeded by the activity's name.

bddl is driven through its parser and condition_evaluation module with a
backend whose predicates look the atoms up (its TrivialBackend mislabels
several predicates); the predicates and arities are chore's domains', as
iGibson's and OmniGibson's backends define more than bddl's domain files list.

Every disagreement must be one of EXPLAINED (docs/activities.md says why); one
that is not, or an explained one that no longer occurs, fails the run.
"""

import argparse
import contextlib
import hashlib
import importlib.metadata
import io
import pathlib
import random
import re
import sys

import bddl
import bddl.config
from bddl.backend_abc import BDDLBackend
from bddl.condition_evaluation import compile_state, create_scope, evaluate_state, get_ground_state_options
from bddl.logic_base import BinaryAtomicFormula, UnaryAtomicFormula
from bddl.parsing import parse_problem, scan_tokens

import chore

ROOT = pathlib.Path(__file__).resolve().parent.parent

# activity name -> (what differs, why); docs/activities.md has the same list.
EXPLAINED = {
    "omnigibson": {
        # bddl 3 keeps the first 20 tuples of the goal's product, all of which
        # hold some c and (not c) here, and asserts; chore goes on to the first
        # consistent ones.
        "make_a_bake_sale_stand_stall": "bddl finds no consistent option",
        "make_a_small_vegetable_garden": "bddl finds no consistent option",
        "picking_fruit_and_vegetables": "bddl finds no consistent option",
        "set_up_a_buffet": "bddl finds no consistent option",
        # Its :goal holds two formulas; bddl reads the first, chore both.
        "loading_the_car": "bddl drops (not (open car)), the second formula of :goal",
    },
    "igibson": {},
}


class Atoms:
    """The atoms that hold, as (predicate, object, ...) tuples."""

    true = frozenset()


class Instance:
    def __init__(self, name):
        self.name = name


def _unary(self, obj):
    return (self.STATE_NAME, obj.name) in Atoms.true


def _binary(self, obj1, obj2):
    return (self.STATE_NAME, obj1.name, obj2.name) in Atoms.true


def _no_sampling(self, *args, **kwargs):
    raise AssertionError("the reference check never samples")


class AtomBackend(BDDLBackend):
    def __init__(self, domain_file):
        tokens = scan_tokens(filename=str(domain_file))
        predicates = next(group[1:] for group in tokens if isinstance(group, list) and group[0] == ":predicates")
        self.classes = {}
        for name, *arguments in predicates:
            arity = sum(a.startswith("?") for a in arguments)
            base, evaluate = (UnaryAtomicFormula, _unary) if arity == 1 else (BinaryAtomicFormula, _binary)
            self.classes[name] = type(name, (base,), {"STATE_NAME": name, "_evaluate": evaluate,
                                                     "_sample": _no_sampling})

    def get_predicate_class(self, name):
        return self.classes[name]


def literal(parsed):
    """bddl's ['not', ['ontop', 'a', 'b']] as chore.Goal's ('not', ('ontop', 'a', 'b'))."""
    return ("not", tuple(parsed[1])) if parsed[0] == "not" else tuple(parsed)


def bddl_goal(text, dialect, backend):
    """The compiled goal, its ground options and the :init literals, as bddl makes them."""
    _, objects, init, goal = parse_problem("reference", 0, dialect, predefined_problem=text)
    scope = create_scope(objects)
    for name in scope:
        scope[name] = Instance(name)
    compiled = compile_state(goal, backend, scope=scope, object_map=objects)
    options = get_ground_state_options(compiled, backend, scope=scope, object_map=objects)
    if not options:
        raise AssertionError("no ground option")  # bddl.activity.get_ground_goal_state_options asserts
    return compiled, options, init


def sampled_states(name, goal, init):
    atoms = sorted({lit[1] if lit[0] == "not" else lit for lit in goal.literals})
    initial = {tuple(l) for l in init if l[0] not in ("not", "inroom")}
    states = [set(), initial]
    for option in goal.options[:5]:
        states.append({goal.literals[i] for i in option if goal.literals[i][0] != "not"})
    rng = random.Random(name)
    for _ in range(8):
        base = rng.choice(states)
        states.append({a for a in atoms if (a in base) != (rng.random() < 0.25)} | (base - set(atoms)))
    return states


def compare(path, dialect, backend):
    """A list of what differs between chore and bddl on this file (empty: they agree)."""
    text = path.read_text()
    try:
        goal = chore.Goal(str(path))
        chore_error = None
    except chore.Error as e:
        chore_error = str(e)
    try:
        with contextlib.redirect_stdout(io.StringIO()):  # bddl prints what it skips
            compiled, options, init = bddl_goal(text, dialect, backend)
        bddl_error = None
    except Exception as e:  # bddl's failures are assertions, KeyErrors and its own exceptions
        bddl_error = f"{type(e).__name__}: {e}"
    if chore_error or bddl_error:
        if chore_error and bddl_error:
            return []
        return [f"chore {'fails: ' + chore_error if chore_error else 'parses'}, "
                f"bddl {'fails: ' + bddl_error if bddl_error else 'parses'}"]
    differences = []
    reference_options = [[literal(head.body) for head in option] for option in options]
    chore_options = [[goal.literals[i] for i in option] for option in goal.options]
    if reference_options != chore_options:
        first = next((i for i, (a, b) in enumerate(zip(reference_options, chore_options)) if a != b),
                     min(len(reference_options), len(chore_options)))
        differences.append(f"ground options: bddl {len(reference_options)}, chore {len(chore_options)}, "
                           f"first different at {first}")
    for state in sampled_states(path.parent.name if path.name.startswith("problem") else path.stem, goal, init):
        Atoms.true = frozenset(state)
        success, holding = evaluate_state(compiled)
        q = max(sum(bool(head.evaluate()) for head in option) / len(option) for option in options)
        score = goal.score(state)
        conditions = [i for i, holds in enumerate(score["condition_holds"]) if holds]
        if (success, holding["satisfied"], q) != (score["success"], conditions, score["q"]):
            differences.append(f"on {len(state)} true atoms: bddl success {success}, conditions "
                               f"{holding['satisfied']}, Q {q:.4f}; chore {score['success']}, {conditions}, "
                               f"{score['q']:.4f}")
            break
    return differences


def corpus(dialect, directories):
    """Each file of the dialect once (by content), from the package's definitions and the directories."""
    roots = [pathlib.Path(bddl.config.ACTIVITY_CONFIGS_PATH)] + [pathlib.Path(d) for d in directories]
    seen, files = set(), []
    for root in roots:
        for path in sorted(root.rglob("*.bddl")):
            text = path.read_text()
            match = re.search(r"\(:domain\s+([\w-]+)\)", text)
            if not match or match.group(1) != dialect:
                continue
            digest = hashlib.sha256(text.encode()).hexdigest()
            if digest not in seen:
                seen.add(digest)
                files.append(path)
    return files


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("directories", nargs="*", help="more activity files (their release's dialect is checked)")
    parser.add_argument("--expect-files", type=int, required=True, help="at least this many files")
    args = parser.parse_args()
    version = importlib.metadata.version("bddl")
    dialect = {"1": "igibson", "3": "omnigibson"}[version.split(".")[0]]
    backend = AtomBackend(ROOT / "tasks" / "domains" / f"{dialect}.bddl")
    files = corpus(dialect, args.directories)
    explained = EXPLAINED[dialect]
    unexplained, seen_explained = [], set()
    for path in files:
        name = path.parent.name if path.name.startswith("problem") else path.stem
        differences = compare(path, dialect, backend)
        if differences and name in explained:
            seen_explained.add(name)
            print(f"explained: {name}: {explained[name]}; {differences[0]}")
        elif differences:
            unexplained += [f"{path}: {d}" for d in differences]
    stale = sorted(set(explained) - seen_explained)
    print(f"bddl {version} ({dialect}): {len(files)} files, {len(files) - len(seen_explained) - len(unexplained)} "
          f"agree, {len(seen_explained)} differ as explained, {len(unexplained)} unexplained")
    for line in unexplained:
        print("unexplained:", line)
    for name in stale:
        print(f"stale: {name} is in EXPLAINED but agrees (or is not in the corpus)")
    if len(files) < args.expect_files:
        print(f"only {len(files)} files of the {dialect} dialect; expected at least {args.expect_files}")
        return 1
    return 1 if unexplained or stale else 0


if __name__ == "__main__":
    sys.exit(main())
