#!/usr/bin/env bash
# Fetches real AFM instrument files for the reader tests (crates/surface/tests/afm_instruments.rs).
#
# AFMReader 0.0.7 (TopoStats, University of Sheffield; LGPL-3) ships real scans in its source distribution's
# tests/resources: Bruker .spm, Asylum .ibw, JPK .jpk, Gwyddion .gwy, WSxM .stp/.top. They are ~150 MB and
# not ours to redistribute, so they are fetched with pip into a cache outside git, never committed:
#   $IRIDIS_AFM_SAMPLES, default target/afm-samples (under the repository root).
# A Gwyddion Simple Field sample is then written from the real .stp scan by gsffile (Carlo Dri and
# Angelo Peronio's reader/writer of .gsf on PyPI), an implementation independent of iridis.
#
# Usage: tools/fetch_afm_samples.sh        (idempotent: does nothing when the files are there)
set -euo pipefail
cd "$(dirname "$0")/.."
DEST="${IRIDIS_AFM_SAMPLES:-target/afm-samples}"
SDIST_SHA256=44b40cf188e054915f8b71ec62eee643fe372c4062d77ab548382ae39c01ff1d
PY="${PYTHON:-python3}"
if [ -f "$DEST/sample_0.spm" ] && [ -f "$DEST/sample_0.gsf" ]; then
    echo "AFM samples present in $DEST"
    exit 0
fi
mkdir -p "$DEST"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
"$PY" -m venv "$WORK/venv"
PIP="$WORK/venv/bin/pip"
# --no-binary for AFMReader only: its build requirements may come as wheels.
"$PIP" download --quiet AFMReader==0.0.7 --no-deps --no-binary afmreader -d "$WORK/dl"
SDIST="$WORK/dl/afmreader-0.0.7.tar.gz"
echo "$SDIST_SHA256  $SDIST" | sha256sum -c --quiet -
tar -xzf "$SDIST" -C "$WORK" afmreader-0.0.7/tests/resources
for ext in spm ibw jpk gwy stp top; do cp "$WORK/afmreader-0.0.7/tests/resources/sample_0.$ext" "$DEST"/; done
cp "$WORK"/afmreader-0.0.7/tests/resources/sample_1_um_scale.* "$DEST"/
"$PIP" install --quiet gsffile==0.5.5 numpy
"$WORK/venv/bin/python" - "$DEST" <<'PYEOF'
"""Writes sample_0.gsf with gsffile from the doubles (nm) of the real WSxM scan sample_0.stp."""
import re
import sys
from pathlib import Path

import gsffile
import numpy as np

dest = Path(sys.argv[1])
raw = (dest / "sample_0.stp").read_bytes()
head = raw[:200].decode("latin-1")
size = int(re.search(r"Image header size: (\d+)", head).group(1))
header = raw[:size].decode("latin-1")
rows = int(re.search(r"Number of rows: (\d+)", header).group(1))
cols = int(re.search(r"Number of columns: (\d+)", header).group(1))
x_nm = float(re.search(r"X Amplitude: ([\d.]+) nm", header).group(1))
y_nm = float(re.search(r"Y Amplitude: ([\d.]+) nm", header).group(1))
data = np.frombuffer(raw, dtype="<f8", count=rows * cols, offset=size).reshape(rows, cols)
gsffile.write_gsf(
    dest / "sample_0.gsf",
    (data * 1e-9).astype(np.float32),
    {
        "XReal": x_nm * 1e-9,
        "YReal": y_nm * 1e-9,
        "XYUnits": "m",
        "ZUnits": "m",
        "Title": "Topography (sample_0.stp, written by gsffile)",
    },
)
print(f"wrote {dest / 'sample_0.gsf'} ({rows} x {cols}) with gsffile")
PYEOF
echo "AFM samples in $DEST:"
ls -l "$DEST"
