#!/usr/bin/env bash
# The README's test command (tools/test.sh) compiles the workspace through this wrapper
# (RUSTC_WORKSPACE_WRAPPER: cargo runs it instead of rustc for the workspace's own crates, with rustc's path
# first). It compiles the integration-test harnesses and the CLI's unit tests without optimisation; every
# library, and every dependency, keeps its profile (`ci`: optimised).
#
# Why: cargo has no opt-level per target, only per package, and a test harness at opt-level 3 is mostly LLVM
# optimising assertion code and the generic library code it instantiates, which runs for milliseconds. The
# heavy work the tests check runs inside the libraries, which stay optimised. Floating-point results do not
# depend on the optimisation level (Rust never reassociates or fuses unless the code asks), and debug
# assertions and overflow checks stay off as in the profile, so the tests assert the same numbers.
# thinfilm's unit tests (`src/`, compiled with the library they test: its solver runs in that harness) get
# opt-level 1: measured on the 2-core VM (2026-11-28), that harness took 20 CPU-s to compile at 3 and 12.5 at 1,
# and its 75 tests ran in the same 2.7 s.
set -euo pipefail
rustc="$1"
shift
test_harness=0
crate=""
prev=""
for arg in "$@"; do
    [ "$arg" = --test ] && test_harness=1
    [ "$prev" = --crate-name ] && crate="$arg"
    prev="$arg"
done
if [ "$test_harness" = 1 ]; then
    level=0
    [ "$crate" = iridis_thinfilm ] && level=1
    exec "$rustc" "$@" -C opt-level=$level -C debug-assertions=off -C overflow-checks=off
fi
exec "$rustc" "$@"
