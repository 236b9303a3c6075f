#!/usr/bin/env python3
"""Reference values for the refractiveindex.info dispersion formulas 3, 7, 8 and 9 that iridis-thinfilm reads
from YAML files (crates/thinfilm/src/material.rs), written to
crates/thinfilm/tests/fixtures/dispersion_formulas.json. The Rust test (crates/thinfilm/tests/dispersion_formulas.rs)
reads that file; it does not need Python.

    python3 tools/gen_dispersion_fixtures.py        (standard library only)

The formulas are evaluated as published in the database's documentation ("Dispersion formulas",
https://refractiveindex.info/database/doc/Dispersion%20formulas.pdf; λ in µm, C1… the `coefficients` in order):

    3  Polynomial:  n² = C1 + C2 λ^C3 + C4 λ^C5 + C6 λ^C7 + …
    7  Herzberger:  n  = C1 + C2/(λ² − 0.028) + C3 (1/(λ² − 0.028))² + C4 λ² + C5 λ⁴ + C6 λ⁶
    8  Retro:       (n² − 1)/(n² + 2) = C1 + C2 λ²/(λ² − C3) + C4 λ²
    9  Exotic:      n² = C1 + C2/(λ² − C3) + C4 (λ − C5)/((λ − C5)² + C6)

independently of the Rust code: in 50-digit decimal arithmetic (Python's `decimal`), so the fixture is exact to
far below the f64 rounding the test allows for.

Coefficient sets:
  * formula 3: SCHOTT's former (Laurent-series) formula for BK7, n² = A0 + A1 λ² + A2 λ⁻² + A3 λ⁻⁴ + A4 λ⁻⁶ +
    A5 λ⁻⁸ with A0 = 2.2718929, A1 = −1.0108077e-2, A2 = 1.0592509e-2, A3 = 2.0816965e-4, A4 = −7.6472538e-6,
    A5 = 4.9240991e-7 (SCHOTT catalogue before 1992). Also checked in the Rust test against the published
    catalogue value n_d = 1.51680 at 587.56 nm.
  * formula 7: a Herzberger set of germanium's size (C1 ≈ 4, the 8–14 µm window) with a λ⁶ term added so that
    every coefficient is exercised; the reference is the formula, not a material.
  * formula 8 and 9: coefficient sets with every term non-zero and n in the range of optical solids; again
    the reference is the formula.
"""
import json
import os
from decimal import Decimal, getcontext

getcontext().prec = 50

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "crates", "thinfilm", "tests", "fixtures", "dispersion_formulas.json")

D = Decimal


def polynomial(c, lam):  # formula 3
    s = c[0]
    for i in range(1, len(c) - 1, 2):
        s += c[i] * lam ** c[i + 1]
    return s.sqrt()


def herzberger(c, lam):  # formula 7
    c = c + [D(0)] * (6 - len(c))
    L = 1 / (lam * lam - D("0.028"))
    return c[0] + c[1] * L + c[2] * L * L + c[3] * lam ** 2 + c[4] * lam ** 4 + c[5] * lam ** 6


def retro(c, lam):  # formula 8
    q = c[0] + c[1] * lam ** 2 / (lam ** 2 - c[2]) + c[3] * lam ** 2
    # (n² − 1)/(n² + 2) = q  ⇔  n² = (1 + 2q)/(1 − q)
    return ((1 + 2 * q) / (1 - q)).sqrt()


def exotic(c, lam):  # formula 9
    d = lam - c[4]
    return (c[0] + c[1] / (lam * lam - c[2]) + c[3] * d / (d * d + c[5])).sqrt()


CASES = [
    {
        "formula": 3,
        "what": "SCHOTT BK7, former Laurent-series catalogue formula",
        "range_um": ["0.31", "2.3"],
        "coefficients": ["2.2718929", "-1.0108077e-2", "2", "1.0592509e-2", "-2", "2.0816965e-4", "-4",
                         "-7.6472538e-6", "-6", "4.9240991e-7", "-8"],
        "f": polynomial,
        "wavelengths_um": ["0.4", "0.48613", "0.5875618", "0.65627", "0.78", "1.014", "2.0"],
    },
    {
        "formula": 7,
        "what": "Herzberger, germanium-sized coefficients plus a λ⁶ term",
        "range_um": ["2.0", "14.0"],
        "coefficients": ["3.99931", "0.391707", "0.163492", "-6.0e-6", "5.3e-8", "-1.0e-10"],
        "f": herzberger,
        "wavelengths_um": ["2.0", "3.5", "5.0", "8.0", "10.6", "14.0"],
    },
    {
        "formula": 8,
        "what": "Retro, every term non-zero",
        "range_um": ["0.3", "2.0"],
        "coefficients": ["0.27", "0.04", "0.03", "-0.002"],
        "f": retro,
        "wavelengths_um": ["0.3", "0.45", "0.55", "0.7", "1.2", "2.0"],
    },
    {
        "formula": 9,
        "what": "Exotic, every term non-zero (a resonance near 1.52 µm)",
        "range_um": ["0.3", "1.06"],
        "coefficients": ["2.51527", "0.0240", "0.0300", "0.020", "1.52", "0.8771"],
        "f": exotic,
        "wavelengths_um": ["0.3", "0.4", "0.5", "0.6328", "0.8", "1.06"],
    },
]


def main():
    out = {"generator": "tools/gen_dispersion_fixtures.py", "cases": []}
    for case in CASES:
        c = [D(x) for x in case["coefficients"]]
        rows = []
        for w in case["wavelengths_um"]:
            n = case["f"](c, D(w))
            rows.append({"wavelength_nm": float(D(w) * 1000), "n": float(n)})
        out["cases"].append({
            "formula": case["formula"],
            "what": case["what"],
            "range_um": [float(D(x)) for x in case["range_um"]],
            "coefficients": [float(x) for x in c],
            "values": rows,
        })
    with open(OUT, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")
    print("wrote", OUT)


if __name__ == "__main__":
    main()
