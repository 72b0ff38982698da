#!/bin/sh
# Differential runs of random CLIPS sessions that change the rule base while facts exist
# (rules defined, redefined and removed between asserts and runs, tests that fail on a
# symbol, queries in tests): each seed's program (tests/clips/random_sessions.py) runs in
# real CLIPS 6.30 and in robotino-agent; differing seeds are listed and their programs
# kept. Usage: tests/clips/random_sessions.sh BINARY FROM TO [modules]
# (exit 1 when any differs; `modules`: sessions with modules, see random_sessions.py)
set -u
here=$(cd "$(dirname "$0")" && pwd)
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1"); from=$2; to=$3; mode=${4:-}
command -v clips >/dev/null 2>&1 || { echo "random_sessions.sh: real CLIPS 6.30 (\`clips\`) is not installed" >&2; exit 2; }
scratch=$(mktemp -d)
keep=${TMPDIR:-/tmp}/random_sessions
mkdir -p "$keep"
fail=0
for s in $(seq "$from" "$to"); do
    python3 "$here/random_sessions.py" "$s" $mode > "$scratch/p.clp"
    (cd "$scratch" && timeout 10 clips -f p.clp < /dev/null > c.out 2>&1)
    (cd "$scratch" && timeout 10 "$bin" clips -f p.clp < /dev/null > o.out 2>&1)
    if ! cmp -s "$scratch/c.out" "$scratch/o.out"; then
        echo "differs: seed $s ($keep/session-$s.clp)"
        cp "$scratch/p.clp" "$keep/session-$s.clp"
        fail=$((fail + 1))
    fi
done
rm -rf "$scratch"
echo "random sessions $from..$to${mode:+ ($mode)}: $fail differ"
[ "$fail" -eq 0 ]
