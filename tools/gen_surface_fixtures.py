#!/usr/bin/env python3
"""Writes the height-field fixtures for crates/surface/tests with independent writers:
Gwyddion files by the `gwyfile` package, .npy and .npz files by numpy (`np.save`, `np.savez`,
`np.savez_compressed`). Expected values go to expected.json.

Regenerate: pip install gwyfile numpy && python3 tools/gen_surface_fixtures.py
"""
import json
import os

import gwyfile
import numpy as np
from gwyfile.objects import GwyContainer, GwyDataField

OUT = os.path.join(os.path.dirname(__file__), "..", "crates", "surface", "tests", "fixtures")
os.makedirs(OUT, exist_ok=True)

rows, cols = 48, 64
dx_nm, dy_nm = 100.0, 80.0  # non-square pixels catch an x/y swap
x = np.arange(cols) * dx_nm
y = (rows - 1 - np.arange(rows)) * dy_nm  # y up, row 0 at the top
X, Y = np.meshgrid(x, y)
# A sine grating of period 800 nm along x, 25 nm amplitude, plus a tilt along y (for levelling).
h_nm = 25.0 * np.sin(2 * np.pi * X / 800.0) + 0.01 * Y
# Second channel: a grating along y with period 640 nm, stored in micrometres.
h2_nm = 40.0 * np.cos(2 * np.pi * Y / 640.0)

c = GwyContainer()
c["/0/data"] = GwyDataField(h_nm * 1e-9, xreal=cols * dx_nm * 1e-9, yreal=rows * dy_nm * 1e-9,
                            si_unit_xy="m", si_unit_z="m")
c["/0/data/title"] = "Height"
c["/1/data"] = GwyDataField(h2_nm * 1e-3, xreal=cols * dx_nm * 1e-3, yreal=rows * dy_nm * 1e-3,
                            si_unit_xy="um", si_unit_z="um")
c["/1/data/title"] = "Height (um)"
c.tofile(os.path.join(OUT, "gwyfile_two_channels.gwy"))

# A data field without units (Gwyddion then treats values as unitless): iridis assumes metres and warns.
c2 = GwyContainer()
c2["/0/data"] = GwyDataField(h_nm * 1e-9, xreal=cols * dx_nm * 1e-9, yreal=rows * dy_nm * 1e-9)
c2.tofile(os.path.join(OUT, "gwyfile_no_units.gwy"))

np.save(os.path.join(OUT, "numpy_f64.npy"), h_nm.astype("<f8"))
np.save(os.path.join(OUT, "numpy_f32_fortran.npy"), np.asfortranarray(h_nm.astype("<f4")))
np.save(os.path.join(OUT, "numpy_f64_bigendian.npy"), h_nm.astype(">f8"))
with open(os.path.join(OUT, "numpy_f64.npy.json"), "w") as f:
    json.dump({"pixel_size_nm": [dx_nm, dy_nm], "height_unit": "nm"}, f)

# .npz archives as numpy writes them. savez (stored): one 2-D array and a 1-D axis, which is not a height
# field, so the 2-D one is picked without --channel; a sidecar gives the units.
np.savez(os.path.join(OUT, "numpy_savez.npz"), x_nm=x, heights=h_nm)
with open(os.path.join(OUT, "numpy_savez.npz.json"), "w") as f:
    json.dump({"pixel_size_nm": [dx_nm, dy_nm], "height_unit": "nm"}, f)
# savez_compressed (deflated): two 2-D arrays, so --channel must choose; in name order "amplitude" (the
# second grating, as float32) is 0 and "height" is 1; plus 1-D axes and a scalar, which are not candidates.
np.savez_compressed(os.path.join(OUT, "numpy_savez_compressed.npz"), height=h_nm, amplitude=h2_nm.astype("<f4"),
                    x_nm=x, y_nm=y, scale=np.float64(1.0))

expected = {
    "rows": rows, "cols": cols, "dx_nm": dx_nm, "dy_nm": dy_nm,
    "sum_nm": float(h_nm.sum()), "sum_sq_nm2": float((h_nm ** 2).sum()),
    "height_min_nm": float(h_nm.min()), "height_max_nm": float(h_nm.max()), "rms_nm": float(h_nm.std()),
    "probe": [[r, cc, float(h_nm[r, cc])] for r, cc in [(0, 0), (0, 5), (7, 3), (47, 63), (20, 41)]],
    "channel1_probe": [[r, cc, float(h2_nm[r, cc])] for r, cc in [(0, 0), (3, 9), (47, 63)]],
    "period_x_nm": 800.0, "period_y_nm": 640.0,
    "npz_2d_arrays": {"numpy_savez.npz": ["heights"], "numpy_savez_compressed.npz": ["amplitude", "height"]},
}
with open(os.path.join(OUT, "expected.json"), "w") as f:
    json.dump(expected, f, indent=1)
print("wrote fixtures to", os.path.normpath(OUT))
