#!/usr/bin/env python3
"""The same fit in Python, as a reference for iridis-filmfit: a synthetic noisy reflectance spectrum of a
Cauchy film on an absorbing substrate (3 parameters, 401 wavelengths) fitted by scipy.optimize.least_squares
with the model from the `tmm` package. Writes

  crates/filmfit/tests/fixtures/scipy_fit.csv   the measurement (wavelength_nm, R), seeded noise σ = 0.002
  crates/filmfit/tests/fixtures/scipy_fit.json  scipy's optimum, 1σ from (JᵀJ)⁻¹, χ², its wall time

The Rust test (crates/filmfit/tests/against_scipy.rs) fits the CSV and compares with the JSON; it needs no
Python. With --iridis PATH (the built `iridis` binary) the script also times `iridis thinfilm fit` on the same
file in the same run and prints both times (docs/thinfilm.md).

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install tmm numpy scipy
    /tmp/venv/bin/python tools/fit_scipy_compare.py [--iridis target/release/iridis]
"""
import argparse
import json
import os
import subprocess
import time

import numpy as np
import scipy
import scipy.optimize
import tmm

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIX = os.path.join(ROOT, "crates", "filmfit", "tests", "fixtures")
TRUTH = [1.47, 0.0052, 312.0]          # Cauchy A, B (µm²), thickness (nm)
START = [1.5, 0.004, 330.0]
LO, HI = [1.3, 0.0, 100.0], [1.7, 0.02, 600.0]
SUBSTRATE = complex(3.88, 0.02)
SIGMA = 0.002
WL = np.arange(400.0, 800.0 + 0.5, 1.0)   # 401 wavelengths
STACK = "air | cauchy:{A=1.5:1.3..1.7},{B=0.004:0..0.02} {d=330nm:100nm..600nm} | n=3.88+0.02i"


def model(x):
    a, b, d = x
    out = np.empty(len(WL))
    for i, lam in enumerate(WL):
        n = a + b / (lam / 1000.0) ** 2
        # Normal incidence: s and p are the same, one coh_tmm call per wavelength.
        out[i] = tmm.coh_tmm("s", [1.0, n, SUBSTRATE], [np.inf, d, np.inf], 0.0, lam)["R"]
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--iridis", help="path of the iridis binary, to time it on the same data")
    args = ap.parse_args()
    rng = np.random.default_rng(20261123)
    meas = model(TRUTH) + SIGMA * rng.standard_normal(len(WL))
    csv = os.path.join(FIX, "scipy_fit.csv")
    with open(csv, "w") as f:
        f.write("# tools/fit_scipy_compare.py: air | Cauchy(A=1.47, B=0.0052) 312 nm | n=3.88+0.02i, R at 0°, "
                "noise sigma 0.002\n")
        f.write("wavelength_nm,R\n")
        for w, r in zip(WL, meas):
            f.write(f"{w:.1f},{float(r)!r}\n")

    def residuals(x):
        return (model(x) - meas) / SIGMA

    t0 = time.perf_counter()
    res = scipy.optimize.least_squares(residuals, START, bounds=(LO, HI), method="trf", x_scale="jac",
                                       ftol=1e-12, xtol=1e-12, gtol=1e-12)
    dt = time.perf_counter() - t0
    cov = np.linalg.inv(res.jac.T @ res.jac)
    chi2 = float(np.sum(res.fun ** 2))
    doc = {
        "generator": "tools/fit_scipy_compare.py",
        "reference": f"scipy {scipy.__version__} least_squares (trf, bounds, tol 1e-12), model tmm.coh_tmm, "
                     f"numpy {np.__version__}",
        "stack": STACK,
        "truth": TRUTH,
        "start": START,
        "x": [float(v) for v in res.x],
        "sigma": [float(v) for v in np.sqrt(np.diag(cov))],
        "chi2": chi2,
        "nfev": int(res.nfev),
        "seconds": dt,
    }
    with open(os.path.join(FIX, "scipy_fit.json"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    print(f"scipy: x = {res.x}, sigma = {doc['sigma']}, chi2 = {chi2:.6f}, {res.nfev} evaluations, {dt:.3f} s")
    if args.iridis:
        for grid in ("1", "0"):
            cmd = [args.iridis, "thinfilm", "fit", csv, "--stack", STACK, "--quantity", "R", "--sigma", str(SIGMA),
                   "--grid", grid, "--json"]
            t0 = time.perf_counter()
            out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
            wall = time.perf_counter() - t0
            r = json.loads(out)
            print(f"iridis (--grid {grid}): x = {r['values']}, chi2 = {r['chi2']:.6f}, fit {r['seconds']:.4f} s, "
                  f"process {wall:.3f} s, speed-up (fit) {dt / r['seconds']:.0f}x")


if __name__ == "__main__":
    main()
