#!/usr/bin/env python3
"""Fixtures for the iridis-vision tests: an independent numpy implementation of the models, written from the
papers (not from iridis' Rust, nor from pavo's R code), and its answers on test spectra.

- Govardovskii et al. (2000) A1/A2 templates (alpha and beta bands) and Hart & Vorobyev (2005) oil droplets.
- Quantum catches Q_i = int R I T S_i dlambda (trapezoid rule on the spectra's 1 nm grid), von Kries
  q_i = Q_i / Q_i(background), relative catches, the tetrahedron / triangle / line coordinates and Chittka's
  (1992) hexagon.
- The receptor-noise-limited Delta S of Vorobyev & Osorio (1998) in two independent forms that must agree:
  the closed forms for di-, tri- and tetrachromats as printed in the paper, and the general form as a
  noise-weighted (Mahalanobis) distance with the achromatic direction projected out,
  dS^2 = df' (W - W 1 1' W / 1'W1) df with W = diag(1/e_i^2). Delta L = |ln(Qa/Qb)| / w.

Writes crates/vision/tests/fixtures/vision_numpy.json and data/examples/vision_spectra.csv (the test spectra,
pavo's CSV layout). With --pavo PATH (a git checkout of https://github.com/rmaia/pavo; pip install rdata) it
also checks this implementation against values pavo computes and prints the agreement (docs/vision.md):
pavo's template curves (canis), and the mean Delta S of pavo's regression test on its `flowers` data.

Usage: python3 tools/gen_vision_fixtures.py [--pavo PATH]     (pip install numpy [rdata])
"""
import argparse
import json
import os
import warnings
from itertools import combinations

import numpy as np

ROOT = os.path.join(os.path.dirname(__file__), "..")
WL = np.arange(300.0, 701.0, 1.0)


def trapezoid(y, x, axis=-1):
    """The trapezoid rule, written out (numpy renamed np.trapz to np.trapezoid in 2.0)."""
    y = np.moveaxis(np.asarray(y, float), axis, -1)
    dx = np.diff(x)
    return np.sum(dx * (y[..., 1:] + y[..., :-1]) / 2.0, axis=-1)


# ---- templates and droplets (Govardovskii et al. 2000; Hart & Vorobyev 2005) ----
def alpha(lmax, wl, chrom):
    x = lmax / wl
    if chrom == "A1":
        A, B, b, C, c, D = 69.7, 28.0, 0.922, -14.9, 1.104, 0.674
        a = 0.8795 + 0.0459 * np.exp(-((lmax - 300.0) ** 2) / 11940.0)
    else:
        A = 62.7 + 1.834 * np.exp((lmax - 625.0) / 54.2)
        a = 0.875 + 0.0268 * np.exp((lmax - 665.0) / 40.7)
        B, b, C, c, D = 20.85, 0.9101, -10.37, 1.1123, 0.5343
    return 1.0 / (np.exp(A * (a - x)) + np.exp(B * (b - x)) + np.exp(C * (c - x)) + D)


def beta(lmax, wl, chrom):
    if chrom == "A1":
        amp, centre, width = 0.26, 189.0 + 0.315 * lmax, -40.5 + 0.195 * lmax
    else:
        amp, centre, width = 0.37, 216.7 + 0.287 * lmax, 317.0 - 1.149 * lmax + 0.00124 * lmax ** 2
    return amp * np.exp(-(((wl - centre) / width) ** 2))


REGRESSION = {"C": (0.99, 24.38), "Y": (0.90, 70.03), "R": (0.99, 28.65), "P": (0.96, 33.57)}


def droplet(wl, kind, lcut):
    if kind == "T":
        return np.ones_like(wl)
    s, o = REGRESSION[kind]
    bmid = 0.5 / ((s * lcut + o) - lcut)
    return np.exp(-np.exp(-2.89 * bmid * (wl - lcut) + 1.08))


def template_receptor(lmax, chrom="A1", drop=None):
    """Sensitivity on WL: template peak-scaled to 1 on 300-700 nm, times droplet, unit sum on the 1 nm grid."""
    s = alpha(lmax, WL, chrom) + beta(lmax, WL, chrom)
    s = s / s.max()
    if drop is not None:
        s = s * droplet(WL, *drop)
    return s / s.sum()


def read_csv(path):
    rows, header = [], None
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        f = line.strip().split(",")
        try:
            rows.append([float(x) for x in f])
        except ValueError:
            header = f
    a = np.array(rows)
    return header, a[:, 0], a[:, 1:]


def tabulated(path):
    """Receptors from a data/vision table, interpolated onto WL (zero outside), unit sum on the 1 nm grid."""
    header, w, v = read_csv(os.path.join(ROOT, "data", "vision", path))
    cols = [np.interp(WL, w, v[:, j], left=0.0, right=0.0) for j in range(v.shape[1])]
    return header[1:], [c / c.sum() for c in cols]


