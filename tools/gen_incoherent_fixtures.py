#!/usr/bin/env python3
"""Reference values for iridis-thinfilm's incoherent layers, field profiles, absorption per layer and
ellipsometry, from the `tmm` package (S. J. Byrnes, https://pypi.org/project/tmm/, MIT licence; physics in
arXiv:1603.02720), written to crates/thinfilm/tests/fixtures/tmm_incoherent.json. The Rust tests read that
file; they do not need Python.

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install tmm numpy
    /tmp/venv/bin/python tools/gen_incoherent_fixtures.py

Cases:
  * "inc": random mixed stacks (1-10 layers, each incoherent with probability 0.35, 1 µm - 2 mm thick and
    weakly absorbing or not; coherent layers as in gen_thinfilm_fixtures.py), tmm.inc_tmm R and T for s and
    p, and tmm.inc_absorp_in_each_layer. Cases where tmm's answer is not finite (an evanescent incoherent
    layer) or a coherent layer is beyond tmm's opacity clamp (Im δ > 35) are skipped.
  * "ellips": random coherent stacks, tmm.ellips ψ and Δ (radians).
  * "profile": random coherent stacks, tmm.position_resolved at points inside every medium (poyn, absor,
    |E|² = |Ex|² + |Ey|² + |Ez|²) and tmm.absorp_in_each_layer, for s and p.
"""
import json
import math
import os
import random

import numpy as np
import tmm

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "crates", "thinfilm", "tests", "fixtures", "tmm_incoherent.json")


def fmt_index(n):
    n = complex(n)
    return f"n={n.real!r}" if n.imag == 0 else f"n={n.real!r}+{n.imag!r}i"


def stack_string(ns, ds, cs):
    parts = [fmt_index(ns[0])]
    for n, d, c in zip(ns[1:-1], ds[1:-1], cs[1:-1]):
        parts.append(f"{'inc:' if c == 'i' else ''}{fmt_index(n)} {float(d)!r}nm")
    parts.append(fmt_index(ns[-1]))
    return " | ".join(parts)


def max_im_delta(ns, ds, cs, th0, lam):
    worst = 0.0
    for n, d, c in zip(ns[1:-1], ds[1:-1], cs[1:-1]):
        if c == "i":
            continue
        sx = ns[0] * math.sin(th0) / complex(n)
        cz = np.sqrt(1 - sx * sx)
        worst = max(worst, abs((2 * math.pi / lam * complex(n) * cz * d).imag))
    return worst


def random_layers(rng, count, inc_prob):
    n0 = rng.choice([1.0, 1.0, 1.33, rng.uniform(1.0, 1.8)])
    absorbing = rng.random() < 0.5
    ns, ds, cs = [complex(n0, 0.0)], [np.inf], ["i"]
    for _ in range(count):
        if rng.random() < inc_prob:
            n = rng.uniform(1.3, 2.5)
            k = rng.choice([0.0, rng.uniform(0.0, 2e-4)])
            ns.append(complex(n, k))
            ds.append(rng.uniform(1e3, 2e6))
            cs.append("i")
        else:
            n = rng.uniform(1.0, 3.0)
            k = rng.uniform(0.0, 2.0) if absorbing and rng.random() < 0.5 else 0.0
            ns.append(complex(n, k))
            ds.append(rng.uniform(0.0, 400.0) if not k else rng.uniform(0.0, 60.0))
            cs.append("c")
    sub_k = rng.uniform(0.0, 4.0) if absorbing and rng.random() < 0.3 else 0.0
    ns.append(complex(rng.uniform(1.0, 2.5) if sub_k == 0 else rng.uniform(0.1, 3.0), sub_k))
    ds.append(np.inf)
    cs.append("i")
    return ns, ds, cs


def random_case(rng, max_layers, inc_prob):
    """A random stack of 1 to max_layers layers, a wavelength and an angle; None where the stack's coherent
    layers are too opaque (|Im δ| > 30) for a fair comparison."""
    ns, ds, cs = random_layers(rng, rng.randint(1, max_layers), inc_prob)
    lam = rng.uniform(380.0, 780.0)
    th0 = rng.choice([0.0, math.pi / 2 * 0.98 * rng.random(), math.pi / 2 * 0.98 * rng.random()])
    if max_im_delta(ns, ds, cs, th0, lam) > 30:
        return None
    return ns, ds, cs, lam, th0


