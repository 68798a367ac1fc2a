#!/usr/bin/env bash
# The CLI's exit codes and messages: 0 on success, 2 with a message naming the
# problem for bad arguments and bad input.
set -uo pipefail
chore="$1"
data="$(cd "$(dirname "${BASH_SOURCE[0]}")/data" && pwd)"
failures=0
checks=0

expect() {  # expect CODE PATTERN -- command...
  local code="$1" pattern="$2"
  checks=$((checks + 1))
  shift 3
  local out
  out="$("$@" 2>&1)"
  local got=$?
  if [[ $got -ne $code ]] || ! grep -q -- "$pattern" <<<"$out"; then
    echo "FAIL: $* -> exit $got (want $code), output lacks '$pattern':"
    echo "$out" | tail -5
    failures=$((failures + 1))
  else
    echo "ok: $*"
  fi
}

expect 2 "subcommand" -- "$chore"
expect 2 "no_such_command" -- "$chore" no_such_command
expect 2 "steps" -- "$chore" bench --steps 0
expect 2 "unknown scene 'no_such_scene'" -- "$chore" bench --scenes no_such_scene --steps 1 --repeats 1
expect 2 "CHORE_EGL='bogus'" -- env CHORE_EGL=bogus "$chore" bench --scenes "$data/scenes/box_room.json" --steps 1 --repeats 1
# Asking for a GPU EGL device where there is none is an error, not a crash.
if ! ls /dev/dri/renderD* /dev/nvidia0 >/dev/null 2>&1; then
  expect 2 "no GPU EGL device" -- env CHORE_EGL=device "$chore" bench --scenes "$data/scenes/box_room.json" --steps 1 --repeats 1
else
  expect 0 "Full Feature Set" -- env CHORE_EGL=device "$chore" bench --scenes "$data/scenes/box_room.json" --steps 1 --repeats 1 --envs 2
fi
expect 0 '"vector_env"' -- "$chore" bench --scenes "$data/scenes/box_room.json" --steps 4 --repeats 1 --envs 2 --json
expect 0 "Full Feature Set" -- "$chore" bench --scenes "$data/scenes/box_room.json" --steps 4 --repeats 1 --envs 2
expect 2 "sections" -- "$chore" bench --sections nope
expect 0 "flow" -- "$chore" bench --scenes "$data/scenes/box_room.json" --sections modalities --steps 2 --repeats 1
expect 0 "per extra env" -- "$chore" bench --scenes "$data/scenes/box_room.json" --sections memory --envs 2

# Every observation modality of one frame, as a picture.
expect 2 "size" -- "$chore" observe --size 8 --out /tmp/chore_cli_observe.png
expect 2 "unknown scene 'nope'" -- "$chore" observe --scene nope --out /tmp/chore_cli_observe.png
observe_png="$(mktemp -d)/observe.png"
expect 0 "observe: $observe_png (box_room)" -- "$chore" observe --scene "$data/scenes/box_room.json" --size 64 --out "$observe_png"
if [[ ! -s "$observe_png" ]]; then echo "FAIL: $observe_png was not written"; failures=$((failures + 1)); fi

# Activities: valid files are checked, a malformed one is located.
tasks="$(cd "$(dirname "${BASH_SOURCE[0]}")/../tasks/activities" && pwd)"
expect 0 "store_decoration_0 (igibson): 5 objects" -- "$chore" activity check "$tasks/store_decoration.bddl" "$tasks/collect_trash.bddl" "$tasks/clean_table.bddl"
expect 2 "error_unbalanced.bddl:3:1: expected ')'" -- "$chore" activity check "$data/bddl/error_unbalanced.bddl"
expect 2 "1 of 2 files failed" -- "$chore" activity check "$data/bddl/error_unbalanced.bddl" "$tasks/clean_table.bddl"
expect 0 "3 activities; parsed and grounded 3 (100.0%), instantiated 3 (100.0%)" -- "$chore" activity coverage "$tasks" --threads 2
# Each activity is covered in a process of its own: one whose process dies (killed here, as a crash
# inside MuJoCo would end it) is reported with its signal, and the others are covered.
cover_dir="$(mktemp -d)"
cp "$tasks/clean_table.bddl" "$tasks/collect_trash.bddl" "$cover_dir/"
"$chore" activity coverage "$cover_dir" --json > "$cover_dir/out.json" 2> "$cover_dir/err.txt" &
coverage_pid=$!
child=""
for _ in $(seq 400); do child="$(pgrep -P "$coverage_pid" | head -1)"; [[ -n "$child" ]] && break; sleep 0.05; done
[[ -n "$child" ]] && kill -9 "$child"
wait "$coverage_pid"
coverage_code=$?
checks=$((checks + 1))
if [[ $coverage_code -eq 0 ]] && grep -q '"stage": "crashed"' "$cover_dir/out.json" &&
  grep -q 'the process died of signal 9' "$cover_dir/out.json" && grep -q '"instantiated": 1,' "$cover_dir/out.json"; then
  echo "ok: activity coverage with a child killed"
