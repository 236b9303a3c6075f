#!/usr/bin/env bash
# CPU seconds (user + sys, the test process and every process it starts) of each Rust test binary of the test
# command's build, slowest first: what a 2-core CI spends, independent of how loaded the machine is. Run after
# `bash tools/test.sh` (or `cargo test --workspace --profile ci --tests --no-run`) with the same environment; each binary
# runs from its package's folder as cargo runs it. Note: the first binary to open the GPU scene renderer pays
# lavapipe's cold compile unless MESA_SHADER_CACHE_DIR holds it.
#
# Usage: tools/test_cpu_times.sh [--test-threads=N]
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT="$PWD"
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-${CARGO_TARGET_DIR:-$ROOT/target}/mesa-shader-cache}"
export MESA_SHADER_CACHE_DISABLE=false
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
# (binary, package folder) of every test target, from cargo's own list.
cargo test --workspace --profile ci --tests --no-run --message-format=json 2>/dev/null |
    python3 -c '
import json, os, sys
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m.get("executable") and m["profile"]["test"]:
        print(m["executable"], os.path.dirname(m["manifest_path"]))
' >"$OUT/list"
total=0
while read -r exe dir; do
    /usr/bin/time -f "%U %S" -o "$OUT/t" bash -c 'cd "$1" && shift && exec "$@"' _ "$dir" "$exe" "$@" \
        >"$OUT/log" 2>&1 && rc=0 || rc=$?
    read -r u s <"$OUT/t"
    awk -v u="$u" -v s="$s" -v rc="$rc" -v n="$(basename "$exe")" 'BEGIN {printf "%8.1f  rc=%d  %s\n", u + s, rc, n}' |
        tee -a "$OUT/times"
done <"$OUT/list"
echo "== slowest first (CPU s)"
sort -rn "$OUT/times"
awk '{s += $1} END {printf "%8.1f  total\n", s}' "$OUT/times"
