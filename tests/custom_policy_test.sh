#!/usr/bin/env bash
# The header API end to end: install chore to a scratch prefix, build the
# example policy (examples/custom_policy) out of tree against it with
# find_package(chore), and evaluate it with the installed `chore eval`.
# Usage: custom_policy_test.sh CMAKE BUILD_DIR SOURCE_DIR GENERATOR
set -euo pipefail
cmake="$1" build="$2" source="$3" generator="$4"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT

"$cmake" --install "$build" --prefix "$scratch/prefix" >/dev/null
"$cmake" -S "$source/examples/custom_policy" -B "$scratch/build" -G "$generator" \
  -DCMAKE_PREFIX_PATH="$scratch/prefix" >/dev/null
"$cmake" --build "$scratch/build" >/dev/null
plugin="$scratch/build/libmasked_random_policy.so"
chore="$scratch/prefix/bin/chore"

# The masked policy never picks an action whose precondition fails, so no
# precondition failures and no policy failures; 2 episodes x 6 steps, truncated.
out="$("$chore" eval --policy-plugin "$plugin" --policy-options seed=3 --activity store_decoration \
  --mode symbolic --observations is_grasping,action_mask --seeds 0-0 --episodes 2 --max-steps 6 --json 2>/dev/null)"
for want in '"precondition_failure": 0' '"policy_failure": 0' '"time_limit": 2' '"env_steps": 12'; do
  if ! grep -q -- "$want" <<<"$out"; then
    echo "FAIL: eval output lacks $want:"
    echo "$out" | head -40
    exit 1
  fi
done
# A factory that refuses its options: exit 2 with its message.
set +e
err="$("$chore" eval --policy-plugin "$plugin" --policy-options bogus --activity store_decoration 2>&1)"
code=$?
set -e
if [[ $code -ne 2 ]] || ! grep -q "the factory refused: masked_random: unknown options 'bogus'" <<<"$err"; then
  echo "FAIL: bad options -> exit $code: $err"
  exit 1
fi
echo "ok: installed, built out of tree, evaluated"
