"""chore's interval estimates against rliable's own (issue 55), on committed runs.

For each report given (a `chore reproduce` baselines.json, with its profiles/
CSVs beside it), from the runs it lists:
- the IQM and the mean of each cell's Q (at evaluation seed 0 and over the
  generalisation seeds) equal rliable's metrics.aggregate_iqm and
  aggregate_mean, and their 95% stratified bootstrap intervals lie within
  rliable's Monte Carlo error: rliable's StratifiedBootstrap (the bootstrap its
  get_interval_estimates runs, with arch's percentile method) is drawn `reps`
  times, and chore's endpoint must fall between the draws' order statistics
  6 standard deviations either side of the percentile's rank;
- the probability of improvement of each ordering equals rliable's
  metrics.probability_of_improvement, its interval likewise within rliable's
  Monte Carlo error (StratifiedIndependentBootstrap);
- each performance profile (profiles/ACTIVITY_METHOD.csv) equals rliable's
  score distribution (create_performance_profile's point estimates), to the
  6 significant digits the CSV holds.
"""

import argparse
import csv
import json
import math
import pathlib
import sys

import numpy as np
from rliable import library as rly
from rliable import metrics

Z = 6  # standard deviations of the order-statistic rank the endpoints may move


def iqm(scores):
    return np.array([metrics.aggregate_iqm(scores)])


def mean(scores):
    return np.array([metrics.aggregate_mean(scores)])


def improvement(x, y):
    return np.array([metrics.probability_of_improvement(x, y)])


def band(draws, percent):
    """The values between which a percentile of `draws`' distribution falls, at Z sigma."""
    draws = np.sort(draws)
    r, p = len(draws), percent / 100
    spread = Z * math.sqrt(r * p * (1 - p))
    return draws[max(0, math.floor(r * p - spread))], draws[min(r - 1, math.ceil(r * p + spread))]


def check_interval(what, chore_interval, point, draws, failures):
    """chore's {point, lo, hi} against rliable's point and bootstrap draws."""
    if not math.isclose(chore_interval["point"], point, rel_tol=0, abs_tol=1e-12):
        failures.append(f"{what}: point {chore_interval['point']} where rliable has {point}")
    lo, hi = np.percentile(draws, [2.5, 97.5])  # arch's 'percentile' method, as get_interval_estimates
    for key, percent, theirs in (("lo", 2.5, lo), ("hi", 97.5, hi)):
        low, high = band(draws, percent)
        if not low - 1e-12 <= chore_interval[key] <= high + 1e-12:
            failures.append(f"{what}: {key} {chore_interval[key]:.6f} outside rliable's Monte Carlo band "
                            f"[{low:.6f}, {high:.6f}] (rliable's estimate {theirs:.6f})")


def check_report(path, reps, pair_reps, failures):
    report = json.loads(path.read_text())
    cells = {}
    for run in report["runs"]:
        cells.setdefault((run["activity"], run["method"]), []).append(run)
    checked = 0
    for row in report["rows"]:
        runs = cells.get((row["activity"], row["method"]), [])
        for key in ("q_seed0", "q_generalisation"):
            if not runs:
                continue
            scores = np.array([[r[key]] for r in runs])  # runs x one task
            for name, statistic in (("iqm", iqm), ("mean", mean)):
                what = f"{path}: {row['activity']} {row['method']} {key} {name}"
                np.random.seed(checked)  # rliable's bootstraps draw from numpy's global generator
                # Runs that all score alike resample to themselves: no draws needed.
                draws = (np.full(reps, statistic(scores)[0]) if np.all(scores == scores[0])
                         else rly.StratifiedBootstrap(scores).apply(statistic, reps)[:, 0])
                check_interval(what, row[key + "_intervals"][name], statistic(scores)[0], draws, failures)
                checked += 1
    for ordering in report["orderings"]:
        x = np.array([[r["q_seed0"]] for r in cells[(ordering["activity"], ordering["better"])]])
        y = np.array([[r["q_seed0"]] for r in cells[(ordering["activity"], ordering["worse"])]])
        what = f"{path}: {ordering['activity']} P({ordering['better']} > {ordering['worse']})"
        np.random.seed(checked)
        draws = (np.full(pair_reps, 0.5) if np.all(x == x[0]) and np.all(y == x[0])
                 else rly.StratifiedIndependentBootstrap(x, y).apply(improvement, pair_reps)[:, 0])
        check_interval(what, ordering["probability_of_improvement"], improvement(x, y)[0], draws, failures)
        checked += 1
    for (activity, method), runs in cells.items():
        profile = path.parent / "profiles" / f"{activity}_{method}.csv"
        rows = list(csv.DictReader(profile.open()))
        taus = np.array([float(r["Q"]) for r in rows])
        theirs, _ = rly.create_performance_profile({"m": np.array([[r["q_seed0"]] for r in runs])}, taus, reps=1)
        ours = np.array([float(r["fraction_of_runs"]) for r in rows])
        # The CSV holds 6 significant digits (2/3 is 0.666667): rliable's value written so must match.
        written = np.array([float(f"{v:.6g}") for v in theirs["m"]])
        agree = np.isclose(ours, theirs["m"], rtol=0, atol=1e-12) | (ours == written)
        if not agree.all():
            first = int(np.argmax(~agree))
            failures.append(f"{profile}: at Q {taus[first]} chore has {ours[first]}, rliable {theirs['m'][first]}")
        checked += 1
    return checked


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reports", nargs="+", type=pathlib.Path, help="baselines.json files")
    parser.add_argument("--reps", type=int, default=50000, help="rliable's bootstrap draws (its default: 50000)")
    parser.add_argument("--pair-reps", type=int, default=5000,
                        help="draws for the probability of improvement (scipy's Mann-Whitney per draw is slow)")
    args = parser.parse_args()
    failures = []
    checked = sum(check_report(path, args.reps, args.pair_reps, failures) for path in args.reports)
    for failure in failures:
        print("differs:", failure)
    print(f"rliable: {checked} estimates of {len(args.reports)} report(s) checked, {len(failures)} differ")
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
