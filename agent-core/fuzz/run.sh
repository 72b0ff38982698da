#!/usr/bin/env bash
# Runs every fuzz target (or the ones named) for SECONDS each, one after the other (the
# machine's cores are shared), and prints executions and findings per target.
#   agent-core/fuzz/run.sh SECONDS [TARGET...]
# Needs the nightly toolchain and cargo-fuzz (`cargo install cargo-fuzz`). Not part of
# CI's default run. Crashes land in agent-core/fuzz/artifacts/TARGET/; reproduce one
# with `cargo +nightly fuzz run -O -s none --no-trace-compares TARGET \
#   fuzz/artifacts/TARGET/crash-...`
# (from agent-core/), then turn it into a regression test.
#
# Build flags, the same for every target so they share one build: no sanitizer (the
# code under test is safe Rust; the one `unsafe`, building payloads from bytes, reads
# plain-old-data) and no comparison tracing (the engine target checks invariants after
# every command, and traced comparisons made it ~10x slower); debug assertions stay on.
set -uo pipefail

secs=${1:-60}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(load_str engine_commands payloads batch api_text compiled_write)
fi

here=$(cd "$(dirname "$0")" && pwd)
core=$(dirname "$here")
repo=$(dirname "$core")
cd "$core"

seed() {
    local t=$1 dir="$here/corpus/$1"
    mkdir -p "$dir"
    case $t in
        load_str|batch|compiled_write)
            # the differential and error suites: every construct and error kind
            cp -n "$repo"/tests/clips/*.clp "$repo"/tests/clips-errors/*.clp "$dir"/ 2>/dev/null
            # but 24,000 firings under the breadth strategy: 3 s a run, a timeout on a
            # loaded machine, and slow mutants
            rm -f "$dir"/773-breadth-long-agenda.clp
            ;;
        engine_commands)
            # a few streams: asserts then runs, with modify/retract/reset mixed in
            printf '\x00\x12\x31\x04\x23\x0b\x10\x09\x01\x02\x03\x0c\x0f\x07\x02\x0d' > "$dir/seed-mixed"
            printf '\x00\x10\x21\x00\x21\x32\x00\x32\x13\x06\x2f\x0b\x17\x0e\x02\x0b\x17' > "$dir/seed-rules"
            head -c 600 /dev/urandom > "$dir/seed-random" 2>/dev/null
            ;;
        api_text)
            # facts for assert_str, and one line of each other entry point
            printf '(item (id 7) (tag a) (parts p q))\n(count (n 3))\n(foo bar 1 2.5 "s")\n.5\n-1\n!(+ 1 (twice 3))\n>(facts)\n+(defrule r (foo $?x) => (retract 1))\n.\n#\n' > "$dir/seed-mixed"
            printf '(item (id 3) (parts))\n(item (tag b) (id 9))\n.100\n>(agenda)\n!(modify 1 (tag c))\n' > "$dir/seed-items"
            ;;
        payloads)
            for k in 0 1 2 3 4 5 6 7 8 9 10 11; do
                printf "\\x$(printf %02x $k)\\x01\\x00\\x00\\x00\\x01\\x01\\x01\\x00\\x00\\x00\\x00\\x00" > "$dir/seed-$k"
            done
            ;;
    esac
}

status=0
printf '%-18s %12s %10s %8s %s\n' target executions exec/s crashes notes
for t in "${targets[@]}"; do
    seed "$t"
    extra=()
    if [ "$t" != engine_commands ] && [ "$t" != payloads ]; then
        extra=(-dict="$here/clips.dict" -max_len=8192)
    fi
    log="$here/artifacts/$t.log"
    mkdir -p "$here/artifacts/$t"
    before=$(ls "$here/artifacts/$t" | grep -c -E '^(crash|oom|timeout|leak)-' || true)
    cargo +nightly fuzz run -O -s none --no-trace-compares "$t" "$here/corpus/$t" -- \
        -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 "${extra[@]}" > "$log" 2>&1
    rc=$?
    after=$(ls "$here/artifacts/$t" | grep -c -E '^(crash|oom|timeout|leak)-' || true)
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
    rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
    notes="corpus $(ls "$here/corpus/$t" | wc -l) files"
    if [ $rc -ne 0 ]; then
        notes="$notes; exit $rc, see $log"
        status=1
    fi
    printf '%-18s %12s %10s %8s %s\n' "$t" "${execs:-?}" "${rate:-?}" "$((after - before))" "$notes"
done
exit $status
