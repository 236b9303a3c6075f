"""ΔE00 between the physical (R once) and paper (R²) Fresnel conventions, displayed as iridis' lab crate does
(XYZ × E → linear sRGB, clipped → XYZ → CIELAB, sRGB/D65 white), computed with colour-science.

Makes the table "The Fresnel factor" of docs/diffraction.md from the maps written by (in DIR, default /tmp/fig):
  for b in blazed cd elaphe xenopeltis; for inc in 0deg 20deg; for c in physical paper:
    iridis brdf-map "builtin:$b?size=32.5um&pixel=65nm" --coherence 8um --method reference --incidence $inc \
        --size 128 --fresnel-convention $c -o ${b}_${inc}_$c.png --raw ${b}_${inc}_$c.npy
Usage: python tools/fresnel_convention_delta_e.py [DIR]   (pip install numpy colour-science)"""
import sys

DIR = sys.argv[1] if len(sys.argv) > 1 else "/tmp/fig"
import numpy as np
import colour

M = np.array([[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]])
Minv = np.linalg.inv(M)
white = Minv @ np.ones(3)
def shown(xyz, e):
    rgb = np.clip((xyz * e) @ M.T, 0, 1)
    return colour.XYZ_to_Lab(rgb @ Minv.T, colour.XYZ_to_xy(white))
for b in ["blazed", "cd", "elaphe", "xenopeltis"]:
    for inc in ["0deg", "20deg"]:
        a = np.load(f"{DIR}/{b}_{inc}_physical.npy")
        p = np.load(f"{DIR}/{b}_{inc}_paper.npy")
        n = a.shape[0]
        yy, xx = np.mgrid[0:n, 0:n]
        x = (2 * xx + 1 - n) / n; y = (n - 2 * yy - 1) / n
        inside = x * x + y * y < 1
        row = [f"| {b} | {inc} |"]
        for e in [1, 1500, 7500]:
            d = colour.delta_E(shown(a, e), shown(p, e), method="CIE 2000")[inside]
            row.append(f" {d.mean():.3f} / {np.percentile(d, 95):.3f} / {d.max():.2f} |")
        print("".join(row))
