"""chore's PPO beside Stable-Baselines3's on the same cells (issue 53): per
activity and training seed, Q at evaluation seed 0 (100 episodes, sampled
and greedy), Q in training per 3,000-step window, the entropy at the end and
the wall-clock; the learning curves of both drawn together by `chore plot`.
Plain Python (no NumPy): it reads the two trainers' files.

    python3 peers/compare_sb3.py --chore results/protocol_study/paper/runs/symbolic \\
        --sb3 results/peer_sb3 --activities store_decoration collect_trash --seeds 0 1 2 \\
        --plot build/chore --out results/peer_sb3
"""

import argparse
import csv
import json
import os
import statistics
import subprocess

WINDOW = 3000


def rows(path):
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def windows(metrics, steps):
    """Mean of the rows' mean_q per 3,000-step window (as docs/baselines.md's tables)."""
    out = []
    for start in range(0, steps, WINDOW):
        q = [r["mean_q"] for r in metrics if start < r["env_steps"] <= start + WINDOW]
        out.append(statistics.mean(q) if q else float("nan"))
    return out


def chore_run(directory):
    metrics = rows(os.path.join(directory, "metrics.csv"))
    sampled = json.load(open(os.path.join(directory, "eval_seed0.json")))[0]
    greedy = json.load(open(os.path.join(directory, "eval_seed0_greedy.json")))[0]
    return {"metrics": metrics, "sampled": sampled["q"]["mean"], "greedy": greedy["q"]["mean"],
            "wall_s": metrics[-1]["wall_s"], "entropy": metrics[-1]["entropy"]}


def sb3_run(directory):
    metrics = rows(os.path.join(directory, "metrics.csv"))
    result = json.load(open(os.path.join(directory, "eval_seed0.json")))
    return {"metrics": metrics, "sampled": result["seed0"]["q"]["mean"], "greedy": result["seed0_greedy"]["q"]["mean"],
            "wall_s": result["train_wall_s"], "entropy": metrics[-1]["entropy"]}


def fmt(values):
    return " ".join(f"{v:.3f}" for v in values)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--chore", required=True, help="chore's runs: DIR/ACTIVITY/rl-prim_seedS")
    p.add_argument("--sb3", required=True, help="SB3's runs: DIR/ACTIVITY/seedS")
    p.add_argument("--activities", nargs="+", required=True)
    p.add_argument("--seeds", nargs="+", type=int, required=True)
    p.add_argument("--steps", type=int, default=30000)
    p.add_argument("--plot", help="the chore executable, to draw the curves")
    p.add_argument("--out", required=True)
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    md = ["# chore's PPO beside Stable-Baselines3's (issue 53)", "",
          "Written by `peers/compare_sb3.py`. RL-Prim. (symbolic primitives, the paper's protocol: "
          "docs/baselines.md), 30,000 steps; Q at evaluation seed 0 over episodes 0-99, sampled and greedy; "
          "training Q: the mean of metrics.csv's `mean_q` (last 20 episodes) per 3,000-step window.", ""]
    for activity in a.activities:
        md += [f"## {activity}", "", "| trainer | seed | Q sampled | Q greedy | training Q per window | entropy at the end "
               "| train wall-clock |", "|---|---|---|---|---|---|---|"]
        runs = {"chore": [], "SB3": []}
        for seed in a.seeds:
            runs["chore"].append(chore_run(os.path.join(a.chore, activity, f"rl-prim_seed{seed}")))
            runs["SB3"].append(sb3_run(os.path.join(a.sb3, activity, f"seed{seed}")))
        for trainer, done in runs.items():
            for seed, r in zip(a.seeds, done):
                md.append(f"| {trainer} | {seed} | {r['sampled']:.3f} | {r['greedy']:.3f} | "
                          f"{fmt(windows(r['metrics'], a.steps))} | {r['entropy']:.2f} | {r['wall_s'] / 60:.1f} min |")
        md += ["", "| trainer | mean Q sampled (std) | mean Q greedy (std) | mean training Q, last window |",
               "|---|---|---|---|"]
        for trainer, done in runs.items():
            s = [r["sampled"] for r in done]
            g = [r["greedy"] for r in done]
            last = [windows(r["metrics"], a.steps)[-1] for r in done]
            md.append(f"| {trainer} | {statistics.mean(s):.3f} ({statistics.pstdev(s):.3f}) | "
                      f"{statistics.mean(g):.3f} ({statistics.pstdev(g):.3f}) | {statistics.mean(last):.3f} |")
        if a.plot:
            for column in ("mean_q", "entropy"):
                png = os.path.join(a.out, f"{activity}_{column}.png")
                files = [f"chore PPO={os.path.join(a.chore, activity, f'rl-prim_seed{s}', 'metrics.csv')}" for s in a.seeds]
                files += [f"SB3 PPO={os.path.join(a.sb3, activity, f'seed{s}', 'metrics.csv')}" for s in a.seeds]
                subprocess.run([a.plot, "plot", "--out", png, "--y", column, "--title",
                                f"{activity}: {column} while training, chore's PPO and SB3's (mean +- std over seeds)"]
                               + files, check=True, stdout=subprocess.DEVNULL)
                md += ["", f"![{activity} {column}]({os.path.basename(png)})"]
        md.append("")
    with open(os.path.join(a.out, "report.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print(os.path.join(a.out, "report.md"))


if __name__ == "__main__":
    main()