def light(name):
    if name == "ideal":
        return np.ones_like(WL)
    if name in ("bluesky", "forestshade"):
        _, w, v = read_csv(os.path.join(ROOT, "data", "vision", "illuminant_endler1993_%s.csv" % name))
        return np.interp(WL, w, v[:, 0], left=0.0, right=0.0)
    _, w, v = read_csv(os.path.join(ROOT, "data", "cie", name + ".csv"))
    photons = np.interp(WL, w, v[:, 0]) * WL
    return photons / photons.max()


def system(name):
    """(receptor names, sensitivities on WL, ocular media on WL, achromatic sensitivity on WL or None)."""
    ones = np.ones_like(WL)
    _, dc = tabulated("bluetit_double_cone_hart2000.csv")
    if name == "bluetit":
        _, w, v = read_csv(os.path.join(ROOT, "data", "vision", "bluetit_ocular_media_hart2000.csv"))
        media = np.interp(WL, w, v[:, 0], left=0.0, right=0.0)
        cones = [(371, ("T", 330)), (448, ("C", 413)), (502, ("Y", 507)), (563, ("R", 572))]
        return ["UVS", "SWS", "MWS", "LWS"], [template_receptor(l, "A1", d) for l, d in cones], media, dc[0]
    if name == "avian-uv":
        names, s = tabulated("avian_uv_endler_mielke_2005.csv")
        return names, s, ones, dc[0]
    if name == "human":
        names, s = tabulated("human_ss2000_2deg_quantal.csv")
        return names, s, ones, s[1] + s[2]
    if name == "honeybee":
        s = [template_receptor(l) for l in (344, 436, 556)]
        return ["UV", "B", "G"], s, ones, s[2]
    if name == "ball-python":
        s = [template_receptor(l) for l in (360, 551)]
        return ["UVS", "LWS"], s, ones, s[1]
    if name == "custom-a2":
        cones = [(360, ("T", 0)), (440, ("C", 410)), (520, ("Y", 500)), (600, ("R", 580))]
        s = [template_receptor(l, "A2", d) for l, d in cones]
        return ["λ360", "λ440", "λ520", "λ600"], s, ones, s[3]
    raise KeyError(name)


# ---- the receptor-noise-limited model (Vorobyev & Osorio 1998) ----
def ds_closed(df, e):
    n = len(df)
    if n == 2:
        return np.sqrt((df[0] - df[1]) ** 2 / (e[0] ** 2 + e[1] ** 2))
    if n == 3:
        e1, e2, e3 = e
        f1, f2, f3 = df
        num = e1 ** 2 * (f3 - f2) ** 2 + e2 ** 2 * (f3 - f1) ** 2 + e3 ** 2 * (f1 - f2) ** 2
        return np.sqrt(num / ((e1 * e2) ** 2 + (e1 * e3) ** 2 + (e2 * e3) ** 2))
    e1, e2, e3, e4 = e
    f1, f2, f3, f4 = df
    num = ((e1 * e2) ** 2 * (f4 - f3) ** 2 + (e1 * e3) ** 2 * (f4 - f2) ** 2 + (e1 * e4) ** 2 * (f3 - f2) ** 2
           + (e2 * e3) ** 2 * (f4 - f1) ** 2 + (e2 * e4) ** 2 * (f3 - f1) ** 2 + (e3 * e4) ** 2 * (f2 - f1) ** 2)
    den = (e1 * e2 * e3) ** 2 + (e1 * e2 * e4) ** 2 + (e1 * e3 * e4) ** 2 + (e2 * e3 * e4) ** 2
    return np.sqrt(num / den)


def ds_matrix(df, e):
    W = np.diag(1.0 / np.asarray(e) ** 2)
    one = np.ones(len(df))
    M = W - np.outer(W @ one, one @ W) / (one @ W @ one)
    return np.sqrt(df @ M @ df)


def coords(space, rel, q):
    if space == "tetrahedron":
        u, s, m, l = rel
        p = [((1 - 2 * s - m - u) / 2) * np.sqrt(1.5), (-1 + 3 * m + u) / (2 * np.sqrt(2)), u - 0.25]
    elif space == "triangle":
        s, m, l = rel
        p = [(l - m) / np.sqrt(2), np.sqrt(2 / 3) * (s - (l + m) / 2)]
    elif space == "line":
        s, l = rel
        p = [(l - s) / np.sqrt(2)]
    elif space == "hexagon":
        E = q / (q + 1)
        p = [np.sqrt(3) / 2 * (E[2] - E[0]), E[1] - (E[0] + E[2]) / 2]
    return [float(x) for x in p]