else
  echo "FAIL: activity coverage with a child killed -> exit $coverage_code"; tail -5 "$cover_dir/err.txt"
  grep -E '"stage"|"instantiated"|"error"' "$cover_dir/out.json"
  failures=$((failures + 1))
fi
expect 2 "unknown activity 'nope'" -- "$chore" activity sample nope --out /tmp/chore_cli_nope.png
out_png="$(mktemp -d)/sample.png"
expect 0 "picture: $out_png" -- "$chore" activity sample store_decoration --seed 1 --out "$out_png"
if [[ ! -s "$out_png" ]]; then echo "FAIL: $out_png was not written"; failures=$((failures + 1)); fi

# activity solve: bad seeds exit 2; the steak cooked from seed 0's instance.
expect 2 "--seeds '3-1': B is below A" -- "$chore" activity solve "$data/bddl/behavior-1k/cook_a_steak.bddl" --seeds 3-1
expect 2 "at most 1000 seeds" -- "$chore" activity solve "$data/bddl/behavior-1k/cook_a_steak.bddl" --seeds 0-5000
expect 0 "cook_a_steak: solved, 6 primitives" -- "$chore" activity solve "$data/bddl/behavior-1k/cook_a_steak.bddl" --seeds 0

# The scripted expert: bad options exit 2; two symbolic episodes run and report.
expect 2 "mode" -- "$chore" expert --activity store_decoration --mode teleport
expect 2 "episodes" -- "$chore" expert --activity store_decoration --episodes 0
expect 2 "unknown activity 'nope'" -- "$chore" expert --activity nope --episodes 1
expect 0 '"success_rate"' -- "$chore" expert --activity store_decoration --episodes 2 --seed 1 --mode symbolic --json
expect 0 "success rate" -- "$chore" expert --activity store_decoration --episodes 1 --seed 1 --mode symbolic

# Evaluation: bad arguments exit 2 naming the problem; the expert evaluates.
expect 2 "give the policy" -- "$chore" eval --activity store_decoration
expect 2 "excludes" -- "$chore" eval --expert --policy-plugin x.so --activity store_decoration
expect 2 "activity is required" -- "$chore" eval --expert
expect 2 "--seeds '3-1': B is below A" -- "$chore" eval --expert --activity store_decoration --seeds 3-1
expect 2 "--seeds 'x': expected a seed or a range A-B" -- "$chore" eval --expert --activity store_decoration --seeds x
expect 2 "episodes" -- "$chore" eval --expert --activity store_decoration --episodes 0
expect 2 "policy-options requires --policy-plugin" -- "$chore" eval --expert --activity store_decoration --policy-options a
expect 2 "policy plugin 'no_such.so': no such file" -- "$chore" eval --policy-plugin no_such.so --activity store_decoration
expect 2 "unknown activity 'nope'" -- "$chore" eval --expert --activity nope
expect 2 "unknown observation 'sonar'" -- "$chore" eval --policy-plugin "$chore" --observations sonar --activity store_decoration
expect 2 "cannot load it" -- "$chore" eval --policy-plugin "$data/bddl/error_unbalanced.bddl" --activity store_decoration
expect 0 "success rate .* +- " -- "$chore" eval --expert --activity store_decoration --mode symbolic --seeds 0-1 --episodes 1
expect 0 '"env_seed": 1000000' -- "$chore" eval --expert --activity store_decoration --mode symbolic --seeds 1 --episodes 1 --json

