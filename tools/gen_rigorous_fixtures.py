#!/usr/bin/env python3
"""Reference efficiencies of sine gratings from grcwa (an independent RCWA package, PyPI) for iridis-rigorous.

Writes crates/rigorous/tests/fixtures/grcwa_sine.json. Usage (a venv under /tmp, numpy and grcwa from PyPI):

    python3 -m venv /tmp/rcwa-venv && /tmp/rcwa-venv/bin/pip install numpy grcwa==0.1.2
    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 /tmp/rcwa-venv/bin/python tools/gen_rigorous_fixtures.py

The surface h(x) = a sin(2πx/Λ) on the substrate is cut into `slices` lamellar layers (staircase, each slice
at its mid-height) between z = −a and z = a; grcwa (Jin et al.) solves them with `nG` Fourier orders (Laurent's
rule for ε, the inverse rule for 1/ε_z: no normal-vector factorisation). Each case is run at two resolutions,
(41 orders, 40 slices) and (81 orders, 80 slices); the change between them is grcwa's own convergence estimate,
stored with the values: the tests compare with the finer run only where that change is small (dielectrics, TE
on metal). TM on metal is recorded as well, to document that staircase RCWA does not converge there.

Conventions translated to grcwa's: grcwa's (θ, φ) give the incident wave's direction of travel, iridis' ω_i
points towards the light, so φ_grcwa = φ_i + 180°; grcwa's order G = (m, n) is then iridis' order (m, n)
(k_xy = k_inc,xy + m 2π/Λ). grcwa's s excitation is TE (checked here against Fresnel on a flat surface).
"""
import json
import os
import sys
import time

import numpy as np
import grcwa

grcwa.set_backend("numpy")
PERIOD = 1000.0
NX = 2048
HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "crates", "rigorous", "tests", "fixtures", "grcwa_sine.json")


# grcwa's plane-wave amplitudes and phases (p, p phase, s, s phase) of TE (s) and TM (p) light.
PLANE_WAVE = {"te": (0, 0, 1, 0), "tm": (1, 0, 0, 0)}


def grcwa_sine(eps_sub, lam, theta_deg, phi_deg, amp, n_orders, slices, pol):
    """Reflected (and transmitted) efficiencies by order m of the 1-D sine grating; orders along x only (the
    second lattice vector is made tiny so the circular truncation keeps G2 = 0)."""
    obj = grcwa.obj(n_orders, [PERIOD, 0], [0, PERIOD * 1e-3], 1.0 / lam, np.radians(theta_deg),
                    np.radians(phi_deg + 180.0), verbose=0)
    obj.Add_LayerUniform(0, 1.0)
    for _ in range(slices):
        obj.Add_LayerGrid(2 * amp / slices, NX, 1)
    obj.Add_LayerUniform(0, eps_sub)
    obj.Init_Setup(Gmethod=0)
    x = np.arange(NX) * PERIOD / NX
    h = amp * np.sin(2 * np.pi * x / PERIOD)
    grids = [np.where(h > amp - (j + 0.5) * 2 * amp / slices, eps_sub, 1.0 + 0j) for j in range(slices)]
    if slices:
        obj.GridLayer_geteps(np.concatenate(grids))
    obj.MakeExcitationPlanewave(*PLANE_WAVE[pol], order=0)
    R, T = obj.RT_Solve(normalize=1, byorder=1)
    refl, trans = {}, {}
    for i, g in enumerate(obj.G):
        if g[1] != 0:
            continue
        m = int(g[0])
        kx = -np.sin(np.radians(theta_deg)) * np.cos(np.radians(phi_deg)) + m * lam / PERIOD
        ky = -np.sin(np.radians(theta_deg)) * np.sin(np.radians(phi_deg))
        if kx * kx + ky * ky < 1.0:
            refl[m] = float(R[i])
        if np.real(eps_sub) > 0 and np.imag(eps_sub) == 0 and kx * kx + ky * ky < np.real(eps_sub):
            trans[m] = float(T[i])
    return refl, trans


def check_fresnel():
    n2 = 1.5
    th = np.radians(30.0)
    c2 = np.sqrt(1 - (np.sin(th) / n2) ** 2)
    rs = ((np.cos(th) - n2 * c2) / (np.cos(th) + n2 * c2)) ** 2
    rp = ((n2 * np.cos(th) - c2) / (n2 * np.cos(th) + c2)) ** 2
    for pol, want in (("te", rs), ("tm", rp)):
        r, _ = grcwa_sine(n2 ** 2, 550.0, 30.0, 0.0, 0.0, 5, 0, pol)
        assert abs(r[0] - want) < 1e-9, (pol, r[0], want)


def main():
    check_fresnel()
    media = {"glass": 2.25 + 0j, "metal": -20 + 1j}
    runs = [(41, 40), (81, 80)]
    cases = []
    for material, eps in media.items():
        for ratio in (0.05, 0.10, 0.15):
            for lam in (450.0, 550.0, 650.0):
                for theta in (0.0, 30.0):
                    cases.append((material, eps, ratio, lam, theta, 0.0))
    # Conical incidence on one grating per medium.
    for material, eps in media.items():
        cases.append((material, eps, 0.10, 550.0, 30.0, 45.0))
    out = []
    for (material, eps, ratio, lam, theta, phi) in cases:
        for pol in ("te", "tm"):
            entry = {
                "material": material,
                "eps": [eps.real, eps.imag],
                "period_nm": PERIOD,
                "amplitude_nm": ratio * PERIOD,
                "wavelength_nm": lam,
                "theta_deg": theta,
                "phi_deg": phi,
                "pol": pol,
                "runs": [],
            }
            for n_orders, slices in runs:
                t = time.time()
                refl, trans = grcwa_sine(eps, lam, theta, phi, ratio * PERIOD, n_orders, slices, pol)
                entry["runs"].append({
                    "orders": n_orders,
                    "slices": slices,
                    "seconds": round(time.time() - t, 3),
                    "reflected": {str(m): v for m, v in sorted(refl.items())},
                    "transmitted": {str(m): v for m, v in sorted(trans.items())},
                })
            out.append(entry)
            print(material, ratio, lam, theta, phi, pol, entry["runs"][-1]["reflected"], file=sys.stderr)
    doc = {
        "source": "grcwa 0.1.2 (PyPI), staircase RCWA; tools/gen_rigorous_fixtures.py",
        "grid_points_per_period": NX,
        "cases": out,
    }
    with open(OUT, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
