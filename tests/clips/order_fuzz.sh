#!/bin/sh
# Differential runs of order_fuzz.py programs (activation order through shared alpha
# nodes and joins, rule files loaded under watch compilations before and after facts
# exist): each seed's program runs in real CLIPS 6.30 and in robotino-agent (`clips -f2`,
# in a scratch directory, as the programs write their rule files); differing seeds are
# listed and their programs kept in ${TMPDIR:-/tmp}/order_fuzz. Seeds whose program
# CLIPS reports an error for (`[CSTRNCHK1]` on literals a variable carries from slot to
# slot, say: errors are a class of their own) are counted apart, not compared.
# With KIND `logical`, the programs are logical_fuzz.py's (logical support over self
# joins, rules defined before and after the facts).
# Usage: tests/clips/order_fuzz.sh BINARY FROM TO [order|logical]   (exit 1 when any differs)
set -u
here=$(cd "$(dirname "$0")" && pwd)
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1"); from=$2; to=$3; kind=${4:-order}
command -v clips >/dev/null 2>&1 || { echo "order_fuzz.sh: real CLIPS 6.30 (\`clips\`) is not installed" >&2; exit 2; }
scratch=$(mktemp -d)
keep=${TMPDIR:-/tmp}/order_fuzz
mkdir -p "$keep"
fail=0
skip=0
for s in $(seq "$from" "$to"); do
    python3 "$here/${kind}_fuzz.py" "$s" > "$scratch/p.clp"
    rm -f "$scratch"/rules*.clp
    (cd "$scratch" && timeout 10 clips -f2 p.clp < /dev/null > c.out 2>&1)
    if grep -q '\[[A-Z]*[0-9][0-9]*\]' "$scratch/c.out"; then
        skip=$((skip + 1))
        continue
    fi
    rm -f "$scratch"/rules*.clp
    (cd "$scratch" && timeout 10 "$bin" clips -f2 p.clp < /dev/null > o.out 2>&1)
    if ! cmp -s "$scratch/c.out" "$scratch/o.out"; then
        echo "differs: seed $s ($keep/$kind-$s.clp)"
        cp "$scratch/p.clp" "$keep/$kind-$s.clp"
        fail=$((fail + 1))
    fi
done
rm -rf "$scratch"
echo "$kind fuzz $from..$to: $fail differ ($skip with a CLIPS error, not compared)"
[ "$fail" -eq 0 ]
