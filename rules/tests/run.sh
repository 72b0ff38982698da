#!/bin/sh
# run.sh [FILE...] -- run the scenario tests in real CLIPS.
# Each tests/*.clp (except the lib*.clp helpers) names its strategy on a ";;; strategy:"
# line; it is run with that agent, plus referee, game log and sim where the header
# says ";;; with: game".  Passes when every file prints at least one PASS,
# no FAIL, and CLIPS reports no error.
# CLIPS=COMMAND runs another engine with the same batch options (default: clips).
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
. "$here/clips/strategy.sh"
if [ $# -eq 0 ]; then set -- "$here"/tests/*.clp; fi
status=0; total=0
for test in "$@"; do
  case "$test" in */lib.clp|*/lib-game.clp) continue;; esac
  strategy=$(sed -n 's/^;;; strategy: *//p' "$test" | head -1)
  batch=$(mktemp)
  {
    load_lines "$here" "${strategy:-paper}" | grep -v -e referee.clp -e game-log.clp -e sim.clp -e snapshot.clp -e report.clp
    echo "(load* \"$here/tests/lib.clp\")"
    if grep -q '^;;; with: game' "$test"; then
      echo "(load* \"$here/referee.clp\")"
      echo "(load* \"$here/game-log.clp\")"
      echo "(load* \"$here/sim.clp\")"
      echo "(load* \"$here/snapshot.clp\")"
      echo "(load* \"$here/clips/report.clp\")"
      echo "(load* \"$here/tests/lib-game.clp\")"
    fi
    cat "$test"
    echo "(exit)"
  } > "$batch"
  out=$(timeout 60 ${CLIPS:-clips} -f2 "$batch" 2>&1)
  rm -f "$batch"
  pass=$(printf '%s\n' "$out" | grep -c '^PASS')
  fail=$(printf '%s\n' "$out" | grep -c '^FAIL')
  errors=$(printf '%s\n' "$out" | grep -c -e '^\[' -e 'ERROR')
  total=$((total + pass))
  printf '%s\n' "$out" | grep -e '^FAIL' -e '^\[' -e 'ERROR' -A2
  echo "$(basename "$test"): $pass passed, $fail failed, $errors errors"
  if [ "$fail" -ne 0 ] || [ "$errors" -ne 0 ] || [ "$pass" -eq 0 ]; then status=1; fi
done
echo "total passed: $total"
exit $status
