#!/bin/bash
# c-measure.sh BASE_BIN NEW_BIN: callgrind instruction counts of benchmark rows for two
# builds of ours (run = full batch - the batch without (run), whole = full batch), the
# change in %, and whether the full batch printed the same. The rows are the programs
# `robotino-agent bench --emit-only` wrote into $WORK (default /work/notes/c-work), e.g.
#   robotino-agent bench --emit-only --workloads llsf,manners,join,negation,discrim,\
#     propagate,agent,zebra,manners-pub,sudoku --manners-sizes 16 --scale-sizes 100,10000 \
#     --discrim-sizes 40 --propagate-sizes 500 --agent-sizes 40 --sudoku-puzzles 3x3-p1 \
#     --work-dir /work/notes/c-work
# Give both binaries paths of the same length: the path is in argv, which whole counts.
set -u
base=${1:?base bin}; new=${2:?new bin}
work=${WORK:-/work/notes/c-work}
out=$(mktemp -d)
ir() { # bin dir batch tag
    local f="$out/$(basename "$2").$4.$3.log"
    (cd "$2" && valgrind --tool=callgrind --callgrind-out-file=/dev/null "$1" clips -f2 "$3" \
        > "$out/$(basename "$2").$4.$3.stdout" 2> "$f")
    grep -a "Collected" "$f" | awk '{print $NF}'
}
printf "%-16s %-6s %15s %15s %9s\n" row region base new change
for dir in "$work"/*/; do
    dir=${dir%/}; row=$(basename "$dir")
    [ -f "$dir/full.bat.clp" ] || continue
    bf=$(ir "$base" "$dir" full.bat.clp b)
    bn=$(ir "$base" "$dir" norun.bat.clp b)
    nf=$(ir "$new" "$dir" full.bat.clp n)
    nn=$(ir "$new" "$dir" norun.bat.clp n)
    same=same
    cmp -s "$out/$row.b.full.bat.clp.stdout" "$out/$row.n.full.bat.clp.stdout" || same=DIFFERENT-OUTPUT
    awk -v r="$row" -v bf="$bf" -v bn="$bn" -v nf="$nf" -v nn="$nn" -v s="$same" 'BEGIN{
        br=bf-bn; nr=nf-nn;
        printf "%-16s %-6s %15d %15d %+8.2f%%\n", r, "run", br, nr, (nr-br)*100/br;
        printf "%-16s %-6s %15d %15d %+8.2f%%  %s\n", r, "whole", bf, nf, (nf-bf)*100/bf, s }'
done
rm -rf "$out"
