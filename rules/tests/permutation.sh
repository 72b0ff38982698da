#!/bin/sh
# permutation.sh [SEEDS] -- decisions must not depend on agenda accidents.
# Plays each seed (default 20) per strategy twice in real CLIPS: once as
# is, once with the setup facts and the agent's machine and place facts in
# reverse order (other fact indices, other activation order among equal
# saliences).  The decision logs and results must be identical.
# CLIPS=COMMAND runs another engine with the same batch options (default: clips).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
. "$here/clips/strategy.sh"
seeds=${1:-20}
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-/work/target-rules}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The world model with its deffacts lines (machines, places) reversed.
awk '/^  \((machine|place) / { held[n++] = $0; next }
     n > 0 { for (i = n - 1; i >= 0; i--) print held[i]; n = 0 }
     { print }' "$here/worldmodel.clp" > "$tmp/worldmodel-rev.clp"
status=0
for strategy in naive paper travel; do
  for seed in $(seq 0 $((seeds - 1))); do
    (cd "$here" && cargo run -q -p rules --example setup -- "$seed" --seeded-times --faults 2) > "$tmp/fwd.clp"
    # Reverse the fact lines between "(deffacts game-setup" and the closing ")".
    { head -1 "$tmp/fwd.clp"; sed '1d;$d' "$tmp/fwd.clp" | tac; tail -1 "$tmp/fwd.clp"; } > "$tmp/rev.clp"
    for order in fwd rev; do
      {
        if [ $order = fwd ]; then
          load_lines "$here" "$strategy"
        else
          load_lines "$here" "$strategy" | sed "s|$here/worldmodel.clp|$tmp/worldmodel-rev.clp|"
        fi
        echo "(load* \"$tmp/$order.clp\")"
        echo "(reset)"
        echo "(run)"
        echo "(report-decisions)"
        echo "(report-game)"
        echo "(exit)"
      } > "$tmp/play-$order.clp"
      timeout 60 ${CLIPS:-clips} -f2 "$tmp/play-$order.clp" > "$tmp/out-$order.txt"
    done
    if ! grep -q '^RESULT' "$tmp/out-fwd.txt" || ! cmp -s "$tmp/out-fwd.txt" "$tmp/out-rev.txt"; then
      echo "FAIL $strategy seed $seed: decisions depend on fact order"
      diff "$tmp/out-fwd.txt" "$tmp/out-rev.txt" | head -5
      status=1
    fi
  done
  echo "$strategy: $seeds seeds checked"
done
[ $status -eq 0 ] && echo "PASS permutation"
exit $status
