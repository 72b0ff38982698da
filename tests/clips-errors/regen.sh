#!/bin/sh
# Records what real CLIPS 6.30 prints for each malformed program, as NNN-*.clips-out.
# These transcripts are for humans (to see CLIPS's own error text); the harness
# host-shim/tests/parse_errors.rs checks our CLI against the `; expect:` header instead.
# Programs that end inside an unclosed form make CLIPS wait for input; stdin is /dev/null,
# so CLIPS sees end of input and stops.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
command -v clips >/dev/null 2>&1 || { echo "regen.sh: real CLIPS 6.30 (\`clips\`) is not installed" >&2; exit 1; }
if [ $# -eq 0 ]; then set -- "$here"/*.clp; fi
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
for program in "$@"; do
    program=$(cd "$(dirname "$program")" && pwd)/$(basename "$program")
    out=${program%.clp}.clips-out
    (cd "$scratch" && timeout 10 clips -f "$program" < /dev/null > "$out") || true
    echo "wrote $out"
done
