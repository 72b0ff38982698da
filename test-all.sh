#!/usr/bin/env bash
# Runs ALL tests of robotino-agent: formatting, clippy, host tests, the i586 unit tests
# under qemu, the no_std proof, the agent image under `qemu-i386 -cpu pentium`, the
# footprint gate, the instruction-set gate, and a short game between robotino-sim and
# robotino-agent built for i586, both under `qemu-i386 -cpu pentium2`. Every stage prints its time; a stage never
# skips silently; the run exits non-zero if any stage fails.
#
# Run as root on a fresh Debian machine, it installs what is missing (rustup targets and
# components, then apt packages after `apt-get update`). Run as another user, it prints
# exactly what to install and exits non-zero.
#
# Uses cargo's default target dir (./target) unless CARGO_TARGET_DIR is set.
set -u -o pipefail

cd "$(dirname "$0")"
# rustup's default place, in case the calling environment (e.g. CI) lacks it in PATH.
if [[ -d "${HOME:-/root}/.cargo/bin" ]]; then
    PATH="${HOME:-/root}/.cargo/bin:$PATH"
fi

readonly I586=i586-unknown-linux-gnu
readonly NO_STD_TARGET=x86_64-unknown-none
readonly APT_PACKAGES=(qemu-user gcc-multilib clips binutils)
readonly TARGET_DIR="${CARGO_TARGET_DIR:-target}"
# A clean clone gains nothing from incremental caches; they only cost disk.
export CARGO_INCREMENTAL="${CARGO_INCREMENTAL:-0}"

SUMMARY=()
FAILED=0
PASSED=0
STAGE_NOTE=""

# disk_report: the target dir's size and the free space on its file system.
disk_report() {
    local used free where=.
    [[ -d "$TARGET_DIR" ]] && where="$TARGET_DIR"
    used=$(du -sm "$TARGET_DIR" 2>/dev/null | cut -f1)
    free=$(df -Pm "$where" 2>/dev/null | awk 'NR == 2 { print $4 }')
    echo "${TARGET_DIR}: ${used:-0} MB used, ${free:-?} MB free"
}

# run_stage NAME FUNCTION: runs one stage, times it, records the outcome.
run_stage() {
    local name="$1" fn="$2" start end status
    STAGE_NOTE=""
    echo
    echo "==== stage ${name}"
    start=$(date +%s.%N)
    if "$fn"; then
        status=ok
        PASSED=$((PASSED + 1))
    else
        status=FAILED
        FAILED=$((FAILED + 1))
    fi
    end=$(date +%s.%N)
    local secs
    secs=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
    # Disk is a resource CI can run out of: show what the target dir holds after each stage.
    echo "target dir $(disk_report)"
    echo "==== stage ${name}: ${status} in ${secs} s${STAGE_NOTE:+ (${STAGE_NOTE})}"
    SUMMARY+=("$(printf '%-26s %-7s %8s s  %s' "$name" "$status" "$secs" "$STAGE_NOTE")")
}

# ---------------------------------------------------------------------------------------
# Stage 0: prerequisites.

missing_tools() {
    # Prints one word per missing thing: target:<t>, component:<c>, apt:<package>.
    local installed_targets
    if command -v rustup >/dev/null 2>&1; then
        installed_targets=$(rustup target list --installed 2>/dev/null)
        for t in "$I586" "$NO_STD_TARGET"; do
            grep -qx "$t" <<<"$installed_targets" || echo "target:$t"
        done
        cargo fmt --version >/dev/null 2>&1 || echo "component:rustfmt"
        cargo clippy --version >/dev/null 2>&1 || echo "component:clippy"
    else
        echo "rustup"
    fi
    command -v qemu-i386 >/dev/null 2>&1 || echo "apt:qemu-user"
    command -v objdump >/dev/null 2>&1 || echo "apt:binutils"
    command -v clips >/dev/null 2>&1 || echo "apt:clips"
    # Linking for i586 needs 32-bit crt files and libgcc: try it.
    if ! echo 'int main(void) { return 0; }' |
        cc -m32 -x c - -o "${TMPDIR:-/tmp}/robotino-m32-check.$$" >/dev/null 2>&1; then
        echo "apt:gcc-multilib"
    fi
    rm -f "${TMPDIR:-/tmp}/robotino-m32-check.$$"
}

