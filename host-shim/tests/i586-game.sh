#!/bin/sh
# A short LLSF game between robotino-sim and robotino-agent built for i586, both run under
# `qemu-i386 -cpu pentium2` (the LX800's closest model for std binaries, see
# shared/toolchain.md) and talking over iceoryx2 shared memory, which qemu-user passes
# through. Exits non-zero unless the game ends with a `done` line and the agent's rules
# decided at least one skill.
#
#   host-shim/tests/i586-game.sh [GAME_SECONDS]      (default 120 simulated seconds)
#
# Builds the two binaries first (release, i586-unknown-linux-gnu); set I586_BIN to a folder
# holding prebuilt ones to skip that. Honours CARGO_TARGET_DIR.
set -eu

seconds=${1:-120}
root=$(cd "$(dirname "$0")/../.." && pwd)
target_dir=${CARGO_TARGET_DIR:-$root/target}
if [ -z "${I586_BIN:-}" ]; then
    (cd "$root" && cargo build --target i586-unknown-linux-gnu -p host-shim --release)
    I586_BIN=$target_dir/i586-unknown-linux-gnu/release
fi
qemu="qemu-i386 -cpu pentium2"
prefix="i586game/$$-$(date +%s)"
work=$(mktemp -d)
sim_pid=
agent_pid=
cleanup() {
    [ -n "$agent_pid" ] && kill "$agent_pid" 2>/dev/null || true
    [ -n "$sim_pid" ] && kill "$sim_pid" 2>/dev/null || true
    rm -rf "$work"
    # The prefix's own iceoryx2 root (host-shim/src/shim/transport.rs, root_dir).
    rm -rf "/tmp/iceoryx2/robotino/i586game/$$-"*
}
trap cleanup EXIT

echo "i586-game: $I586_BIN under '$qemu', prefix $prefix, $seconds s"
$qemu "$I586_BIN/robotino-sim" --prefix "$prefix" --lockstep --game-seconds "$seconds" \
    >"$work/sim.log" 2>&1 &
sim_pid=$!
$qemu "$I586_BIN/robotino-agent" run --prefix "$prefix" --lockstep >"$work/agent.log" 2>&1 &
agent_pid=$!

# Watchdog: a game of this length takes well under the limit even emulated.
limit=$((seconds * 2 + 120))
waited=0
while kill -0 "$sim_pid" 2>/dev/null; do
    if [ "$waited" -ge "$limit" ]; then
        echo "i586-game: FAIL: no end of game within $limit s"
        tail -20 "$work/sim.log" "$work/agent.log"
        exit 1
    fi
    sleep 1
    waited=$((waited + 1))
done
sim_status=0
wait "$sim_pid" || sim_status=$?
sim_pid=
kill -TERM "$agent_pid" 2>/dev/null || true
agent_status=0
wait "$agent_pid" || agent_status=$?
agent_pid=

done_line=$(grep 'robotino-sim: done' "$work/sim.log" || true)
stats_line=$(grep 'robotino-agent run: done' "$work/agent.log" || true)
skills=$(grep -c ' start ' "$work/agent.log" || true)
echo "${done_line:-no done line}"
echo "${stats_line:-no agent statistics}"
echo "i586-game: skills=$skills sim_exit=$sim_status agent_exit=$agent_status"
if [ "$sim_status" -ne 0 ] || [ "$agent_status" -ne 0 ] || [ -z "$done_line" ] \
    || [ "$skills" -lt 1 ]; then
    echo "i586-game: FAIL"
    tail -20 "$work/sim.log" "$work/agent.log"
    exit 1
fi
echo "i586-game: OK"
