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

# Activities: valid files are checked, a malformed one is located.
tasks="$(cd "$(dirname "${BASH_SOURCE[0]}")/../tasks/activities" && pwd)"
expect 0 "store_decoration_0 (igibson): 5 objects" -- "$chore" activity check "$tasks/store_decoration.bddl" "$tasks/collect_trash.bddl" "$tasks/clean_table.bddl"
expect 2 "error_unbalanced.bddl:3:1: expected ')'" -- "$chore" activity check "$data/bddl/error_unbalanced.bddl"
expect 2 "unknown activity 'nope'" -- "$chore" activity sample nope --out /tmp/chore_cli_nope.png
out_png="$(mktemp -d)/sample.png"
expect 0 "picture: $out_png" -- "$chore" activity sample store_decoration --seed 1 --out "$out_png"
if [[ ! -s "$out_png" ]]; then echo "FAIL: $out_png was not written"; failures=$((failures + 1)); fi

# The scripted expert: bad options exit 2; two symbolic episodes run and report.
expect 2 "mode" -- "$chore" expert --activity store_decoration --mode teleport
expect 2 "episodes" -- "$chore" expert --activity store_decoration --episodes 0
expect 2 "unknown activity 'nope'" -- "$chore" expert --activity nope --episodes 1
expect 0 '"success_rate"' -- "$chore" expert --activity store_decoration --episodes 2 --seed 1 --mode symbolic --json
expect 0 "success rate" -- "$chore" expert --activity store_decoration --episodes 1 --seed 1 --mode symbolic

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
expect 0 "300 steps done" -- "$chore" train --activity collect_trash --baseline rl-prim --mode symbolic --observations is_grasping --steps 300 --out "$run_dir"
if [[ "$(head -1 "$run_dir/metrics.csv" | cut -d, -f1-7)" != "env_steps,wall_s,episodes,success_rate,mean_q,mean_return,mean_length" ]]; then
  echo "FAIL: $run_dir/metrics.csv header"; failures=$((failures + 1))
fi
expect 2 "already holds a run" -- "$chore" train --activity collect_trash --baseline rl-prim --out "$run_dir"
expect 2 "holds a rl-prim run on collect_trash" -- "$chore" train --resume "$run_dir" --baseline rl-vmc
printf 'garbage' > "$run_dir/checkpoint.pt"
expect 2 "not a chore checkpoint" -- "$chore" train --resume "$run_dir"

echo "$((checks - failures)) passed, $failures failed"
[[ $failures -eq 0 ]]