def random_cases(rng, max_layers, inc_prob, enough):
    """random_case's fair cases, drawn one by one until enough() (asked before each draw) says so."""
    while not enough():
        case = random_case(rng, max_layers, inc_prob)
        if case is not None:
            yield case


def write_compact(generator, doc, out, what):
    """Writes a fixture, its generator's name first, as one line of compact JSON and says what it wrote where."""
    with open(out, "w") as f:
        json.dump({"generator": generator, **doc}, f, separators=(",", ":"))
        f.write("\n")
    print(f"wrote {what} to {os.path.relpath(out, ROOT)}")


def inc_cases(rng, count):
    cases = []
    for ns, ds, cs, lam, th0 in random_cases(rng, 10, 0.35, lambda: len(cases) >= count):
        out = {}
        ok = True
        for pol in ("s", "p"):
            with np.errstate(all="ignore"):
                res = tmm.inc_tmm(pol, ns, ds, cs, th0, lam)
                absorp = [float(a) for a in tmm.inc_absorp_in_each_layer(res)]
            vals = [float(res["R"]), float(res["T"])] + absorp
            if not all(math.isfinite(v) for v in vals):
                ok = False
                break
            out[pol] = {"R": float(res["R"]), "T": float(res["T"]), "absorp": absorp}
        if not ok:
            continue
        cases.append({
            "stack": stack_string(ns, ds, cs),
            "incoherent_layers": cs[1:-1].count("i"),
            "absorbing_substrate": ns[-1].imag > 0,
            "wavelength_nm": lam,
            "angle_rad": th0,
            **out,
        })
    return cases


def coherent_cases(rng, count, with_profile):
    cases = []
    for ns, ds, cs, lam, th0 in random_cases(rng, 8, 0.0, lambda: len(cases) >= count):
        case = {"stack": stack_string(ns, ds, cs), "absorbing_substrate": ns[-1].imag > 0,
                "wavelength_nm": lam, "angle_rad": th0}
        e = tmm.ellips(ns, ds, th0, lam)
        case["psi"] = float(e["psi"])
        case["Delta"] = float(e["Delta"])
        if with_profile:
            points = []
            for layer in range(len(ns)):
                if layer == 0:
                    dists = [-rng.uniform(0.0, 300.0), 0.0]
                elif layer == len(ns) - 1:
                    dists = [0.0, rng.uniform(0.0, 200.0)]
                else:
                    dists = [0.0, rng.uniform(0.0, ds[layer]), ds[layer]]
                for dist in dists:
                    points.append({"medium": layer, "dz": dist})
            for pol in ("s", "p"):
                data = tmm.coh_tmm(pol, ns, ds, th0, lam)
                vals = []
                for pt in points:
                    # tmm.position_resolved asserts distance ≥ 0 beyond the incident medium and ≤ d inside.
                    r = tmm.position_resolved(pt["medium"], pt["dz"], data)
                    e2 = abs(r["Ex"]) ** 2 + abs(r["Ey"]) ** 2 + abs(r["Ez"]) ** 2
                    vals.append([float(np.real(r["poyn"])), float(np.real(r["absor"])), float(e2)])
                case[pol] = {"points": vals, "absorp": [float(a) for a in tmm.absorp_in_each_layer(data)],
                             "R": float(data["R"]), "T": float(data["T"])}
            case["points"] = points
        cases.append(case)
    return cases


def main():
    rng = random.Random(20261123)
    doc = {
        "reference": f"tmm (inc_tmm, inc_absorp_in_each_layer, ellips, position_resolved, absorp_in_each_layer), "
                     f"numpy {np.__version__}",
        "inc": inc_cases(rng, 400),
        "ellips": coherent_cases(rng, 300, False),
        "profile": coherent_cases(rng, 150, True),
    }
    counts = " + ".join(str(len(doc[k])) for k in ("inc", "ellips", "profile"))
    write_compact("tools/gen_incoherent_fixtures.py", doc, OUT, f"{counts} cases")


if __name__ == "__main__":
    main()