def analyse(case, spectra):
    names, sens, media, achro = system(case["system"])
    I = light(case["illuminant"]) * case.get("scale", 1.0) * media
    bkg = case["background"]
    Q = {k: np.array([trapezoid(v * I * s, WL) for s in sens]) for k, v in spectra.items()}
    A = {k: float(trapezoid(v * I * achro, WL)) for k, v in spectra.items()}
    if bkg == "none":
        q = Q
    else:
        rb = spectra[bkg] if isinstance(bkg, str) else np.full_like(WL, float(bkg))
        Qb = np.array([trapezoid(rb * I * s, WL) for s in sens])
        q = {k: v / Qb for k, v in Q.items()}
    if "per_receptor" in case:
        e = np.array(case["per_receptor"])
    else:
        d = np.array(case["densities"], float)
        e = case["weber"] * np.sqrt(d[case["reference"]] / d)
    out = {"samples": [], "distances": []}
    for k in spectra:
        rel = q[k] / q[k].sum()
        out["samples"].append({"name": k, "absolute_catches": Q[k].tolist(), "quantum_catches": q[k].tolist(),
                               "relative_catches": rel.tolist(), "achromatic_catch": A[k],
                               "position": coords(case["space"], rel, q[k])})
    for a, b in combinations(list(spectra), 2):
        df = np.log(q[a] / q[b])
        if case.get("noise_model") == "quantum":
            ee = np.sqrt(e ** 2 + 2.0 / (Q[a] + Q[b]))
            w = np.sqrt(0.1 ** 2 + 2.0 / (A[a] + A[b]))
        else:
            ee, w = e, 0.1
        d1, d2 = ds_closed(df, ee), ds_matrix(df, ee)
        assert abs(d1 - d2) <= 1e-10 * max(1.0, d1), (case["name"], a, b, d1, d2)
        out["distances"].append({"a": a, "b": b, "delta_s": float(d1), "delta_l": float(abs(np.log(A[a] / A[b])) / w)})
    return out


def test_spectra():
    sig = lambda c, w: 1 / (1 + np.exp(-(WL - c) / w))
    g = lambda c, w: np.exp(-0.5 * ((WL - c) / w) ** 2)
    return {
        "uv_blue": 0.05 + 0.35 * g(370, 25) + 0.25 * g(460, 35),
        "yellow": 0.04 + 0.7 * sig(510, 12),
        "green": 0.05 + 0.3 * g(550, 30) + 0.03 * sig(690, 8),
        "red": 0.03 + 0.8 * sig(600, 10),
        "grey": np.full_like(WL, 0.3),
        "uv_blue_copy": 0.05 + 0.35 * g(370, 25) + 0.25 * g(460, 35),
    }


CASES = [
    {"name": "bluetit tetrachromat, D65, grey background", "system": "bluetit", "illuminant": "d65",
     "background": 1.0, "weber": 0.1, "reference": 3, "densities": [1, 2, 2, 4], "space": "tetrahedron"},
    {"name": "average avian UV eye, blue sky, no adaptation, quantum noise", "system": "avian-uv",
     "illuminant": "bluesky", "scale": 10000.0, "background": "none", "weber": 0.05, "reference": 3,
     "densities": [1, 1.9, 2.2, 2.1], "noise_model": "quantum", "space": "tetrahedron"},
    {"name": "human trichromat, D65, grey 0.2", "system": "human", "illuminant": "d65", "background": 0.2,
     "weber": 0.02, "reference": 2, "densities": [1, 5, 10], "space": "triangle"},
    {"name": "honeybee hexagon, forest shade, green background", "system": "honeybee", "illuminant": "forestshade",
     "background": "green", "per_receptor": [0.13, 0.06, 0.12], "space": "hexagon"},
    {"name": "ball python dichromat, D65", "system": "ball-python", "illuminant": "d65", "background": 1.0,
     "weber": 0.1, "reference": 1, "densities": [1, 1], "space": "line"},
    {"name": "custom A2 tetrachromat with droplets, illuminant E", "system": "custom-a2", "illuminant": "e",
     "background": 1.0, "weber": 0.1, "reference": 3, "densities": [1, 1, 1, 1], "space": "tetrahedron"},
]


