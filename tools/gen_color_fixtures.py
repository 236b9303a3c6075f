#!/usr/bin/env python3
"""Fixtures for the iridis-color tests, computed with colour-science (an independent implementation).

Writes crates/color/tests/fixtures/colour_science.json:
- the XYZ (Y = 1), xy and CIELAB of the illuminants D65, D50, A, E as emitters, both observers;
- a set of reflectance spectra sampled at 1 nm on 360-830 nm, with XYZ under each illuminant
  (colour.sd_to_XYZ, method "Integration", illuminant interpolated linearly to 1 nm), CIELAB relative to
  the illuminant's white, and linear sRGB (IEC 61966-2-1 matrix, no chromatic adaptation).

Sharma, Wu & Dalal (2005) CIEDE2000 test data are in sharma2005.json (published values, typed in from
Table 1 of the paper; colour-science's own test suite carries the same table).

Usage: python3 tools/gen_color_fixtures.py
"""
import json
import os
import numpy as np
import colour
from colour.algebra import LinearInterpolator

OUT = os.path.join(os.path.dirname(__file__), "..", "crates", "color", "tests", "fixtures")
os.makedirs(OUT, exist_ok=True)
SHAPE = colour.SpectralShape(360, 830, 1)
WL = np.arange(360, 831, 1.0)
OBSERVERS = {"1931": "CIE 1931 2 Degree Standard Observer", "1964": "CIE 1964 10 Degree Standard Observer"}


def illuminant(name):
    if name == "E":
        return colour.SpectralDistribution(np.full(WL.shape, 100.0), WL, name="E")
    if name == "A":
        return colour.sd_CIE_standard_illuminant_A(SHAPE)
    sd = colour.SDS_ILLUMINANTS[name].copy()
    sd.interpolator = LinearInterpolator
    sd.extrapolator_kwargs = {"method": "Constant", "left": None, "right": None}
    return sd.align(SHAPE, interpolator=LinearInterpolator)


rng = np.random.default_rng(20261122)
spectra = []
for k in range(6):  # smooth random reflectances: sums of Gaussian bumps
    v = np.full(WL.shape, 0.05)
    for _ in range(3):
        c, w, a = rng.uniform(400, 700), rng.uniform(15, 80), rng.uniform(0.1, 0.6)
        v += a * np.exp(-0.5 * ((WL - c) / w) ** 2)
    spectra.append(("bumps%d" % k, np.clip(v, 0, 1)))
# Thin-film-like oscillation and a sharp band-pass: hard cases for sampling.
spectra.append(("oscillation", 0.5 + 0.45 * np.cos(2 * np.pi * 2 * 1.33 * 500 / WL)))
spectra.append(("bandpass", np.where((WL > 520) & (WL < 560), 0.9, 0.02)))
spectra.append(("perfect_white", np.ones(WL.shape)))

out = {"generator": "tools/gen_color_fixtures.py", "colour_science": colour.__version__,
       "wavelengths_nm": WL.tolist(), "illuminants": [], "spectra": []}
for obs_key, obs_name in OBSERVERS.items():
    cmfs = colour.MSDS_CMFS[obs_name]
    for ill_name in ["D65", "D50", "A", "E"]:
        ill = illuminant(ill_name)
        xyz_w = colour.sd_to_XYZ(ill, cmfs, method="Integration") / 100.0
        out["illuminants"].append({"observer": obs_key, "illuminant": ill_name,
                                   "XYZ": (xyz_w / xyz_w[1]).tolist(),
                                   "xy": colour.XYZ_to_xy(xyz_w).tolist()})
        for name, values in spectra:
            sd = colour.SpectralDistribution(values, WL, name=name)
            xyz = colour.sd_to_XYZ(sd, cmfs, ill, method="Integration") / 100.0
            white = colour.sd_to_XYZ(colour.SpectralDistribution(np.ones(WL.shape), WL), cmfs, ill,
                                     method="Integration") / 100.0
            lab = colour.XYZ_to_Lab(xyz, colour.XYZ_to_xy(white))
            rgb = colour.XYZ_to_RGB(xyz, colour.RGB_COLOURSPACES["sRGB"], None, None)
            out["spectra"].append({"name": name, "observer": obs_key, "illuminant": ill_name,
                                   "XYZ": xyz.tolist(), "Lab": lab.tolist(), "linear_srgb": rgb.tolist()})
out["spectrum_values"] = {name: values.tolist() for name, values in spectra}
with open(os.path.join(OUT, "colour_science.json"), "w") as f:
    json.dump(out, f, indent=1)
print("wrote", os.path.join(OUT, "colour_science.json"))