# Video: bad arguments exit 2; a short symbolic expert episode is written.
expect 2 "--out is required" -- "$chore" video --expert --activity store_decoration
expect 2 "give the policy" -- "$chore" video --activity store_decoration --out /tmp/chore_cli_video.mp4
expect 2 "size" -- "$chore" video --expert --activity store_decoration --size 0 --out /tmp/chore_cli_video.mp4
video_out="$(mktemp -d)/expert.mp4"
expect 0 "11 frames of 512x300" -- "$chore" video --expert --activity store_decoration --mode symbolic --seed 1 --out "$video_out"

# Plot: bad arguments and files exit 2; a constructed run is drawn.
plot_dir="$(mktemp -d)"
mkdir -p "$plot_dir/ppo_seed0"
printf 'env_steps,wall_s,episodes,success_rate,mean_q,mean_return,mean_length\n0,0,0,0,0,0,0\n100,1,4,0.5,0.6,0.5,9\n' > "$plot_dir/ppo_seed0/metrics.csv"
expect 2 "--out is required" -- "$chore" plot "$plot_dir/ppo_seed0/metrics.csv"
expect 2 "$plot_dir/none.csv: no such file; expected a metrics.csv" -- "$chore" plot --out "$plot_dir/c.png" "$plot_dir/none.csv"
expect 2 "has no column 'kl'" -- "$chore" plot --out "$plot_dir/c.png" --y kl "$plot_dir/ppo_seed0/metrics.csv"
expect 0 "ppo (1 run)" -- "$chore" plot --out "$plot_dir/c.png" "$plot_dir/ppo_seed0/metrics.csv"
if [[ ! -s "$plot_dir/c.png" ]]; then echo "FAIL: $plot_dir/c.png was not written"; failures=$((failures + 1)); fi

# chore train: bad arguments exit 2 naming the problem; a short symbolic run
# writes metrics and checkpoints; a folder holding a run is not overwritten.
run_dir="$(mktemp -d)/run"
expect 2 "baseline" -- "$chore" train --activity collect_trash --baseline rl-magic --out "$run_dir"
expect 2 "--activity is required" -- "$chore" train --baseline rl-prim --out "$run_dir"
expect 2 "give --out DIR" -- "$chore" train --activity collect_trash --baseline rl-prim
expect 2 "steps" -- "$chore" train --activity collect_trash --baseline rl-prim --steps 0 --out "$run_dir"
expect 2 "envs" -- "$chore" train --activity collect_trash --baseline rl-prim --envs 0 --out "$run_dir"
expect 2 "mode" -- "$chore" train --activity collect_trash --baseline rl-prim --mode teleport --out "$run_dir"
expect 2 "unknown activity 'nope'" -- "$chore" train --activity nope --baseline rl-prim --out "$run_dir"
expect 2 "unknown observation 'smell'" -- "$chore" train --activity collect_trash --baseline rl-prim --observations smell --out "$run_dir"
expect 2 "--history is for rl-prim-hist" -- "$chore" train --activity collect_trash --baseline rl-prim --history 2 --out "$run_dir"
expect 2 "no checkpoint.pt there" -- "$chore" train --resume "$run_dir"
expect 2 "--set ppo.nope: no such setting" -- "$chore" train --activity collect_trash --baseline rl-prim --set ppo.nope=1 --out "$run_dir"
expect 2 "--set ppo.epochs: 'many' is not a number" -- "$chore" train --activity collect_trash --baseline rl-prim --set ppo.epochs=many --out "$run_dir"
if [[ -e "$run_dir/config.json" ]]; then echo "FAIL: a refused train wrote $run_dir/config.json"; failures=$((failures + 1)); fi
expect 0 "300 steps done" -- "$chore" train --activity collect_trash --baseline rl-prim --mode symbolic --observations is_grasping --steps 300 --set ppo.epochs=3 --out "$run_dir"
if ! grep -q '"epochs": 3' "$run_dir/config.json"; then echo "FAIL: $run_dir/config.json lacks --set's epochs"; failures=$((failures + 1)); fi
expect 2 "--set changes a new run" -- "$chore" train --resume "$run_dir" --set ppo.epochs=4
if [[ "$(head -1 "$run_dir/metrics.csv" | cut -d, -f1-7)" != "env_steps,wall_s,episodes,success_rate,mean_q,mean_return,mean_length" ]]; then
  echo "FAIL: $run_dir/metrics.csv header"; failures=$((failures + 1))
