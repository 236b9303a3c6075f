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
# at the end of the Rust step.
TARGETS=(--tests)
step "cargo test --workspace --profile ci: build"
cargo test --workspace --profile ci "${TARGETS[@]}" --no-run

wait "$APT_JOB" || true
cat "$LOGS/apt.log"
echo "== AFM sample files (tools/fetch_afm_samples.sh)"
if ! wait "$AFM_JOB"; then
    echo "warning: could not fetch the AFM sample files; the real-file reader tests will be skipped"
fi
cat "$LOGS/afm.log"

step "cargo test --workspace --profile ci: run"
cargo test --workspace --profile ci "${TARGETS[@]}" --no-fail-fast
step "cargo test --workspace --profile ci --doc"
cargo test --workspace --profile ci --doc

# The Python package (crates/python), built and installed the way the README tells users to
# (`pip install ./crates/python`), into a throw-away virtual environment, then its tests (pytest: the tmm drop-in
# against tmm and the committed fixtures, colours, films, the README's example, the Dask example on a two-worker
# local cluster). The build reuses cargo's target directory and the test build's compiled crates: the same
# profile, and the feature `test-build` (crates/python/Cargo.toml) gives the shared dependencies the features
# `cargo test --workspace` gave them, so only the binding crate and pyo3 compile anew.
step "Python package: pip install ./crates/python into a throw-away venv, then pytest"
if ! wait "$PIP_JOB"; then
    cat "$LOGS/pip.log"
    echo "error: could not install the Python test dependencies (maturin numpy pytest tmm scipy dask)"
    exit 1
fi
CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target}" MATURIN_PEP517_ARGS="--profile ci --features test-build" \
    "$VENV/bin/pip" install -q --disable-pip-version-check ./crates/python
(cd crates/python && "$VENV/bin/python" -m pytest -q tests)
step "done"
