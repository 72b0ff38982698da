#!/bin/sh
# play.sh SEED [STRATEGY] [setup options...] -- play one game in real CLIPS.
#   STRATEGY: naive | paper (default) | travel
#   setup options go to the setup example: --index --clock-off
#   --seeded-times --faults N --s0 N
# Prints the decision log and a RESULT line.  TRACE=1 adds (watch rules).
# EMIT=1 prints the self-contained batch file instead of running it (the
# setup inline), e.g. for running the same game in another engine.
# CLIPS=COMMAND runs another engine with the same batch options (default: clips).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
seed=${1:?usage: play.sh SEED [STRATEGY] [setup options]}
shift
strategy=paper
case "${1:-}" in naive|paper|travel) strategy=$1; shift;; esac
. "$here/clips/strategy.sh"
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-/work/target-rules}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
(cd "$here" && cargo run -q -p rules --example setup -- "$seed" "$@") > "$tmp/setup.clp"
{
  load_lines "$here" "$strategy"
  cat "$tmp/setup.clp"
  echo "(reset)"
  if [ "${TRACE:-0}" = 1 ]; then echo "(watch rules)"; fi
  echo "(run)"
  echo "(report-decisions)"
  echo "(report-game)"
  echo "(exit)"
} > "$tmp/play.clp"
if [ "${EMIT:-0}" = 1 ]; then cat "$tmp/play.clp"; exit 0; fi
timeout 60 ${CLIPS:-clips} -f2 "$tmp/play.clp"