fi
expect 2 "already holds a run" -- "$chore" train --activity collect_trash --baseline rl-prim --out "$run_dir"
expect 2 "holds a rl-prim run on collect_trash" -- "$chore" train --resume "$run_dir" --baseline rl-vmc
# The trained checkpoint evaluates in the env it was trained in; a bad one is an error.
expect 0 "success rate .* +- " -- "$chore" eval --checkpoint "$run_dir/checkpoint.pt" --seeds 0-1 --episodes 1 --max-steps 5
# A frame per step plus the first; the greedy policy may end early (policy failure).
expect 0 "2 frames of.*; 1 steps\|3 frames of.*; 2 steps\|4 frames of.*; 3 steps\|5 frames of.*; 4 steps\|6 frames of.*; 5 steps" -- "$chore" video --checkpoint "$run_dir/checkpoint.pt" --seed 0 --max-steps 5 --out "$(mktemp -d)/policy.mp4"
printf 'garbage' > "$run_dir/checkpoint.pt"
expect 2 "not a chore checkpoint" -- "$chore" train --resume "$run_dir"
expect 2 "not a chore checkpoint" -- "$chore" eval --checkpoint "$run_dir/checkpoint.pt"
expect 2 "excludes" -- "$chore" eval --checkpoint "$run_dir/checkpoint.pt" --expert
expect 2 "sample requires --checkpoint" -- "$chore" eval --expert --activity store_decoration --sample

# chore train as two ranks of a data-parallel run (torchrun's variables,
# Gloo over loopback): rank 0 writes the run, rank 1 trains beside it and
# writes nothing; both resume from rank 0's checkpoint. A bad rank variable
# is exit 2 naming it.
ranks_dir="$(mktemp -d)/run"
port=$((20000 + RANDOM % 20000))
ranked() {  # ranked RANK PORT train-arguments...
  local r="$1" p="$2"
  shift 2
  env WORLD_SIZE=2 RANK="$r" MASTER_ADDR=127.0.0.1 MASTER_PORT="$p" "$chore" train "$@"
}
ranked 1 "$port" --activity collect_trash --baseline rl-prim --mode symbolic --observations is_grasping --steps 600 --set ppo.epochs=3 --out "$ranks_dir" > "$ranks_dir.rank1" 2>&1 &
expect 0 "600 steps done; checkpoint" -- ranked 0 "$port" --activity collect_trash --baseline rl-prim --mode symbolic --observations is_grasping --steps 600 --set ppo.epochs=3 --out "$ranks_dir"
wait
expect 0 "rank 1 of 2: 600 steps done (rank 0 writes the run)" -- cat "$ranks_dir.rank1"
expect 0 "^600," -- tail -1 "$ranks_dir/metrics.csv"
ranked 1 $((port + 1)) --resume "$ranks_dir" --steps 1200 > "$ranks_dir.rank1" 2>&1 &
expect 0 "1200 steps done; checkpoint" -- ranked 0 $((port + 1)) --resume "$ranks_dir" --steps 1200
wait
expect 0 "rank 1 of 2: 1200 steps done" -- cat "$ranks_dir.rank1"
expect 2 "distributed: RANK='2' is not a whole number in \[0, 1\]" -- ranked 2 "$port" --resume "$ranks_dir" --steps 1800
# A rank killed mid-run: the other stops with an error naming it (exit 2, at
# its next all-reduce), and both resume from rank 0's last checkpoint.
killed_dir="$(mktemp -d)/run"
train_killed=(--activity collect_trash --baseline rl-prim --mode symbolic --steps 6000 --checkpoint-every 600
  --set ppo.epochs=3 --out "$killed_dir")  # RGB: ~10 s a checkpoint, killed long before the end
