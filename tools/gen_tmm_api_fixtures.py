#!/usr/bin/env python3
"""What tmm 0.2.0 (S. J. Byrnes, https://pypi.org/project/tmm/, MIT licence) answers for every public function
of ``tmm.tmm_core``, written to crates/python/tests/fixtures/tmm_api.json; crates/python/tests/test_tmm_api.py
checks ``iridis.tmm`` against it (and against a live tmm where installed).

    python3 -m venv /tmp/v && /tmp/v/bin/pip install tmm==0.2.0 numpy && /tmp/v/bin/python tools/gen_tmm_api_fixtures.py

The file holds, per function, its signature (``inspect.signature``) and cases: arguments and tmm's result.
Values are tagged so that JSON keeps them: ``{"c": [re, im]}`` complex, ``{"nan": 1}`` NaN, ``{"inf": ±1}``
infinities, ``{"a": [...]}`` NumPy arrays (lists stay lists), ``{"dtype": "complex"}`` a type argument,
``{"error": "..."}`` where tmm raises.
"""
import inspect
import json
import math
import os

import numpy as np
import tmm
from tmm import tmm_core

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "crates", "python", "tests", "fixtures", "tmm_api.json")
inf = np.inf


def enc(x):
    if x is complex or x is float:
        return {"dtype": x.__name__}
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, np.ndarray):
        return {"a": [enc(v) for v in x.tolist()]}
    if isinstance(x, (list, tuple)):
        return [enc(v) for v in x]
    if isinstance(x, dict):
        return {k: enc(v) for k, v in x.items()}
    if isinstance(x, (complex, np.complexfloating)):
        return {"c": [enc(float(x.real)), enc(float(x.imag))]}
    if isinstance(x, (float, np.floating)):
        x = float(x)
        if math.isnan(x):
            return {"nan": 1}
        if math.isinf(x):
            return {"inf": 1 if x > 0 else -1}
        return x
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, str):
        return x
    if isinstance(x, tmm_core.absorp_analytic_fn):
        return {"absorp_analytic_fn": {k: enc(getattr(x, k)) for k in ("A1", "A2", "A3", "a1", "a3", "d")}}
    raise TypeError(type(x))


def call(fn, *args):
    try:
        return enc(fn(*args))
    except (AssertionError, ValueError) as e:
        return {"error": f"{type(e).__name__}: {e}"}


def cases(fn, arglists):
    return [{"args": enc(list(a)), "result": call(fn, *a)} for a in arglists]


# Stacks: lossless, absorbing, total internal reflection (complex angles), an absorbing incident medium with the
# complex angle that makes n0 sin th0 real.
N0 = 1.5 + 0.02j
TH0_ABSORBING = np.lib.scimath.arcsin(0.6 / N0)
STACKS = [
    ("s", [1, 2.2, 3.3 + 0.3j, 1], [inf, 100, 300, inf], 0.3, 400),
    ("p", [1, 2.2 + 0.2j, 3.3 + 0.3j, 1], [inf, 100, 300, inf], np.pi / 4, 400),
    ("p", [1.517, 3.719 + 4.362j, 0.130 + 3.162j, 1], [inf, 5, 30, inf], 0.75, 633),
    ("s", [1.5, 1.0, 2.0, 1.0], [inf, 200, 80, inf], 0.9, 550),
    ("p", [N0, 2.0, 1.46 + 0.001j, 1.0], [inf, 120, 90, inf], TH0_ABSORBING, 500),
    ("s", [1, 1.46, 3.87 + 0.02j], [inf, 250, inf], 70 * np.pi / 180, 633),
]


def coh_data(i):
    pol, n, d, th, lam = STACKS[i]
    return tmm.coh_tmm(pol, np.array(n), np.array(d, float), th, lam)


