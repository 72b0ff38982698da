#!/bin/bash
# Quick differential check without cargo: runs every tests/clips/NNN-*.clp (or the
# programs given) in our CLI and compares with CLIPS 6.30's golden transcript NNN-*.out,
# as host-shim/tests/differential.rs does (banner line aside, our `--> FILE:L:C:
# expected` lines dropped). Prints the programs that differ and a count.
# Usage: tests/clips/quickdiff.sh /abs/path/robotino-agent [PROGRAM.clp ...]
set -u
bin=${1:?usage: quickdiff.sh /abs/path/robotino-agent [PROGRAM.clp ...]}
shift
here=$(cd "$(dirname "$(readlink -f "$0")")" && pwd)
if [ $# -eq 0 ]; then set -- "$here"/[0-9]*.clp; fi
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
total=0 differ=0
for program in "$@"; do
    program=$(cd "$(dirname "$program")" && pwd)/$(basename "$program")
    golden=${program%.clp}.out
    rm -rf "${scratch:?}"/*
    total=$((total + 1))
    (cd "$scratch" && timeout 60 "$bin" clips -f "$program" < /dev/null 2>/dev/null) \
        | tail -n +2 | grep -av -E '^--> .*: expected ' > "$scratch.ours"
    status=${PIPESTATUS[0]}
    tail -n +2 "$golden" > "$scratch.clips"
    # a hang is a crash, even when the golden transcript stops where ours does
    if [ "$status" -eq 124 ]; then
        differ=$((differ + 1))
        echo "TIMEOUT: $(basename "$program")"
    elif ! cmp -s "$scratch.ours" "$scratch.clips"; then
        differ=$((differ + 1))
        echo "DIFFERS: $(basename "$program")"
    fi
done
rm -f "$scratch.ours" "$scratch.clips"
echo "$total programs, $differ differ"
[ "$differ" -eq 0 ]
