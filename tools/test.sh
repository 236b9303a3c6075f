#!/usr/bin/env bash
# The README's test command: everything the tests need, then all the tests. Works on a fresh machine: as root
# with apt it installs Mesa's software Vulkan driver (lavapipe) and Xvfb for the GPU and viewer tests, and it
# fetches the real AFM instrument files with pip (into a throw-away venv) for the reader tests.
set -euo pipefail
cd "$(dirname "$0")/.."

# The GPU tests (crates/gpu, crates/cli/tests/gpu_cli.rs) need a Vulkan adapter: lavapipe on machines without a
# GPU; the viewer's test runs the window under a virtual X server (Xvfb), and winit loads the X11 and
# xkbcommon libraries at run time.
PACKAGES="mesa-vulkan-drivers xvfb xauth libxkbcommon-x11-0 libx11-xcb1 libxcursor1 libxi6 libxrandr2"
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

# Real AFM instrument files for the reader tests (AFMReader 0.0.7's test resources, ~150 MB, fetched with pip
# into target/afm-samples, never committed). Without PyPI the tests say they skipped and pass.
echo "== AFM sample files (tools/fetch_afm_samples.sh)"
if command -v python3 >/dev/null 2>&1; then
    bash tools/fetch_afm_samples.sh ||
        echo "warning: could not fetch the AFM sample files; the real-file reader tests will be skipped"
else
    echo "warning: no python3; the real-file reader tests will be skipped"
fi

echo "== cargo test --workspace --release"
cargo test --workspace --release