def main():
    out = {"tmm_version": "0.2.0", "functions": {}}
    f = out["functions"]

    def add(name, arglists, fn=None):
        fn = fn or getattr(tmm_core, name)
        f[name] = {"signature": str(inspect.signature(getattr(tmm_core, name))), "cases": cases(fn, arglists)}

    add("make_2x2_array", [(1, 2, 3, 4), (1j, 2, 3, 4 + 1j, complex)])
    add("is_forward_angle", [(1.5, 0.3), (1.5, np.pi - 0.3), (2 + 0.1j, 0.4 + 0.05j), (1.0, 0.5 + 1.2j),
                             (1.0, np.pi / 2 - 1.2j), (1.5 - 0.1j, 0.3)])
    add("snell", [(1, 1.5, 0.4), (1.5, 1.0, 1.2), (1, 3 + 0.5j, 0.7), (N0, 1.0, TH0_ABSORBING)])
    add("list_snell", [(np.array([1, 1.5, 2.0]), 0.4), (np.array([1.5, 1.0, 2.0 + 0.1j, 1.0]), 1.2),
                       (np.array([N0, 2.0, 1.0]), TH0_ABSORBING)])
    iface = [("s", 1, 1.5, 0.3, tmm.snell(1, 1.5, 0.3)), ("p", 1, 1.5, 0.3, tmm.snell(1, 1.5, 0.3)),
             ("s", 1.5, 1, 1.2, tmm.snell(1.5, 1, 1.2)), ("p", 1.5, 1, 1.2, tmm.snell(1.5, 1, 1.2)),
             ("p", 1, 0.2 + 3.4j, 0.6, tmm.snell(1, 0.2 + 3.4j, 0.6)), ("x", 1, 1.5, 0.0, 0.0)]
    for name in ("interface_r", "interface_t", "interface_R", "interface_T"):
        add(name, iface)
    add("R_from_r", [(0.3 - 0.4j,), (-0.2,)])
    add("T_from_t", [("s", 0.8 + 0.1j, 1, 1.5, 0.3, tmm.snell(1, 1.5, 0.3)),
                     ("p", 0.8 + 0.1j, 1, 2 + 0.3j, 0.3, tmm.snell(1, 2 + 0.3j, 0.3)),
                     ("s", 0.5, N0, 1.0, TH0_ABSORBING, tmm.snell(N0, 1.0, TH0_ABSORBING)), ("q", 1, 1, 1, 0, 0)])
    add("power_entering_from_r", [("s", 0.3 - 0.4j, 1, 0.3), ("p", 0.3 - 0.4j, 1, 0.3),
                                  ("s", 0.2 + 0.1j, N0, TH0_ABSORBING), ("p", 0.2 + 0.1j, N0, TH0_ABSORBING)])
    add("coh_tmm", [(p, np.array(n), np.array(d, float), th, lam) for p, n, d, th, lam in STACKS]
        + [("s", np.array([1, 1.5]), np.array([inf, inf]), 0.1 + 0j, 500)])
    add("coh_tmm_reverse", [(p, np.array(n), np.array(d, float), th, lam) for p, n, d, th, lam in STACKS
                            if complex(n[0]).imag == 0])
    add("ellips", [(np.array(n), np.array(d, float), th, lam) for _, n, d, th, lam in STACKS])
    add("unpolarized_RT", [(np.array(n), np.array(d, float), th, lam) for _, n, d, th, lam in STACKS])
    positions = []
    for i, (_, n, d, _, _) in enumerate(STACKS):
        for depth in (-30.0, 0.0, 0.5 * d[1], d[1], d[1] + 0.25 * (d[2] if len(d) > 3 else 100), 1000.0):
            layer, z = tmm.find_in_structure_with_inf(d, depth)
            positions.append((i, layer, z))
    f["position_resolved"] = {
        "signature": str(inspect.signature(tmm_core.position_resolved)),
        "cases": [{"stack": i, "args": [layer, enc(z)], "result": enc(tmm.position_resolved(layer, z, coh_data(i)))}
                  for i, layer, z in positions],
    }
    add("find_in_structure", [([100, 300], -5.0), ([100, 300], 0.0), ([100, 300], 150.0), ([100, 300], 400.0),
                              ([100, 300], 1e4), ([inf, 100], 5.0)])
    add("find_in_structure_with_inf", [([inf, 100, 300, inf], -5.0), ([inf, 100, 300, inf], 99.0),
                                       ([inf, 100, 300, inf], 100.0), ([inf, 100, 300, inf], 450.0)])
    add("layer_starts", [([inf, 100, 300, inf],), ([inf, 5, 30, 7, inf],)])
    fns = []
    for i, layer in [(0, 1), (0, 2), (1, 1), (1, 2), (2, 2), (4, 2)]:
        a = tmm_core.absorp_analytic_fn().fill_in(coh_data(i), layer)
        zs = np.linspace(0, a.d, 7)
        b = a.copy().flip()
        c = a.copy().scale(0.37)
        s = a.copy().add(b.copy().flip())
        fns.append({"stack": i, "layer": layer, "fill_in": enc(a), "run": enc(a.run(zs)), "z": enc(zs),
                    "flip": enc(b), "flip_run": enc(b.run(zs)), "scale": enc(c), "add": enc(s)})
    f["absorp_analytic_fn"] = {"signature": "class with fill_in(self, coh_tmm_data, layer), copy(self), "
                               "run(self, z), flip(self), scale(self, factor), add(self, b)", "cases": fns}
    f["absorp_in_each_layer"] = {"signature": str(inspect.signature(tmm_core.absorp_in_each_layer)),
                                 "cases": [{"stack": i, "result": enc(tmm.absorp_in_each_layer(coh_data(i)))}
                                           for i in range(len(STACKS))]}
    inc_cases = [
        ("s", [1, 1.5, 2.0 + 0.01j, 1.46, 1], [inf, 1e5, 80, 120, inf], ["i", "i", "c", "c", "i"], 0.4, 500),
        ("p", [1, 2.2 + 0.02j, 1.5, 1.38, 2.0, 1], [inf, 90, 2e6, 100, 60, inf], ["i", "c", "i", "c", "c", "i"],
         0.7, 633),
        ("s", [1, 1.5 + 1e-4j, 1.33, 1.5 + 1e-4j, 1], [inf, 5e5, 300, 5e5, inf], ["i", "i", "c", "i", "i"], 0.2,
         450),
        ("p", [1, 1.5, 1], [inf, 1e6, inf], ["i", "i", "i"], 0.5, 550),
        ("s", [1, 1.5, 1], [inf, 1e6, inf], ["i", "x", "i"], 0.5, 550),
    ]
    add("inc_group_layers", [(np.array(n), np.array(d, float), c) for _, n, d, c, _, _ in inc_cases[:4]])
    inc_out = []
    for p, n, d, c, th, lam in inc_cases:
        try:
            res = tmm.inc_tmm(p, np.array(n), np.array(d, float), c, th, lam)
        except (AssertionError, ValueError) as e:
            inc_out.append({"args": enc([p, n, d, c, th, lam]), "result": {"error": f"{type(e).__name__}: {e}"}})
            continue
        slim = {k: v for k, v in res.items() if k not in ("coh_tmm_data_list", "coh_tmm_bdata_list")}
        slim["coh_R"] = [x["R"] for x in res["coh_tmm_data_list"]]
        slim["coh_bT"] = [x["T"] for x in res["coh_tmm_bdata_list"]]
        absorb = tmm.inc_absorp_in_each_layer(res)
        analytic = []
        for layer, kind in enumerate(c):
            if kind == "c":
                try:
                    a = tmm.inc_find_absorp_analytic_fn(layer, res)
                except ValueError as e:
                    # tmm compares the forward and backward k_z exactly; rounding can make them differ.
                    analytic.append({"layer": layer, "error": f"ValueError: {e}"})
                    continue
                analytic.append({"layer": layer, "fn": enc(a), "run": enc(a.run(np.linspace(0, a.d, 5)))})
        inc_out.append({"args": enc([p, n, d, c, th, lam]), "result": enc(slim), "inc_absorp_in_each_layer":
                        enc(absorb), "inc_find_absorp_analytic_fn": analytic})
    for name in ("inc_tmm", "inc_absorp_in_each_layer", "inc_find_absorp_analytic_fn"):
        f[name] = {"signature": str(inspect.signature(getattr(tmm_core, name))),
                   "cases": inc_out if name == "inc_tmm" else "in inc_tmm's cases"}
    f["STACKS"] = enc([list(s) for s in STACKS])
    public = sorted(k for k, v in vars(tmm_core).items()
                    if not k.startswith("_") and (inspect.isfunction(v) or inspect.isclass(v))
                    and getattr(v, "__module__", "") == tmm_core.__name__)
    out["public"] = public
    missing = [k for k in public if k not in f]
    assert not missing, missing
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w") as fh:
        json.dump(out, fh, indent=1)
    print(f"wrote {OUT}: {len(public)} public names of tmm_core, {sum(len(v['cases']) if isinstance(v, dict) and isinstance(v.get('cases'), list) else 0 for v in f.values())} cases")


if __name__ == "__main__":
    main()