install_missing() {
    local missing=("$@") apt=() item
    for item in "${missing[@]}"; do
        case "$item" in
            target:*) rustup target add "${item#target:}" || return 1 ;;
            component:*) rustup component add "${item#component:}" || return 1 ;;
            apt:*) apt+=("${item#apt:}") ;;
            rustup)
                echo "rustup is missing: install it from the Rust project, then rerun" >&2
                return 1
                ;;
        esac
    done
    if ((${#apt[@]} > 0)); then
        echo "installing apt packages: ${APT_PACKAGES[*]}"
        DEBIAN_FRONTEND=noninteractive apt-get update || return 1
        DEBIAN_FRONTEND=noninteractive apt-get install -y "${APT_PACKAGES[@]}" || return 1
    fi
}

# Prints the commands that install exactly the missing things.
install_hint() {
    local item targets=() components=() apt=()
    echo "Not root, so nothing was installed. Run as root, or install:"
    for item in "$@"; do
        case "$item" in
            target:*) targets+=("${item#target:}") ;;
            component:*) components+=("${item#component:}") ;;
            apt:*) apt+=("${item#apt:}") ;;
            rustup) echo "  install rustup (https://rustup.rs), then rerun this script" ;;
        esac
    done
    ((${#targets[@]} > 0)) && echo "  rustup target add ${targets[*]}"
    ((${#components[@]} > 0)) && echo "  rustup component add ${components[*]}"
    ((${#apt[@]} > 0)) && echo "  sudo apt-get update && sudo apt-get install -y ${apt[*]}"
    return 0
}

stage_prerequisites() {
    local missing
    mapfile -t missing < <(missing_tools)
    if ((${#missing[@]} == 0)); then
        echo "all present: rustup targets $I586 $NO_STD_TARGET, clippy, rustfmt, ${APT_PACKAGES[*]}"
        return 0
    fi
    echo "missing: ${missing[*]}"
    if [[ $(id -u) -eq 0 ]]; then
        install_missing "${missing[@]}" || return 1
        mapfile -t missing < <(missing_tools)
        if ((${#missing[@]} > 0)); then
            echo "still missing after installing: ${missing[*]}" >&2
            return 1
        fi
        STAGE_NOTE="installed what was missing"
        return 0
    fi
    install_hint "${missing[@]}" >&2
    return 1
}

# ---------------------------------------------------------------------------------------
# Stages 1-3: formatting, lints, host tests.

stage_fmt() {
    cargo fmt --all --check
}

stage_clippy() {
    # the workspace build has agent-core's u32 pool indices and host speed-ups
    # (host-shim enables `wide-index` and `host-speedups`); agent-core alone has the
    # image's u16 indices and neither: lint both ...
    cargo clippy --workspace --all-targets -- -D warnings || return 1
    echo "-- clippy on agent-core alone (u16 pool indices, no host speed-ups)"
    cargo clippy -p agent-core --all-targets -- -D warnings || return 1
    # ... and the library with each of the two independent features alone
    echo "-- clippy on agent-core with wide-index alone, then host-speedups alone"
    cargo clippy -p agent-core --features wide-index -- -D warnings || return 1
    cargo clippy -p agent-core --features host-speedups -- -D warnings || return 1
    # The image's freestanding code (entry point, syscalls, mem functions) only exists
    # when built for i586: lint that build too.
    echo "-- clippy on the freestanding image build ($I586)"
    cargo clippy -p agent-image --target "$I586" --profile image -- -D warnings
}

stage_host_tests() {
    # host-shim enables agent-core's `wide-index` (u32 pool indices) and
    # `host-speedups`, and cargo unifies features across the workspace: this run tests
    # agent-core with both on ...
    cargo test --workspace --no-fail-fast || return 1
    # ... and this one with both off, as in the agent image (u16 indices, no host
    # speed-ups), on the host, with the invariants checked before and after every
    # engine operation (`check-invariants`).
    echo "-- agent-core as in the image (no wide-index, no host-speedups) and check-invariants"
    cargo test -p agent-core --features check-invariants --no-fail-fast || return 1
    # The host speed-ups keep state of their own (the joins' one-child flags): the
    # invariant property tests and fuzz regressions run with them on as well.
    echo "-- agent-core's invariant tests with host-speedups and check-invariants"
    cargo test -p agent-core --features check-invariants,host-speedups --no-fail-fast \
        --test invariants_property || return 1
    # Without default features (no parser, extras, defer or wipe: the image's matching
    # paths); the tests that evaluate builtins need `parser`, which links their code.
    echo "-- agent-core without default features"
    cargo test -p agent-core --no-default-features --no-fail-fast
}

# ---------------------------------------------------------------------------------------
# Stage 4: the unit tests of agent-core, hal and rules cross-compiled for i586 and run
# under qemu through the runner in .cargo/config.toml.

stage_i586_tests() {
    local runner
    runner=$(sed -n "/^\[target\.$I586\]/,/^\[/ s/^runner *= *\"\(.*\)\"/\1/p" .cargo/config.toml)
    if [[ -z "$runner" ]]; then
        echo "no runner for $I586 in .cargo/config.toml" >&2
        return 1
    fi
    echo "runner for $I586 (.cargo/config.toml): $runner"
    # Build first, then run verbosely so cargo shows each `Running \`qemu-i386 ...\`` line.
    env -u CARGO_TARGET_I586_UNKNOWN_LINUX_GNU_RUNNER \
        cargo test --target "$I586" -p agent-core -p hal -p rules --no-run || return 1
    env -u CARGO_TARGET_I586_UNKNOWN_LINUX_GNU_RUNNER \
        cargo test -v --no-fail-fast --target "$I586" -p agent-core -p hal -p rules 2>&1 |
        grep -vE '^ +Fresh '
}

# ---------------------------------------------------------------------------------------
# Stage 5: agent-core, hal and rules are no_std; agent-core uses neither alloc nor heapless.

stage_no_std() {
    echo "-- build for $NO_STD_TARGET (a target without std: any use of std fails here)"
    cargo build --target "$NO_STD_TARGET" -p agent-core -p hal -p rules || return 1
    echo "-- build for $I586"
    cargo build --target "$I586" -p agent-core -p hal -p rules || return 1
    echo "-- cargo tree -e normal -p agent-core --target $I586"
    local tree
    tree=$(cargo tree -e normal -p agent-core --target "$I586") || return 1
    echo "$tree"
    if grep -qE '(^|[ ─└├│])(heapless|alloc[A-Za-z0-9_-]*) v[0-9]' <<<"$tree"; then
        echo "agent-core depends on heapless or an alloc crate (see tree above)" >&2
        return 1
    fi
    # The sysroot `alloc` crate never shows in cargo tree: look for it in the source. Only
    # the host's growing storage may use it, behind `#[cfg(feature = "grow")]`, a feature
    # that neither the default build nor the robot's image enables (checked below).
    local ungated
    ungated=$(find agent-core/src -name '*.rs' -exec awk '
        FNR == 1 { prev = "" }
        /^[[:space:]]*(pub[[:space:]]+)?extern[[:space:]]+crate[[:space:]]+alloc([^A-Za-z0-9_]|$)/ {
            if (prev !~ /^[[:space:]]*#\[cfg\(feature = "grow"\)\]/) print FILENAME ":" FNR ": " $0
        }
        NF { prev = $0 }' {} +)
    if [ -n "$ungated" ]; then
        echo "$ungated"
        echo "agent-core uses the alloc crate outside the grow feature (lines above)" >&2
        return 1
    fi
    if grep -qE '^default *=.*"grow"' agent-core/Cargo.toml; then
        echo "agent-core's default features include grow (alloc)" >&2
        return 1
    fi
    local image_features
    # Only the image's own (normal) dependencies: a build script that links agent-core
    # with grow (rules-compiled's writer) runs on the host and puts nothing in the image.
    image_features=$(cargo tree -e features,no-build,no-dev -i agent-core -p agent-image \
        --target "$I586") || return 1
    if grep -q 'feature "grow"' <<<"$image_features"; then
        echo "$image_features"
        echo "the agent image enables agent-core's grow feature (alloc)" >&2
        return 1
    fi
    echo "agent-core: no alloc (but behind the host-only grow feature), no heapless"
}

# ---------------------------------------------------------------------------------------
# Stage 6: the agent image, built in profile `image` and run under strict i586 qemu.

stage_image() {
    local out="$TARGET_DIR/agent-image.out"
    mkdir -p "$TARGET_DIR"
    # The config's runner (pentium2) is for std test binaries; the freestanding image must
    # run on strict i586, so this one run overrides it. Cargo prints the `Running` line.
    CARGO_TARGET_I586_UNKNOWN_LINUX_GNU_RUNNER="qemu-i386 -cpu pentium" \
        cargo run -p agent-image --profile image --target "$I586" | tee "$out" || return 1
    if ! grep -q '^agent-image: stack_max_bytes=[0-9]' "$out"; then
        echo "the image printed no stack measurement" >&2
        return 1
    fi
    check_score "$out"
}

# The image plays the seeded game of `robotino-agent sim --seed 0`: its score, decisions and
# rules fired must be the sim's (the `RESULT ...` line and "(N rules fired)").
check_score() {
    local out="$1" image sim sim_out
    image=$(sed -n 's/^agent-image: game .* fired=\([0-9]*\) decisions=\([0-9]*\) .*/fired \1 decisions \2/p' "$out")
    image="$image points $(sed -n 's/^agent-image: score=\(-\{0,1\}[0-9][0-9]*\)$/\1/p' "$out")"
    sim_out=$(cargo run -q --release -p host-shim --bin robotino-agent -- sim --seed 0) || {
        echo "score check: robotino-agent sim --seed 0 failed" >&2
        return 1
    }
    sim="fired $(sed -n 's/.*after [0-9]* decisions (\([0-9]*\) rules fired).*/\1/p' <<<"$sim_out")"
    sim="$sim decisions $(sed -n 's/^RESULT .* decisions \([0-9]*\) .*/\1/p' <<<"$sim_out")"
    sim="$sim points $(sed -n 's/^RESULT points \(-\{0,1\}[0-9]*\) .*/\1/p' <<<"$sim_out")"
    echo "score check: image: $image; sim --seed 0: $sim"
    if [[ "$image" != "$sim" || "$image" != *" points "[0-9-]* ]]; then
        echo "score check: the image's game differs from sim --seed 0" >&2
        return 1
    fi
    STAGE_NOTE="image game = sim --seed 0 ($image)"
}

# ---------------------------------------------------------------------------------------
# Stages 7-8: the gates.

stage_footprint() {
    cargo run -q -p tests --bin footprint -- --json-out "$TARGET_DIR/footprint.json" || return 1
    echo "JSON report: $TARGET_DIR/footprint.json"
}

stage_isa() {
    cargo run -q -p tests --bin isa-gate
}

# ---------------------------------------------------------------------------------------

total_start=$(date +%s)
# ---------------------------------------------------------------------------------------
# Stage 9: the robot's two programs built for i586 play a short game (120 simulated
# seconds) against each other over iceoryx2, both under `qemu-i386 -cpu pentium2`.

stage_i586_game() {
    CARGO_TARGET_DIR="$TARGET_DIR" bash host-shim/tests/i586-game.sh 120
}

# ---------------------------------------------------------------------------------------
# Stage 10: the team over Zenoh. `team-link` is a workspace of its own (zenoh's crates stay
# out of the main build): its tests play the claims protocol over Zenoh sessions on
# 127.0.0.1 with 10 % loss and 2 s delays, and short team games (a few seeds, a short clock)
# whose robots reach each other only over Zenoh, with the host tests' debug binaries of
# robotino-agent and robotino-sim. Debug build in the same target dir (the crates both
# workspaces share are built once).

stage_zenoh_team() {
    local bins
    bins=$(cd "$TARGET_DIR/debug" 2>/dev/null && pwd) || {
        echo "no $TARGET_DIR/debug: the host tests stage builds robotino-agent there" >&2
        return 1
    }
    CARGO_TARGET_DIR="$TARGET_DIR" ROBOTINO_BIN_DIR="$bins" \
        cargo test --manifest-path team-link/Cargo.toml --no-fail-fast
}

# ---------------------------------------------------------------------------------------
# Disk. CI's machine may have little of it: one run stopped in stage 10 with 3.5 GB used
# by the target dir. Between stages, outputs that no later stage reads are deleted. Cargo
# rebuilds whatever a later stage does need, so deleting too much would cost time, never
# change a result.

# drop_test_executables DIR: the test binaries in DIR/deps (19-40 MB each, dozens of them).
# Binaries cargo uplifted into DIR (robotino-agent, robotino-sim, which stage 10 runs) are
# hard links of theirs and stay; proc-macro libraries (.so) stay.
drop_test_executables() {
    local dir="$1"
    [[ -d "$dir/deps" ]] || return 0
    find "$dir/deps" -maxdepth 1 -type f -perm -u+x ! -name '*.so' -delete
}

# drop_dirs NAME...: target-dir subdirectories no later stage reads.
drop_dirs() {
    local name
    for name in "$@"; do
        rm -rf "${TARGET_DIR:?}/$name"
    done
}

# prune NOTE COMMAND...: runs one of the two above and reports what is left.
prune() {
    local note="$1"
    shift
    "$@"
    echo "pruned ${note}: target dir $(disk_report)"
}

run_stage "0 prerequisites" stage_prerequisites
if ((FAILED > 0)); then
    echo "prerequisites missing: no other stage can run" >&2
    exit 1
fi
run_stage "1 cargo fmt --check" stage_fmt
run_stage "2 clippy -D warnings" stage_clippy
run_stage "3 host tests" stage_host_tests
prune "stage 3's test binaries" drop_test_executables "$TARGET_DIR/debug"
prune "stage 3's scratch files (an oversize image build: 150 MB)" drop_dirs tmp
run_stage "4 i586 tests (qemu)" stage_i586_tests
run_stage "5 no_std proof" stage_no_std
prune "stages 4-5's builds" drop_dirs "$I586/debug" "$NO_STD_TARGET"
run_stage "6 agent image (qemu)" stage_image
run_stage "7 footprint gate" stage_footprint
run_stage "8 instruction-set + contents gate" stage_isa
run_stage "9 i586 game (qemu)" stage_i586_game
prune "the i586, image and release builds" drop_dirs "$I586" release image
run_stage "10 team over Zenoh" stage_zenoh_team

echo
echo "==== summary ($(($(date +%s) - total_start)) s in total)"
printf '%s\n' "${SUMMARY[@]}"
echo "stages: ${PASSED} passed, ${FAILED} failed"
((FAILED == 0))
