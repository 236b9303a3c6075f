#!/usr/bin/env python3
"""Times grcwa (PyPI, staircase RCWA) on the cases of iridis-rigorous's benchmark, at equal accuracy, in the
same run as the Rust benchmark.

    python3 -m venv /tmp/rcwa-venv && /tmp/rcwa-venv/bin/pip install numpy grcwa==0.1.2
    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 /tmp/rcwa-venv/bin/python tools/bench_rigorous_peers.py [BENCH.json]

Without BENCH.json it runs `cargo run --release -p iridis-rigorous --example bench` first (the library's
`benchmark`, one thread). For each case, grcwa walks a ladder of (orders, slices) until every propagating
efficiency above 1e-3 is within 1 % (the issue's bar) of the C-method's reference answer (itself converged to
~1e-10), then within 0.1 %; the time of the first rung that meets each level is the peer's time at that
accuracy. One thread for numpy (the variables above) so both sides use one core. Prints a table (markdown).
"""
import json
import os
import subprocess
import sys
import time

import numpy as np
import grcwa

grcwa.set_backend("numpy")
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def grcwa_solve(case, n_orders, slices, pol, nx):
    p, a = case["period_nm"], case["amplitude_nm"]
    eps = complex(case["eps"][0], case["eps"][1])
    two_d = case["two_d"]
    l2 = [0, p] if two_d else [0, p * 1e-3]
    obj = grcwa.obj(n_orders, [p, 0], l2, 1.0 / case["wavelength_nm"], np.radians(case["theta_i_deg"]),
                    np.radians(case["phi_i_deg"] + 180.0), verbose=0)
    obj.Add_LayerUniform(0, 1.0)
    for _ in range(slices):
        obj.Add_LayerGrid(2 * a / slices, nx, nx if two_d else 1)  # h spans [−a, a] in both cases
    obj.Add_LayerUniform(0, eps)
    obj.Init_Setup(Gmethod=0)
    x = np.arange(nx) * p / nx
    k = 2 * np.pi / p
    if two_d:
        X, Y = np.meshgrid(x, x, indexing="ij")
        h = 0.5 * a * (np.sin(k * X) + np.sin(k * Y))
        grids = [np.where(h > a - (j + 0.5) * 2 * a / slices, eps, 1.0 + 0j).flatten() for j in range(slices)]
    else:
        h = a * np.sin(k * x)
        grids = [np.where(h > a - (j + 0.5) * 2 * a / slices, eps, 1.0 + 0j) for j in range(slices)]
    obj.GridLayer_geteps(np.concatenate(grids))
    if pol == "te":
        obj.MakeExcitationPlanewave(0, 0, 1, 0, order=0)
    else:
        obj.MakeExcitationPlanewave(1, 0, 0, 0, order=0)
    R, T = obj.RT_Solve(normalize=1, byorder=1)
    out = {}
    for i, g in enumerate(obj.G):
        out[(int(g[0]), int(g[1]) if two_d else 0, False)] = float(R[i])
        out[(int(g[0]), int(g[1]) if two_d else 0, True)] = float(T[i])
    return out


def metal(case):
    return case["eps"][0] < 0


def error(case, ref, res_te, res_tm):
    """Worst error over the propagating orders; TE only on a metal, where staircase RCWA does not converge in
    TM (Popov et al. 2002; the ladder below shows it)."""
    worst = 0.0
    for o in ref:
        if case["eps"][1] != 0 and o["transmitted"]:
            continue
        key = (o["m"], o["n"], o["transmitted"])
        pairs = ((o["te"], res_te),) if metal(case) else ((o["te"], res_te), (o["tm"], res_tm))
        for want, res in pairs:
            got = res.get(key, 0.0)
            worst = max(worst, abs(got - want) / max(want, 1e-3))
    return worst


def tm_error(case, ref, res_tm):
    return max(abs(res_tm.get((o["m"], o["n"], o["transmitted"]), 0.0) - o["tm"]) / max(o["tm"], 1e-3)
               for o in ref if not o["transmitted"])


def main():
    if len(sys.argv) > 1:
        bench = json.load(open(sys.argv[1]))
    else:
        out = subprocess.run(["cargo", "run", "--quiet", "--release", "-p", "iridis-rigorous", "--example", "bench"],
                             cwd=ROOT, check=True, capture_output=True, text=True).stdout
        bench = json.loads(out)
    print("| case | iridis C-method: orders, time, error | grcwa at 1 %: orders/slices, time, error | "
          "grcwa at 0.1 % | speed-up at 1 % |")
    print("|---|---|---|---|---|")
    for rep in bench:
        case = rep["case"]
        two_d = case["two_d"]
        ladder = ([(25, 6), (49, 10), (81, 16), (121, 20), (169, 30), (225, 40)] if two_d else
                  [(11, 10), (21, 20), (31, 30), (41, 40), (61, 60), (81, 80), (121, 120)])
        nx = 128 if two_d else 2048
        found = {}
        last = None
        for n_orders, slices in ladder:
            t = time.time()
            te = grcwa_solve(case, n_orders, slices, "te", nx)
            tm = grcwa_solve(case, n_orders, slices, "tm", nx)
            dt = time.time() - t
            err = error(case, rep["reference"], te, tm)
            last = (n_orders, slices, dt, err)
            extra = f", TM error {tm_error(case, rep['reference'], tm):.2e}" if metal(case) else ""
            print(f"  grcwa {case['name']}: {n_orders} orders, {slices} slices: {dt:.2f} s (TE+TM), "
                  f"error {err:.2e}{extra}", file=sys.stderr)
            for level in (1e-2, 1e-3):
                if err <= level and level not in found:
                    found[level] = (n_orders, slices, dt, err)
            if 1e-3 in found or dt > 60:
                break
        ours = f"{rep['orders']}, {rep['seconds']:.4f} s, {rep['measured_error']:.1e}"

        def cell(level):
            if level in found:
                n, s, dt, err = found[level]
                return f"{n}/{s}, {dt:.2f} s, {err:.1e}"
            n, s, dt, err = last
            return f"not reached (at {n}/{s}: {dt:.2f} s, error {err:.1e})"

        speed = (f"{found[1e-2][2] / rep['seconds']:.0f}×" if 1e-2 in found
                 else f"> {last[2] / rep['seconds']:.0f}× (grcwa not at 1 %)")
        pols = "TE+TM; grcwa's error on TE" if metal(case) else "TE+TM"
        print(f"| {case['name']} ({pols}) | {ours} | {cell(1e-2)} | {cell(1e-3)} | {speed} |")


if __name__ == "__main__":
    main()
