#!/usr/bin/env bash
# The README's test command: everything the tests need, then all the tests. Works on a fresh machine: as root
# with apt it installs Mesa's software Vulkan driver (lavapipe) and Xvfb for the GPU and viewer tests, and it
# fetches the real AFM instrument files with pip (into a throw-away venv) for the reader tests.
set -euo pipefail
cd "$(dirname "$0")/.."

# Timings of the steps, so a slow one shows itself (CI is a 2-core machine: the whole command is meant to take at
# most 12 minutes there, build included).
step() { echo "== [${SECONDS}s] $*"; }
LOGS="$(mktemp -d "${TMPDIR:-/tmp}/iridis-test-logs.XXXXXX")"
VENV="$(mktemp -d "${TMPDIR:-/tmp}/iridis-venv.XXXXXX")"
# (Cleanup never decides the exit status: with no background job left, `kill` with no pid fails, and under
# `set -e` that failure would become the script's.)
cleanup() {
    local pids
    pids="$(jobs -p)"
    if [ -n "$pids" ]; then
        # shellcheck disable=SC2086
        kill $pids 2>/dev/null || true
        wait 2>/dev/null || true
    fi
    rm -rf "$VENV" "$LOGS"
}
trap cleanup EXIT

# The Python environment first (quick; on Debian without python3-venv it needs apt-get before the GPU packages'
# install below takes apt's lock).
if ! command -v python3 >/dev/null 2>&1; then
    echo "error: python3 is needed for the Python package's tests (Debian: apt-get install python3 python3-venv)"
    exit 1
fi
if ! python3 -m venv "$VENV" >/dev/null 2>&1; then
    # Debian's python3 comes without ensurepip unless python3-venv is installed.
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        echo "== installing python3-venv"
        apt-get update -qq && apt-get install -y -qq python3-venv >/dev/null
        rm -rf "$VENV" && python3 -m venv "$VENV"
    else
        echo "error: python3 -m venv failed; install python3-venv (Debian/Ubuntu) and run again"
        exit 1
    fi
fi

