#!/usr/bin/env python3
"""Reference values for the position-resolved profile of stacks with incoherent layers
(iridis_thinfilm::incoherent::Profile), from the `tmm` package (S. J. Byrnes, https://pypi.org/project/tmm/,
MIT licence), written to crates/thinfilm/tests/fixtures/tmm_inc_profile.json. The Rust tests read that file;
they do not need Python.

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install tmm numpy
    /tmp/venv/bin/python tools/gen_inc_profile_fixtures.py

tmm 0.2.0 (the release on PyPI) has no `inc_position_resolved`; what it has is
`inc_find_absorp_analytic_fn(layer, inc_tmm_data)`, the absorbed power density in a coherent layer of a mixed
stack (the group's coherent solution lit from above scaled by the forward intensity F plus the one lit from
below scaled by B). So, per random mixed stack, wavelength, angle and polarisation:

  * coherent layers: absorption from `inc_find_absorp_analytic_fn(...).run(z)` (its two halves
    run and summed, see inc_absorp_at); the flux and |E|² from
    `position_resolved` on tmm's own forward and backward group solutions (`coh_tmm_data_list`,
    `coh_tmm_bdata_list`) weighted by tmm's `stackFB_list` intensities (flux F S_f − B S_b; |E|² F' |E_f|² +
    B' |E_b|², each intensity converted to the group's incident amplitude, flux per |E|² = Re(n cos θ) for s,
    Re(n conj(cos θ)) for p, relative to the stack's incident medium);
  * incoherent layers: Beer–Lambert on tmm's forward and backward intensities at the layer's top
    (`VW_list`), α = 4π Im(n cos θ)/λ with tmm's angles (`list_snell`): flux V e^{−αz} − W e^{αz}, absorption
    α (V e^{−αz} + W e^{αz}); tmm's `inc_absorp_in_each_layer` is stored too (the profile must integrate to it);
  * the substrate just below the last interface: the flux is tmm's T.
"""
import json
import math
import os
import random
import sys

import numpy as np
import tmm

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gen_incoherent_fixtures import max_im_delta, random_layers, stack_string, write_compact  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "crates", "thinfilm", "tests", "fixtures", "tmm_inc_profile.json")


def flux_per_e2(n, th, pol):
    c = np.cos(th)
    return float((n * (np.conj(c) if pol == "p" else c)).real)


def inc_absorp_at(layer, res, z):
    """tmm.inc_find_absorp_analytic_fn(layer, res).run(z), step by step: tmm's own `add` refuses to sum the
    forward and backward functions when their wave vectors differ in the last bit (they are computed through
    the stack in opposite directions), so the two are run separately and summed, which is what `add` does."""
    stack_i, within = res["stack_from_all"][layer]
    f = tmm.absorp_analytic_fn().fill_in(res["coh_tmm_data_list"][stack_i], within)
    f.scale(res["stackFB_list"][stack_i][0])
    b = tmm.absorp_analytic_fn().fill_in(res["coh_tmm_bdata_list"][stack_i], -1 - within)
    b.scale(res["stackFB_list"][stack_i][1])
    b.flip()
    return f.run(z) + b.run(z)


def one_pol(pol, ns, ds, cs, th0, lam, points):
    res = tmm.inc_tmm(pol, ns, ds, cs, th0, lam)
    th = tmm.list_snell(np.array(ns), th0)
    norm = flux_per_e2(ns[0], th0, pol)
    out = []
    for pt in points:
        layer, z = pt["medium"], pt["dz"]
        if layer == len(ns) - 1:
            out.append({"poyn": float(res["T"])})
            continue
        if cs[layer] == "c":
            stack_i, within = res["stack_from_all"][layer]
            fwd, bwd = res["coh_tmm_data_list"][stack_i], res["coh_tmm_bdata_list"][stack_i]
            big_f, big_b = res["stackFB_list"][stack_i]
            absor = float(np.real(inc_absorp_at(layer, res, z)))
            rf = tmm.position_resolved(within, z, fwd)
            rb = tmm.position_resolved(len(bwd["n_list"]) - 1 - within, ds[layer] - z, bwd)
            e2 = lambda r: abs(r["Ex"]) ** 2 + abs(r["Ey"]) ** 2 + abs(r["Ez"]) ** 2
            top = flux_per_e2(fwd["n_list"][0], fwd["th_list"][0], pol)
            bottom = flux_per_e2(bwd["n_list"][0], bwd["th_list"][0], pol)
            out.append({
                "absor": absor,
                "poyn": float(big_f * np.real(rf["poyn"]) - big_b * np.real(rb["poyn"])),
                "e2": float(big_f * norm / top * e2(rf) + big_b * norm / bottom * e2(rb)),
            })
        else:
            k = res["inc_from_all"][layer]
            v, w = res["VW_list"][k]
            alpha = 4 * math.pi * (ns[layer] * np.cos(th[layer])).imag / lam
            fw, bw = v * math.exp(-alpha * z), w * math.exp(alpha * z)
            out.append({"absor": float(alpha * (fw + bw)), "poyn": float(fw - bw)})
    absorp = [float(a) for a in tmm.inc_absorp_in_each_layer(res)]
    return {"points": out, "absorp": absorp, "R": float(res["R"]), "T": float(res["T"])}


def cases(rng, count):
    found = []
    while len(found) < count:
        ns, ds, cs = random_layers(rng, rng.randint(2, 7), 0.35)
        if "i" not in cs[1:-1]:
            continue
        lam = rng.uniform(380.0, 780.0)
        th0 = rng.choice([0.0, math.pi / 2 * 0.9 * rng.random()])
        if max_im_delta(ns, ds, cs, th0, lam) > 30:
            continue
        # Incoherent layers that absorb noticeably, so their profile is not flat.
        for i in range(1, len(ns) - 1):
            if cs[i] == "i" and rng.random() < 0.7:
                ns[i] = complex(ns[i].real, rng.uniform(1e-6, 1e-4) * 1e6 / ds[i])
        points = []
        for layer in range(1, len(ns)):
            if layer == len(ns) - 1:
                points.append({"medium": layer, "dz": 0.0})
            else:
                for z in (0.0, rng.uniform(0.0, ds[layer]), ds[layer]):
                    points.append({"medium": layer, "dz": z})
        case = {"stack": stack_string(ns, ds, cs), "wavelength_nm": lam, "angle_rad": th0, "points": points}
        ok = True
        for pol in ("s", "p"):
            with np.errstate(all="ignore"):
                r = one_pol(pol, ns, ds, cs, th0, lam, points)
            vals = [v for p in r["points"] for v in p.values()] + r["absorp"]
            if not all(math.isfinite(v) for v in vals):
                ok = False
                break
            case[pol] = r
        if ok:
            found.append(case)
    return found


def main():
    rng = random.Random(20261124)
    doc = {
        "reference": f"tmm {tmm.__version__ if hasattr(tmm, '__version__') else '0.2.0'} (inc_tmm, "
                     f"inc_find_absorp_analytic_fn, position_resolved, VW_list, stackFB_list, "
                     f"inc_absorp_in_each_layer), numpy {np.__version__}",
        "cases": cases(rng, 120),
    }
    write_compact("tools/gen_inc_profile_fixtures.py", doc, OUT, f"{len(doc['cases'])} cases")


if __name__ == "__main__":
    main()
