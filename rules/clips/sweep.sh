#!/bin/sh
# sweep.sh STRATEGY [FROM TO] [setup options...] -- play assignments
# (or with --seeds: seeds) FROM..TO (default all 4200 assignments) in one
# real-CLIPS process and summarise:
# mean points, P per game, the P distribution, end reasons (deadlocks must
# be 0).  Example: sweep.sh paper 0 4200 --clock-off
# CLIPS=COMMAND runs another engine with the same batch options (default: clips).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
strategy=${1:?usage: sweep.sh STRATEGY [FROM TO] [setup options]}
shift
from=0; to=4200
case "${1:-}" in [0-9]*) from=$1; to=${2:?TO}; shift 2;; esac
. "$here/clips/strategy.sh"
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-/work/target-rules}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
{
  load_lines "$here" "$strategy"
  (cd "$here" && cargo run -q -p rules --example setup -- --sweep "$from" "$to" "$@")
  echo "(exit)"
} > "$tmp/sweep.clp"
timeout 3000 ${CLIPS:-clips} -f2 "$tmp/sweep.clp" > "$tmp/out.txt"
if [ -n "${KEEP:-}" ]; then cp "$tmp/out.txt" "$KEEP"; fi
awk -v strategy="$strategy" '
  /^GAME/ {
    for (i = 1; i < NF; i++) v[$i] = $(i+1)
    games++; pts += v["points"]; p = v["p"]; pp[p]++; prod += p
    ends[v["end"]]++; dec += v["decisions"]; disc += v["discarded"]
    t += v["time"]; m += v["travel"]
    if (p == 0) nop++
    if (games == 1 || v["points"] < min) min = v["points"]
    if (v["points"] > max) max = v["points"]
  }
  /DEADLOCK|WARN/ { warn++ }
  END {
    printf "%s: games %d mean points %.2f min %d max %d mean P %.3f no-P %d decisions/game %.1f discarded %d warnings %d mean end %.1f s travel %.1f m\n",
      strategy, games, pts / games, min, max, prod / games, nop + 0, dec / games, disc + 0, warn + 0, t / games, m / games
    printf "  P per game:"; for (k = 0; k <= 10; k++) if (pp[k]) printf " %d:%d", k, pp[k]; printf "\n"
    printf "  ends:"; for (e in ends) printf " %s:%d", e, ends[e]; printf "\n"
  }' "$tmp/out.txt"