def pavo_checks(path):
    import rdata
    warnings.filterwarnings("ignore")
    sysdata = rdata.read_rda(os.path.join(path, "R", "sysdata.rda"))
    v = sysdata["vissyst"]
    res = {}
    for col, lmax in [("canis.s", 430), ("canis.l", 555)]:
        mine = template_receptor(lmax)
        res[col] = float(np.abs(mine - np.asarray(v[col], float)).max() / mine.max())
        print("template vs pavo %s (lambda max %d): max |difference| / peak = %.2e" % (col, lmax, res[col]))
    fl = rdata.read_rda(os.path.join(path, "data", "flowers.rda"))["flowers"]
    R = np.asarray(fl.iloc[:, 1:], float) / 100.0  # percent, as pavo's vismodel divides
    S = np.column_stack([np.asarray(v["avg.uv." + k], float) for k in "usml"])
    e = 0.1 * np.sqrt(4.0 / np.array([1, 2, 2, 4.0]))
    for rule in ("sum", "trapezoid"):
        Q = R.T @ S if rule == "sum" else trapezoid(R[:, :, None] * S[:, None, :], WL, axis=0)
        ds = [ds_matrix(np.log(Q[a] / Q[b]), e) for a, b in combinations(range(Q.shape[0]), 2)]
        res["flowers_mean_dS_" + rule] = float(np.mean(ds))
        print("pavo regression coldist(vismodel(flowers), avg.uv): mean dS = 11.7606 (pavo); numpy, %s rule: %.4f"
              % (rule, np.mean(ds)))
    # the same with iridis' own data file (6 significant digits) for the avian UV eye
    names, Sd = tabulated("avian_uv_endler_mielke_2005.csv")
    Q = trapezoid(R[:, :, None] * np.column_stack(Sd)[:, None, :], WL, axis=0)
    ds = [ds_matrix(np.log(Q[a] / Q[b]), e) for a, b in combinations(range(Q.shape[0]), 2)]
    res["flowers_mean_dS_trapezoid_datafile"] = float(np.mean(ds))
    print("  with data/vision/avian_uv_endler_mielke_2005.csv, trapezoid: %.4f" % np.mean(ds))
    # trispace regression (pavo result9): colspace(vismodel(flowers, visual = "apis", achromatic = "l"))
    Sa = np.column_stack([np.asarray(v["apis." + k], float) for k in "sml"])
    Qa = R.T @ Sa
    rel = Qa / Qa.sum(axis=1, keepdims=True)
    lum = Qa[:, 2]
    x = (rel[:, 2] - rel[:, 1]) / np.sqrt(2)
    y = np.sqrt(2 / 3) * (rel[:, 0] - (rel[:, 2] + rel[:, 1]) / 2)
    cols = np.column_stack([rel, lum, x, y, np.arctan2(y, x), np.hypot(x, y)])
    res["flowers_trispace_mean"] = float(cols.mean())
    print("pavo regression trispace(apis): mean of s, m, l, lum, x, y, h.theta, r.vec = 0.0876 (pavo); numpy: %.4f"
          % cols.mean())
    tt = sysdata["ttvertex"]
    mine = coords("tetrahedron", [1, 0, 0, 0], None)
    print("tetrahedron UV vertex: pavo", [float(np.asarray(tt[k]).ravel()[0]) for k in ("xu", "yu", "zu")], "numpy", mine)
    return res


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pavo", help="a git checkout of pavo, to check against its values")
    args = ap.parse_args()
    spectra = test_spectra()
    with open(os.path.join(ROOT, "data", "examples", "vision_spectra.csv"), "w") as f:
        f.write("wl," + ",".join(spectra) + "\n")
        for i, w in enumerate(WL):
            f.write("%g," % w + ",".join("%.6f" % spectra[k][i] for k in spectra) + "\n")
    # the fixtures use the spectra exactly as written to the CSV
    _, _, v = read_csv(os.path.join(ROOT, "data", "examples", "vision_spectra.csv"))
    spectra = {k: v[:, j] for j, k in enumerate(spectra)}
    out = {"generator": "tools/gen_vision_fixtures.py", "numpy": np.__version__, "spectra_csv": "data/examples/vision_spectra.csv"}
    wl_t = np.arange(300.0, 801.0, 10.0)
    out["templates"] = [{"lambda_max_nm": l, "chromophore": c, "wavelength_nm": wl_t.tolist(),
                         "alpha": alpha(l, wl_t, c).tolist(), "beta": beta(l, wl_t, c).tolist()}
                        for c in ("A1", "A2") for l in (350.0, 420.0, 500.0, 560.0, 620.0)]
    out["droplets"] = [{"type": k, "lambda_cut_nm": lc, "wavelength_nm": wl_t.tolist(),
                        "transmittance": droplet(wl_t, k, lc).tolist()}
                       for k, lc in (("C", 413.0), ("Y", 507.0), ("R", 572.0), ("P", 440.0))]
    out["cases"] = []
    for case in CASES:
        r = analyse(case, spectra)
        out["cases"].append(dict(case, **r))
    if args.pavo:
        out["pavo_checks"] = pavo_checks(args.pavo)
    path = os.path.join(ROOT, "crates", "vision", "tests", "fixtures", "vision_numpy.json")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
    print("wrote", path)


if __name__ == "__main__":
    main()
