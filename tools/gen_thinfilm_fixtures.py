#!/usr/bin/env python3
"""Reference values for iridis-thinfilm from an independent transfer-matrix code, the `tmm` package
(S. J. Byrnes, https://pypi.org/project/tmm/, MIT licence), written to
crates/thinfilm/tests/fixtures/tmm_reference.json. The Rust tests read that file; they do not need Python.

    pip install tmm numpy
    python3 tools/gen_thinfilm_fixtures.py

Cases:
  * "random": random stacks of 1-20 layers with constant indices — dielectric (κ = 0) and absorbing
    (κ up to 2 in the layers, up to 4 in the substrate), incident media of n = 1-1.8 (so total internal
    reflection occurs), angles over 0°-90°, s and p. Absorption is kept below tmm's own clamp
    (|Im δ| < 35 per layer, where tmm warns and changes the answer).
  * "tir": dense incident media, lossless layers and a rarer substrate beyond its critical angle.
  * "seed": the stacks of Sussenbach section 5.1 (soap films of 348 nm and 635 nm, the oil slick, Si 108 nm
    on glass with the Aspnes & Studna data in data/materials/si_aspnes.yml, interpolated linearly with
    numpy.interp) at 1°, 400-700 nm.
Each case stores tmm's complex r and t and its R and T for s and p. For an absorbing substrate tmm's T is the
power entering the substrate; iridis reports 0 there (docs/PHYSICS.md), so the tests compare R only.
"""
import math
import os
import random
import sys

import numpy as np
import tmm

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gen_incoherent_fixtures import write_compact  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "crates", "thinfilm", "tests", "fixtures", "tmm_reference.json")


def run(n_list, d_list, th0, lam):
    out = {}
    for pol in ("s", "p"):
        res = tmm.coh_tmm(pol, n_list, d_list, th0, lam)
        out[pol] = {
            "r": [float(np.real(res["r"])), float(np.imag(res["r"]))],
            "t": [float(np.real(res["t"])), float(np.imag(res["t"]))],
            "R": float(res["R"]),
            "T": float(res["T"]),
        }
    return out


def fmt_index(n):
    n = complex(n)
    return f"n={n.real!r}" if n.imag == 0 else f"n={n.real!r}+{n.imag!r}i"


def stack_string(n_list, d_list):
    parts = [fmt_index(n_list[0])]
    for n, d in zip(n_list[1:-1], d_list[1:-1]):
        parts.append(f"{fmt_index(n)} {float(d)!r}nm")
    parts.append(fmt_index(n_list[-1]))
    return " | ".join(parts)


def max_im_delta(n_list, d_list, th0, lam):
    worst = 0.0
    for n, d in zip(n_list[1:-1], d_list[1:-1]):
        sx = n_list[0] * math.sin(th0) / complex(n)
        c = np.sqrt(1 - sx * sx)
        worst = max(worst, abs((2 * math.pi / lam * complex(n) * c * d).imag))
    return worst


def case(kind, ns, ds, layers, absorbing_substrate, lam, th0):
    """One case: the stack as iridis reads it and tmm's answers."""
    return {
        "kind": kind,
        "stack": stack_string(ns, ds),
        "layers": layers,
        "absorbing_substrate": absorbing_substrate,
        "wavelength_nm": lam,
        "angle_rad": th0,
        **run(ns, ds, th0, lam),
    }