# The GPU tests (crates/gpu, crates/cli/tests/gpu_cli.rs) need a Vulkan adapter: lavapipe on machines without a
# GPU; the viewer's test runs the window under a virtual X server (Xvfb), and winit loads the X11 and
# xkbcommon libraries at run time. Installed in the background while cargo compiles.
PACKAGES="mesa-vulkan-drivers xvfb xauth libxkbcommon-x11-0 libx11-xcb1 libxcursor1 libxi6 libxrandr2"
install_gpu_packages() {
    if ! ls /usr/share/vulkan/icd.d/*.json >/dev/null 2>&1 || ! command -v xvfb-run >/dev/null 2>&1; then
        if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
            echo "== installing $PACKAGES"
            # shellcheck disable=SC2086
            { apt-get update -qq && apt-get install -y -qq $PACKAGES >/dev/null; } ||
                echo "warning: could not install $PACKAGES; the GPU tests will fail (IRIDIS_SKIP_GPU=1 skips them)"
        else
            echo "warning: no Vulkan driver or no xvfb-run, and not root: install $PACKAGES (Debian/Ubuntu), or set"
            echo "         IRIDIS_SKIP_GPU=1 to skip the GPU tests"
        fi
    fi
}
install_gpu_packages >"$LOGS/apt.log" 2>&1 &
APT_JOB=$!

# Downloads run in the background while cargo compiles (they wait on the network, the build on the CPU): the
# Python test dependencies, and the real AFM instrument files for the reader tests (AFMReader 0.0.7's test
# resources, ~150 MB, fetched with pip into target/afm-samples, never committed; without PyPI the tests say they
# skipped and pass).
"$VENV/bin/pip" install -q --disable-pip-version-check maturin numpy pytest tmm scipy "dask[distributed]" \
    >"$LOGS/pip.log" 2>&1 &
PIP_JOB=$!
bash tools/fetch_afm_samples.sh >"$LOGS/afm.log" 2>&1 &
AFM_JOB=$!

# On a CPU with AVX2 and FMA (x86-64-v3: every x86 server and desktop CPU since 2013–2015), compile for it: the
# numeric loops that the compiler vectorises (the ground truth's sums, the windowed spectra) use 256-bit
# registers instead of 128-bit ones. The numbers are the same: Rust never fuses a multiply and an add unless the
# code asks (`mul_add`), vectorised loops keep each sum's order, and the maths library and the SIMD crates (faer,
# rustfft) choose their code at run time either way. Measured on the 2-core VM (2026-11-27), the same 1 092 `iridis`
# processes of the CLI's tests: 402 CPU-s from the default build, 370 from this one, their outputs the same
# (every test passes; sweep, brdf eval, thinfilm color JSON and render EXR compared byte for byte). A RUSTFLAGS
# of your own is left alone; `IRIDIS_BASELINE_CPU=1` tests the default build (what `cargo build --release` makes).
v3_flags="avx avx2 bmi1 bmi2 f16c fma abm movbe xsave"
has_v3() {
    [ "$(uname -m)" = x86_64 ] && [ -r /proc/cpuinfo ] || return 1
    local f
    for f in $v3_flags; do grep -qw "$f" /proc/cpuinfo || return 1; done
}
if [ -z "${RUSTFLAGS+set}" ] && [ "${IRIDIS_BASELINE_CPU:-0}" != 1 ] && has_v3; then
    export RUSTFLAGS="-C target-cpu=x86-64-v3"
    echo "== compiling for x86-64-v3 (AVX2, FMA: this CPU has them; IRIDIS_BASELINE_CPU=1 for the default target)"
fi

# The test harnesses (each crate's integration tests, the CLI's unit tests) compiled without optimisation; the
# libraries and dependencies they test keep the `ci` profile. Cargo has no opt-level per target, so a wrapper
# (tools/rustc-tests-unoptimised.sh, which says why the numbers are the same) adds it to the harnesses' rustc
# commands. Measured on the 2-core VM (2026-11-27), the 14 harnesses: 173 CPU-s to compile at opt-level 3, 30
# at 0; their run times the same within the VM's noise (render 47.7 -> 44.9 CPU-s, GPU 155 -> 135,
# diffraction 63 -> 47, thinfilm 21.8 -> 20.3). A RUSTC_WORKSPACE_WRAPPER of your own is left alone.
if [ -z "${RUSTC_WORKSPACE_WRAPPER:-}" ]; then
    export RUSTC_WORKSPACE_WRAPPER="$PWD/tools/rustc-tests-unoptimised.sh"
fi

# Mesa's shader cache in a folder we know is writable (CI may run with a read-only or missing home): lavapipe
# compiles the scene renderer once (about 40 s of one core; docs/gpu.md) and every later test process and CLI run
# that opens the same pipeline loads it from here in seconds. Without the cache each of them compiled it again.
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-${CARGO_TARGET_DIR:-$PWD/target}/mesa-shader-cache}"
export MESA_SHADER_CACHE_DISABLE=false
mkdir -p "$MESA_SHADER_CACHE_DIR"

# The `ci` profile (Cargo.toml): release for our crates and the numeric dependencies, no optimisation for the
# viewer's window stack, the GPU API layer and small-file parsers, whose compile time was a third of a fresh
# build's and whose speed no test needs.
# The targets that hold tests: `--tests` is every target with `test = true`, i.e. the libraries' and binaries'
# unit tests and the integration tests (crates/*/tests/main.rs, one binary a crate). Not `--lib --bins`: naming
# a target kind overrides its `test = false`, and built the Python binding's empty test harness (no tests, 10-18
# s of compile). Examples are not built here (clippy --all-targets in .ci/run checks that they compile); doc tests run
# with the tests below.
TARGETS=(--tests)
step "cargo test --workspace --profile ci: build"
# JSON on stdout names every test executable and its package; the compiler's messages still go to the terminal.
cargo test --workspace --profile ci "${TARGETS[@]}" --no-run --message-format=json-render-diagnostics >"$LOGS/build.json"

wait "$APT_JOB" || true
cat "$LOGS/apt.log"
echo "== AFM sample files (tools/fetch_afm_samples.sh)"
if ! wait "$AFM_JOB"; then
    echo "warning: could not fetch the AFM sample files; the real-file reader tests will be skipped"
fi
cat "$LOGS/afm.log"
if ! wait "$PIP_JOB"; then
    cat "$LOGS/pip.log"
    echo "error: could not install the Python test dependencies (maturin numpy pytest tmm scipy dask)"
    exit 1
fi

