#!/bin/sh
# parity.sh OTHER_COMMAND [SEEDS] -- same decisions as real CLIPS.
# Plays SEEDS (default 20) seeded games per strategy (seeded times, two
# faults) with (watch rules) in real CLIPS and in OTHER_COMMAND (a
# CLIPS-compatible command line taking -f2, e.g. "robotino-agent clips"),
# and requires identical FIRE lines, decision logs and RESULT lines.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
other=${1:?usage: parity.sh OTHER_COMMAND [SEEDS]}
seeds=${2:-20}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
status=0; same=0
for strategy in naive paper travel; do
  for seed in $(seq 0 $((seeds - 1))); do
    EMIT=1 TRACE=1 "$here/clips/play.sh" "$seed" "$strategy" --seeded-times --faults 2 > "$tmp/game.clp"
    # Keep what both engines print the same way: rule firings, the decision
    # log lines (they start with the decision number) and the result.
    keep='^(FIRE|RESULT| +[0-9]+ +[0-9.]+ )'
    timeout 120 clips -f2 "$tmp/game.clp" | grep -E "$keep" > "$tmp/clips.txt" || true
    timeout 120 $other -f2 "$tmp/game.clp" 2>&1 | grep -E "$keep" > "$tmp/other.txt" || true
    if grep -q '^RESULT' "$tmp/clips.txt" && cmp -s "$tmp/clips.txt" "$tmp/other.txt"; then
      same=$((same + 1))
    else
      status=1
      echo "FAIL $strategy seed $seed:"
      diff "$tmp/clips.txt" "$tmp/other.txt" | head -4
    fi
  done
done
echo "identical games: $same of $((3 * seeds))"
exit $status