env WORLD_SIZE=2 RANK=1 MASTER_ADDR=127.0.0.1 MASTER_PORT=$((port + 2)) "$chore" train "${train_killed[@]}" >/dev/null 2>&1 &
killed=$!  # chore's own pid (a function in the background would be a subshell's)
ranked 0 $((port + 2)) "${train_killed[@]}" >"$killed_dir.rank0" 2>&1 &
survivor=$!
for _ in $(seq 240); do [[ -e "$killed_dir/checkpoint_600.pt" ]] && break; sleep 0.25; done
kill -9 "$killed"
wait "$killed" 2>/dev/null
wait "$survivor"
survivor_code=$?
expect 0 "all-reduce failed (a rank gone?)" -- cat "$killed_dir.rank0"
if [[ $survivor_code -ne 2 ]]; then echo "FAIL: rank 0 beside a killed rank exited $survivor_code (want 2)"; failures=$((failures + 1)); fi
ranked 1 $((port + 3)) --resume "$killed_dir" --steps 2400 >/dev/null 2>&1 &
expect 0 "2400 steps done; checkpoint" -- ranked 0 $((port + 3)) --resume "$killed_dir" --steps 2400
wait

# chore reproduce: bad arguments exit 2 before any run starts (the table itself
# is tested in tests/reproduce_test.cpp).
reproduce_out="$(mktemp -d)"
expect 2 "unknown activity 'nope'" -- "$chore" reproduce --activities nope --out "$reproduce_out"
expect 2 "give activities by name" -- "$chore" reproduce --activities "$data/bddl/collect_one_bottle.bddl" --out "$reproduce_out"
expect 2 "methods" -- "$chore" reproduce --methods rl-magic --out "$reproduce_out"
expect 2 "steps" -- "$chore" reproduce --steps 0 --out "$reproduce_out"
expect 2 "--generalisation-seeds '5-1': B is below A" -- "$chore" reproduce --generalisation-seeds 5-1 --out "$reproduce_out"
expect 2 "--set ppo.nope: no such setting" -- "$chore" reproduce --set ppo.nope=1 --out "$reproduce_out"
if [[ -n "$(ls -A "$reproduce_out")" ]]; then echo "FAIL: a refused reproduce wrote to $reproduce_out"; failures=$((failures + 1)); fi

# scripts/compare_runs: one short cell run twice reproduces bit for bit (exit 0);
# a machine's speed (wall_s) is not compared, a learning column is (exit 1); an
# unreadable checkpoint is exit 2.
compare_runs="$(cd "$(dirname "${BASH_SOURCE[0]}")/../scripts" && pwd)/compare_runs"
twice="$(mktemp -d)"
for copy in a b; do
  expect 0 "1/1 runs done" -- "$chore" reproduce --activities collect_trash --methods rl-prim --seeds 0 --steps 300 --mode symbolic --jobs 1 --eval-episodes 1 --generalisation-seeds 100-100 --no-videos --set ppo.epochs=3 --out "$twice/$copy"
done
run_a="$twice/a/runs/symbolic/collect_trash/rl-prim_seed0"
run_b="$twice/b/runs/symbolic/collect_trash/rl-prim_seed0"
expect 0 "checkpoint.pt tensors: identical" -- "$compare_runs" "$run_a" "$run_b"
awk -F, -v OFS=, 'NR == 2 { $2 = $2 + 1000 } 1' "$run_b/metrics.csv" > "$twice/m" && mv "$twice/m" "$run_b/metrics.csv"
expect 0 "metrics.csv: identical" -- "$compare_runs" "$run_a" "$run_b"
awk -F, -v OFS=, 'NR == 2 { $11 = $11 + 1 } 1' "$run_b/metrics.csv" > "$twice/m" && mv "$twice/m" "$run_b/metrics.csv"
expect 1 "metrics.csv: DIFFERENT" -- "$compare_runs" "$run_a" "$run_b"
printf 'garbage' > "$run_b/checkpoint.pt"
expect 2 "not a chore checkpoint" -- "$compare_runs" "$run_a" "$run_b"
expect 2 "no_such_run" -- "$compare_runs" "$run_a" "$twice/no_such_run"

echo "$((checks - failures)) passed, $failures failed"
[[ $failures -eq 0 ]]
