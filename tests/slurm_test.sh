#!/usr/bin/env bash
# A real Slurm cluster (scripts/slurm_local: one node, this machine) runs a
# two-task training job (srun: two ranks of chore train, DD-PPO over Gloo) and
# the table's runs as a job array (chore reproduce --launcher slurm), whose runs
# are those of --launcher local bit for bit; a cancelled array task resumes
# when the command runs again.
set -uo pipefail
chore="$1"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work="$(mktemp -d)"
export SLURM_LOCAL_PORT=$((16000 + RANDOM % 8000))
trap '"$root/scripts/slurm_local" stop "$work/cluster"; rm -rf "$work"' EXIT
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

eval "$("$root/scripts/slurm_local" start "$work/cluster")" || { echo "FAIL: the cluster did not start"; exit 1; }

# Two tasks of one job: srun's variables make them ranks 0 and 1.
run="$work/ddppo"
sbatch --wait --ntasks=2 --cpus-per-task=1 --output="$work/ddppo.log" \
  --wrap "srun '$chore' train --activity collect_trash --baseline rl-prim --mode symbolic --observations is_grasping --steps 600 --set ppo.epochs=3 --out '$run'" >/dev/null ||
  fail "the two-task job failed: $(tail -5 "$work/ddppo.log")"
grep -q "rank 1 of 2: 600 steps done" "$work/ddppo.log" || fail "no rank 1 in $(cat "$work/ddppo.log")"
grep -q "600 steps done; checkpoint" "$work/ddppo.log" || fail "no rank 0 in $(cat "$work/ddppo.log")"
[[ "$(tail -1 "$run/metrics.csv" | cut -d, -f1)" == 600 ]] || fail "$run/metrics.csv does not end at 600 steps"

# The table's runs as a job array, then here: the same runs, the same Q.
table=(--activities collect_trash --methods rl-prim --seeds 0-1 --steps 300 --mode symbolic --eval-episodes 2
  --generalisation-seeds 100-100 --no-videos --set ppo.epochs=3)
"$chore" reproduce "${table[@]}" --launcher slurm --out "$work/slurm" >"$work/slurm.log" 2>&1 ||
  fail "reproduce --launcher slurm: $(tail -5 "$work/slurm.log")"
grep -q "2 run(s) as a Slurm job array" "$work/slurm.log" || fail "reproduce did not submit an array: $(cat "$work/slurm.log")"
"$chore" reproduce "${table[@]}" --launcher local --jobs 2 --out "$work/local" >"$work/local.log" 2>&1 ||
  fail "reproduce --launcher local: $(tail -5 "$work/local.log")"
for seed in 0 1; do
  "$root/scripts/compare_runs" "$work/slurm/runs/symbolic/collect_trash/rl-prim_seed$seed" \
    "$work/local/runs/symbolic/collect_trash/rl-prim_seed$seed" >"$work/compare.log" 2>&1 ||
    fail "seed $seed: the array's run differs from the local one: $(cat "$work/compare.log")"
done
q() { python3 -c 'import json,sys; print(sorted((r["seed"], r["q_seed0"]) for r in json.load(open(sys.argv[1]))["runs"]))' "$1"; }
[[ "$(q "$work/slurm/baselines.json")" == "$(q "$work/local/baselines.json")" ]] || fail "the reports' Q differ"
# Again: every run done, nothing submitted.
"$chore" reproduce "${table[@]}" --launcher slurm --out "$work/slurm" >"$work/again.log" 2>&1 || fail "the second reproduce failed"
grep -q "Slurm job array" "$work/again.log" && fail "runs done were submitted again"

# An array task cancelled mid-run (its checkpoint at 600 of 3,000 steps): the
# command reports the run failed (exit 1); run again, it submits that run
# alone, which resumes from its checkpoint, and the table is whole.
long=(--activities collect_trash --methods rl-prim --seeds 0-1 --steps 3000 --mode symbolic --eval-episodes 2
  --generalisation-seeds 100-100 --no-videos --set ppo.epochs=3 --set checkpoint_every=600 --launcher slurm
  --out "$work/cancel")
"$chore" reproduce "${long[@]}" >"$work/cancel.log" 2>&1 &
submitter=$!
for _ in $(seq 240); do [[ -e "$work/cancel/runs/symbolic/collect_trash/rl-prim_seed0/checkpoint_600.pt" ]] && break; sleep 0.5; done
scancel "$(cut -d';' -f1 "$work/cancel/slurm/sbatch.out")_0"
wait "$submitter"
code=$?
[[ $code -eq 1 ]] || fail "reproduce beside a cancelled task exited $code (want 1): $(tail -3 "$work/cancel.log")"
grep -q "1/2 runs done" "$work/cancel.log" || fail "the cancelled run was reported done: $(tail -3 "$work/cancel.log")"
"$chore" reproduce "${long[@]}" >"$work/resumed.log" 2>&1 || fail "the resubmitted table failed: $(tail -3 "$work/resumed.log")"
grep -q "1 run(s) as a Slurm job array" "$work/resumed.log" || fail "not the cancelled run alone resubmitted"
grep -q "2/2 runs done" "$work/resumed.log" || fail "the table is not whole after resubmitting"

echo "slurm: $failures failure(s)"
[[ $failures -eq 0 ]]