def random_cases(rng, count):
    cases = []
    while len(cases) < count:
        layers = rng.randint(1, 20)
        absorbing = rng.random() < 0.5
        n0 = rng.choice([1.0, 1.0, 1.33, rng.uniform(1.0, 1.8)])
        ns = [complex(n0, 0.0)]
        ds = [np.inf]
        for _ in range(layers):
            n = rng.uniform(1.0, 3.0)
            k = rng.uniform(0.0, 2.0) if absorbing and rng.random() < 0.5 else 0.0
            ns.append(complex(n, k))
            ds.append(rng.uniform(0.0, 400.0) if not k else rng.uniform(0.0, 60.0))
        sub_k = rng.uniform(0.0, 4.0) if absorbing and rng.random() < 0.5 else 0.0
        ns.append(complex(rng.uniform(1.0, 2.5) if sub_k == 0 else rng.uniform(0.1, 3.0), sub_k))
        ds.append(np.inf)
        lam = rng.uniform(380.0, 780.0)
        th0 = rng.choice([0.0, math.pi / 2 * rng.random(), math.pi / 2 * rng.random(), math.radians(89.9)])
        if max_im_delta(ns, ds, th0, lam) > 30:
            continue
        cases.append(case("random", ns, ds, layers, sub_k > 0, lam, th0))
    return cases


def tir_cases(rng, count):
    """Dense incident medium, lossless layers, a less dense substrate, beyond the substrate's critical
    angle (some layers evanescent too): R = 1, T = 0."""
    cases = []
    while len(cases) < count:
        n0 = rng.uniform(1.5, 2.2)
        nsub = rng.uniform(1.0, 1.4)
        layers = rng.randint(1, 12)
        ns = [complex(n0, 0)] + [complex(rng.uniform(1.0, 2.5), 0) for _ in range(layers)] + [complex(nsub, 0)]
        ds = [np.inf] + [rng.uniform(0.0, 300.0) for _ in range(layers)] + [np.inf]
        crit = math.asin(nsub / n0)
        th0 = rng.uniform(crit + 1e-3, math.pi / 2)
        lam = rng.uniform(380.0, 780.0)
        if max_im_delta(ns, ds, th0, lam) > 30:
            continue
        cases.append(case("tir", ns, ds, layers, False, lam, th0))
    return cases


def si_aspnes():
    rows = []
    with open(os.path.join(ROOT, "data", "materials", "si_aspnes.yml")) as f:
        inside = False
        for line in f:
            if line.strip().startswith("data: |"):
                inside = True
                continue
            if inside:
                parts = line.split()
                if len(parts) == 3:
                    rows.append([float(p) for p in parts])
    a = np.array(rows)
    return a[:, 0] * 1000.0, a[:, 1], a[:, 2]


def seed_cases():
    cases = []
    th0 = math.radians(1.0)
    wl, sn, sk = si_aspnes()
    stacks = [
        ("air | water 348nm | air", lambda lam: ([1.0, 1.33, 1.0], [np.inf, 348.0, np.inf])),
        ("air | water 635nm | air", lambda lam: ([1.0, 1.33, 1.0], [np.inf, 635.0, np.inf])),
        ("air | gasoline 216nm | water 220nm | asphalt",
         lambda lam: ([1.0, 1.4, 1.33, 1.635], [np.inf, 216.0, 220.0, np.inf])),
        ("air | Si 108nm | glass",
         lambda lam: ([1.0, complex(np.interp(lam, wl, sn), np.interp(lam, wl, sk)), 1.5], [np.inf, 108.0, np.inf])),
    ]
    for name, f in stacks:
        for lam in range(400, 701, 10):
            ns, ds = f(float(lam))
            cases.append({
                "kind": "seed",
                "stack": name,
                "absorbing_substrate": False,
                "wavelength_nm": float(lam),
                "angle_rad": th0,
                **run(ns, ds, th0, float(lam)),
            })
    return cases


def main():
    rng = random.Random(20260322)
    cases = random_cases(rng, 1000) + tir_cases(rng, 60) + seed_cases()
    doc = {
        "reference": f"tmm {getattr(tmm, '__version__', '0.2.0')} (coh_tmm), numpy {np.__version__}",
        "cases": cases,
    }
    write_compact("tools/gen_thinfilm_fixtures.py", doc, OUT, f"{len(cases)} cases")


if __name__ == "__main__":
    main()