# The tests: every test executable (each crate's integration binary, thinfilm's and the CLI's unit tests), the
# doc tests and the Python package, two at a time. `cargo test` would run the executables one after another, and
# one binary alone leaves a core idle whenever its last tests run (the CLI's help examples are one test of ~60 s;
# the GPU tests take turns on the scene pipeline): measured on the 2-core VM (2026-11-27), the binaries alone
# took 328 s for 557 CPU-s. Each executable runs as `cargo test` runs it: from its package's folder, with the
# default two test threads; a line says when each job starts, and its output is printed whole when it ends.
# The order (measured): the CLI's binary first (the longest, 165 s alone), the others beside it. The GPU crate's
# starts after the Python package, when the CLI's GPU tests have put the scene pipeline in Mesa's cache: started
# together, both processes compiled it, and the pair took as long as the two one after the other; started last,
# it ran alone for a minute. The CLI's and the Python package's GPU tests take turns at the scene shader through
# a file lock in Mesa's cache folder (crates/cli/tests/gpu_cli.rs, `scene_shader_turn`), so that one of them
# compiles it and the other loads it.
JOB_NAMES=()
JOB_COMMANDS=()
add_job() { JOB_NAMES+=("$1"); JOB_COMMANDS+=("$2"); }
python3 - "$LOGS/build.json" "$PWD" >"$LOGS/executables.txt" <<'PY'
import json, os, sys
order = ["crates/cli integration", "python", "crates/gpu integration", "crates/render integration",
         "crates/diffraction integration", "crates/thinfilm integration", "crates/api integration"]
rows = [("python", "", "")]
for line in open(sys.argv[1]):
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m.get("executable") and m["profile"]["test"]:
        folder = os.path.dirname(m["manifest_path"])
        rows.append((f"{os.path.relpath(folder, sys.argv[2])} {m['target']['name']}", folder, m["executable"]))
rank = lambda row: order.index(row[0]) if row[0] in order else len(order)
for row in sorted(rows, key=rank):
    print(*row, sep="\t")
PY
while IFS=$'\t' read -r name folder exe; do
    if [ "$name" = python ]; then
        # The package built and installed the way the README tells users to (`pip install ./crates/python`), into
        # the throw-away venv, then its tests (pytest: the tmm drop-in against tmm and the committed fixtures,
        # colours, films, the README's example, the Dask example on a two-worker local cluster). The build reuses
        # cargo's target directory and the test build's compiled crates: the same profile, and the feature
        # `test-build` (crates/python/Cargo.toml) gives the shared dependencies the features `cargo test
        # --workspace` gave them, so only the binding crate and pyo3 compile anew. The build's time and pytest's
        # eight slowest tests are printed, so that a slow one shows itself.
        add_job "Python package (pip install ./crates/python, pytest)" \
            "CARGO_TARGET_DIR='${CARGO_TARGET_DIR:-$PWD/target}' MATURIN_PEP517_ARGS='--profile ci --features test-build' \
             '$VENV/bin/pip' install -q --disable-pip-version-check ./crates/python && \
             echo \"(built and installed in \${SECONDS} s)\" && \
             cd crates/python && '$VENV/bin/python' -m pytest -q --durations=8 tests"
    else
        add_job "$name" "cd '$folder' && '$exe'"
    fi
done <"$LOGS/executables.txt"
if [ "${#JOB_NAMES[@]}" -lt 4 ]; then
    echo "error: cargo named $((${#JOB_NAMES[@]} - 1)) test executables; expected one a crate or more"
    exit 1
fi
add_job "doc tests (cargo test --workspace --profile ci --doc)" "cargo test --workspace --profile ci --doc"

step "tests: ${#JOB_NAMES[@]} jobs, two at a time"
run_job() {
    local k=$1 t0 rc=0
    t0=$(date +%s)
    bash -c "${JOB_COMMANDS[$k]}" >"$LOGS/job$k.log" 2>&1 || rc=$?
    echo "$rc $(($(date +%s) - t0))" >"$LOGS/job$k.rc"
}
FAILED=()
next=0
shown=0
declare -A SHOWN=()
while [ "$shown" -lt "${#JOB_NAMES[@]}" ]; do
    while [ "$next" -lt "${#JOB_NAMES[@]}" ] && [ $((next - shown)) -lt 2 ]; do
        echo "== [${SECONDS}s] started: ${JOB_NAMES[$next]}"
        run_job "$next" &
        next=$((next + 1))
    done
    wait -n || true
    for ((k = 0; k < next; k++)); do
        if [ -z "${SHOWN[$k]:-}" ] && [ -f "$LOGS/job$k.rc" ]; then
            SHOWN[$k]=1
            shown=$((shown + 1))
            read -r rc secs <"$LOGS/job$k.rc"
            if [ "$rc" = 0 ]; then verdict=ok; else verdict="FAILED (exit status $rc)"; FAILED+=("${JOB_NAMES[$k]}"); fi
            echo "== [${SECONDS}s] ${JOB_NAMES[$k]}: $verdict in ${secs} s"
            cat "$LOGS/job$k.log"
        fi
    done
done
if [ "${#FAILED[@]}" -gt 0 ]; then
    echo "== [${SECONDS}s] failed: ${FAILED[*]}"
    exit 1
fi
step "done"
