#!/bin/sh
# Regenerates the golden transcripts tests/clips/NNN-*.out from real CLIPS 6.30.
# Usage: tests/clips/regen.sh [PROGRAM.clp ...]   (default: every program)
# Each program runs in a fresh scratch directory (some write files) under a timeout,
# exactly as host-shim/tests/differential.rs runs it.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
command -v clips >/dev/null 2>&1 || { echo "regen.sh: real CLIPS 6.30 (\`clips\`) is not installed" >&2; exit 1; }
if [ $# -eq 0 ]; then set -- "$here"/*.clp; fi
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
for program in "$@"; do
    program=$(cd "$(dirname "$program")" && pwd)/$(basename "$program")
    out=${program%.clp}.out
    rm -rf "$scratch"/* 
    if ! (cd "$scratch" && timeout 10 clips -f "$program" < /dev/null > "$out"); then
        echo "regen.sh: clips failed or timed out on $program" >&2
        exit 1
    fi
    echo "wrote $out"
done
