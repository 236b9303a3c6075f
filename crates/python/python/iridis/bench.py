"""``python -m iridis.bench``: iridis.tmm against its peers in the same run, on this machine.

1. call by call: ``iridis.tmm.coh_tmm`` against ``tmm.coh_tmm`` (same arguments, a loop of calls reading
   ``['R']``; and reading every key);
2. a batch of (λ, θ) points: ``iridis.tmm.coh_tmm_batch`` against a loop of ``tmm.coh_tmm`` and, where it is
   installed, ``tmm_fast`` (PyTorch, CPU) on the same grid;
3. issue 29's absorbing stack ``[1, 1.4, 1.33+0.001j, 1.635]`` over 10⁵ wavelengths at one angle, the same way.

Every result is checked against tmm's before it is timed. Options: ``--points N`` (batch size, default 10⁵),
``--tmm-points N`` (how many of the batch's points tmm runs, default all; fewer are timed and scaled, which
the output says), ``--json``.

``python -m iridis.bench NAME [options]`` runs instead the library's bench NAME — ``diffraction``,
``diffraction-accuracy``, ``diffraction-methods``, ``gpu``, ``render``, ``grating`` — the very function
``iridis bench NAME`` calls (``iridis_api::bench``), with its options (``--map-size 8``, ``--surface S``
repeated, ``--exposures 1,1000``, ``--coherence-nm``, …) and its text or ``--json``. From Python:
``run(NAME, **options)`` returns the JSON as a dict, ``report(NAME, **options)`` the text and the dict.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import time

import numpy as np

from . import _native
from ._gpu import ensure_gpu_environment
from . import tmm as itmm

STACKS = {
    "3 layers": ([1.0, 1.38, 2.35 + 0.01j, 1.46, 1.52], [np.inf, 95.0, 60.0, 140.0, np.inf]),
    "10 layers": ([1.0] + [2.35, 1.46] * 5 + [1.52], [np.inf] + [60.0, 95.0] * 5 + [np.inf]),
}


def best_of(fn, repeat=3):
    """The fastest of `repeat` runs of fn(), in seconds (the least disturbed by other work)."""
    return best_of_with_cpu(fn, repeat)[0]


def best_of_with_cpu(fn, repeat=3):
    """The fastest of `repeat` runs of fn(): wall-clock seconds and the process' CPU seconds (all threads).
    CPU time counts no time spent waiting for a core, so on a loaded machine it is the steadier measure of work;
    a ratio of CPU times compares one core's work against one core's."""
    wall = cpu = float("inf")
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        fn()
        wall, cpu = min(wall, time.perf_counter() - t0), min(cpu, time.process_time() - c0)
    return wall, cpu


def call_by_call(tmm, calls):
    rows = []
    for name, (n, d) in STACKS.items():
        lam = np.linspace(400, 700, calls)
        a = [tmm.coh_tmm("p", n, d, 0.3, x)["R"] for x in lam[:50]]
        b = [itmm.coh_tmm("p", n, d, 0.3, x)["R"] for x in lam[:50]]
        assert np.max(np.abs(np.array(a) - b)) < 1e-9, "iridis.tmm disagrees with tmm"
        t_tmm = best_of(lambda: [tmm.coh_tmm("p", n, d, 0.3, x)["R"] for x in lam])
        t_iri = best_of(lambda: [itmm.coh_tmm("p", n, d, 0.3, x)["R"] for x in lam])
        t_all = best_of(lambda: [dict(itmm.coh_tmm("p", n, d, 0.3, x)) for x in lam])
        rows.append({"stack": name, "calls": calls, "tmm_us": t_tmm / calls * 1e6, "iridis_us": t_iri / calls * 1e6,
                     "iridis_all_keys_us": t_all / calls * 1e6, "speedup": t_tmm / t_iri,
                     "speedup_all_keys": t_tmm / t_all})
    return rows


def batch(tmm, points, tmm_points):
    n, d = STACKS["3 layers"]
    k = max(1, int(round(points / 1000)))
    lam = np.linspace(380.0, 780.0, points // k)
    th = np.linspace(0.0, np.radians(85.0), k)
    grid_th, grid_lam = np.meshgrid(th, lam)
    t_iri, cpu_iri = best_of_with_cpu(lambda: itmm.coh_tmm_batch("s", n, d, grid_th, grid_lam))
    out = itmm.coh_tmm_batch("s", n, d, grid_th, grid_lam)
    flat_th, flat_lam, flat_r = grid_th.ravel(), grid_lam.ravel(), out["R"].ravel()
    total = flat_th.size
    m = total if tmm_points is None else min(tmm_points, total)
    pick = np.linspace(0, total - 1, m).astype(int)
    t0, c0 = time.perf_counter(), time.process_time()
    ref = np.array([tmm.coh_tmm("s", n, d, flat_th[i], flat_lam[i])["R"] for i in pick])
    t_tmm = (time.perf_counter() - t0) * total / m
    cpu_tmm = (time.process_time() - c0) * total / m
    worst = float(np.max(np.abs(ref - flat_r[pick])))
    assert worst < 1e-9, f"coh_tmm_batch disagrees with tmm by {worst}"
    row = {"points": total, "grid": f"{lam.size} λ × {th.size} θ", "stack": "3 layers", "iridis_s": t_iri,
           "tmm_s": t_tmm, "tmm_points_timed": m, "speedup": t_tmm / t_iri, "worst_abs_diff_R": worst,
           "iridis_cpu_s": cpu_iri, "tmm_cpu_s": cpu_tmm, "speedup_cpu": cpu_tmm / cpu_iri}
    row["tmm_fast"] = tmm_fast_peer(n, d, th, lam, out["R"])
    return row


def absorbing(tmm, points, tmm_points):
    """Issue 29's measurement: a 2-layer stack with one absorbing layer, many wavelengths at one angle."""
    n, d = [1.0, 1.4, 1.33 + 0.001j, 1.635], [np.inf, 100.0, 300.0, np.inf]
    lam = np.linspace(380.0, 780.0, points)
    t_iri, cpu_iri = best_of_with_cpu(lambda: itmm.coh_tmm_batch("s", n, d, 0.0, lam))
    out = itmm.coh_tmm_batch("s", n, d, 0.0, lam)
    m = points if tmm_points is None else min(tmm_points, points)
    pick = np.linspace(0, points - 1, m).astype(int)
    t0, c0 = time.perf_counter(), time.process_time()
    ref = np.array([tmm.coh_tmm("s", n, d, 0.0, lam[i])["R"] for i in pick])
    t_tmm = (time.perf_counter() - t0) * points / m
    cpu_tmm = (time.process_time() - c0) * points / m
    worst = float(np.max(np.abs(ref - out["R"][pick])))
    assert worst < 1e-9, f"coh_tmm_batch disagrees with tmm by {worst}"
    return {"points": points, "stack": "[1, 1.4, 1.33+0.001j, 1.635], 100 nm / 300 nm, θ = 0", "iridis_s": t_iri,
            "tmm_s": t_tmm, "tmm_points_timed": m, "speedup": t_tmm / t_iri, "worst_abs_diff_R": worst,
            "iridis_cpu_s": cpu_iri, "tmm_cpu_s": cpu_tmm, "speedup_cpu": cpu_tmm / cpu_iri}


def tmm_fast_peer(n, d, th, lam, reference):
    """tmm_fast (PyTorch) on the same grid, CPU, where installed."""
    try:
        import torch
        import tmm_fast
    except ImportError as e:
        return {"skipped": f"tmm_fast is not installed ({e.name}); pip install tmm-fast (pulls PyTorch) to add it"}
    N = torch.tensor(np.tile(np.asarray(n, complex)[None, :, None], (1, 1, lam.size)), dtype=torch.complex128)
    T = torch.tensor(np.asarray(d, float)[None, :], dtype=torch.float64)
    Th = torch.tensor(th, dtype=torch.float64)
    L = torch.tensor(lam, dtype=torch.float64)
    run = lambda: tmm_fast.coh_tmm("s", N, T, Th, L, device="cpu")  # noqa: E731
    res = run()
    r = np.asarray(res["R"]).reshape(th.size, lam.size).T
    seconds, cpu = best_of_with_cpu(run)
    return {"seconds": seconds, "cpu_seconds": cpu, "worst_abs_diff_R": float(np.max(np.abs(r - reference))),
            "torch_threads": torch.get_num_threads()}

# How a bench reads its SURFACE arguments (lengths in nm), as the CLI's surface flags.
_SURFACE_OPTIONS = {"pixel_size_nm": float, "max_height_nm": float, "channel": str, "height_unit": str,
                    "level": str, "override_units": bool, "as_height": bool}
# The library's benches (iridis_api::bench) and their options: type, and for lists how they are written.
LIBRARY_BENCHES = {
    "diffraction": {"size": int, "terms": int, "map_sizes": [int], "uv_resolution": int},
    "diffraction-accuracy": {"surface": [str], "map_size": int, "coherence_nm": float, "aperture": str,
                             "exposures": [float], "uv_resolution": int, "convergence_plot": str,
                             **_SURFACE_OPTIONS},
    "diffraction-methods": {"patch_sizes": [int], "map_size": int},
    "gpu": {"scene": str, "size": str, "frames": int, "max_seconds": float, "table": str, "film_size": str,
            "stack": str, "spectral_samples": int, "save": str, "table_precision": str, "build_surface": str,
            "build_uv_resolution": int, "gt_surface": str, "gt_size": int, "gt_cpu_pixels": int,
            **_SURFACE_OPTIONS},
    "render": {"size": int, "spp": int, "scene": [str]},
    "grating": {"repeats": int, "python": str, "no_python": bool, "peer_seconds": float, "batch": int,
                "quick": bool},
}
# Repeated options of the CLI (--surface S --surface T) are lists under a plural name.
_PLURAL = {"surface": "surfaces", "scene": "scenes"}


def report(name, **options):
    """Runs the library bench ``name`` (``iridis bench NAME``'s very function) with ``options`` (the CLI's
    option names with ``_``; lengths in nm): its text, as ``iridis bench NAME`` prints it, and its JSON as a
    dict, as ``--json`` prints it."""
    text, data = _raw(name, options)
    return text, json.loads(data)


def _raw(name, options):
    """The bench's text and its JSON text (formatted as the CLI prints it)."""
    if name not in LIBRARY_BENCHES:
        raise ValueError(f"no bench {name!r}: the benches are {', '.join(LIBRARY_BENCHES)}")
    if name == "gpu":
        ensure_gpu_environment()
    return _native.bench_run(name, options)


def run(name, **options):
    """The JSON of the library bench ``name`` as a dict (see :func:`report`)."""
    return report(name, **options)[1]


def library_main(name, argv):
    """``python -m iridis.bench NAME [--option value …] [--json]``."""
    p = argparse.ArgumentParser(prog=f"python -m iridis.bench {name}",
                                description=f"iridis bench {name}, the library's function (iridis_api::bench)")
    for key, kind in LIBRARY_BENCHES[name].items():
        flag = "--" + key.replace("_", "-")
        if kind is bool:
            p.add_argument(flag, action="store_true", default=None)
        elif isinstance(kind, list) and key in _PLURAL:
            p.add_argument(flag, dest=_PLURAL[key], action="append", type=kind[0])
        elif isinstance(kind, list):
            p.add_argument(flag, type=lambda v, t=kind[0]: [t(x) for x in v.split(",")])
        else:
            p.add_argument(flag, type=kind)
    p.add_argument("--json", action="store_true")
    a = vars(p.parse_args(argv))
    as_json = a.pop("json")
    options = {k: v for k, v in a.items() if v is not None}
    text, data = _raw(name, options)
    print(data if as_json else text)


def main(argv=None):
    import sys

    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] in LIBRARY_BENCHES:
        return library_main(argv[0], argv[1:])
    if argv and argv[0] == "tmm":
        argv = argv[1:]
    p = argparse.ArgumentParser(prog="python -m iridis.bench [tmm]", description=__doc__.split("\n\n")[0])
    p.add_argument("--points", type=int, default=100_000)
    p.add_argument("--tmm-points", type=int, default=None)
    p.add_argument("--calls", type=int, default=2000)
    p.add_argument("--json", action="store_true")
    a = p.parse_args(argv)
    try:
        import tmm
    except ImportError:
        raise SystemExit("the peer, tmm, is not installed: pip install tmm")
    info = {"machine": platform.machine(), "cpus": os.cpu_count(), "python": platform.python_version(),
            "numpy": np.__version__, "tmm": getattr(tmm, "__version__", "?")}
    calls = call_by_call(tmm, a.calls)
    b = batch(tmm, a.points, a.tmm_points)
    ab = absorbing(tmm, a.points, a.tmm_points)
    try:
        info["load_average"] = os.getloadavg()
    except OSError:
        pass
    if a.json:
        print(json.dumps({"info": info, "call_by_call": calls, "batch": b, "absorbing": ab}, indent=1))
        return
    print(f"iridis.bench on {info['cpus']} CPUs, Python {info['python']}, numpy {info['numpy']} "
          "(best of 3 runs each; every result checked against tmm first)")
    print("\ncoh_tmm, call by call (p, θ = 0.3 rad, reading ['R']):")
    print(f"  {'stack':<10} {'tmm µs':>9} {'iridis µs':>10} {'speed-up':>9} {'all keys µs':>12} {'speed-up':>9}")
    for r in calls:
        print(f"  {r['stack']:<10} {r['tmm_us']:9.1f} {r['iridis_us']:10.2f} {r['speedup']:8.0f}× "
              f"{r['iridis_all_keys_us']:12.2f} {r['speedup_all_keys']:8.0f}×")
    scaled = "" if b["tmm_points_timed"] == b["points"] else f" (tmm timed on {b['tmm_points_timed']} points, scaled)"
    print(f"\ncoh_tmm_batch over {b['points']} (λ, θ) points ({b['grid']}, {b['stack']}, s):")
    print(f"  tmm loop     {b['tmm_s']:9.3f} s  (CPU {b['tmm_cpu_s']:.3f} s){scaled}")
    print(f"  iridis       {b['iridis_s']:9.4f} s  (CPU {b['iridis_cpu_s']:.4f} s, all threads)   {b['speedup']:.0f}× "
          f"wall, {b['speedup_cpu']:.0f}× CPU (worst |ΔR| {b['worst_abs_diff_R']:.1e})")
    tf = b["tmm_fast"]
    if "skipped" in tf:
        print(f"  tmm_fast     skipped: {tf['skipped']}")
    else:
        print(f"  tmm_fast     {tf['seconds']:9.4f} s  (CPU {tf['cpu_seconds']:.3f} s)   iridis "
              f"{tf['seconds'] / b['iridis_s']:.1f}× faster wall, {tf['cpu_seconds'] / b['iridis_cpu_s']:.1f}× CPU "
              f"(worst |ΔR| {tf['worst_abs_diff_R']:.1e}, {tf['torch_threads']} torch threads)")
    scaled = "" if ab["tmm_points_timed"] == ab["points"] else f" (tmm timed on {ab['tmm_points_timed']} points, scaled)"
    print(f"\ncoh_tmm_batch over {ab['points']} wavelengths of {ab['stack']} (issue 29), s:")
    print(f"  tmm loop     {ab['tmm_s']:9.3f} s  (CPU {ab['tmm_cpu_s']:.3f} s){scaled}")
    print(f"  iridis       {ab['iridis_s']:9.4f} s  (CPU {ab['iridis_cpu_s']:.4f} s, all threads)   {ab['speedup']:.0f}× "
          f"wall, {ab['speedup_cpu']:.0f}× CPU (worst |ΔR| {ab['worst_abs_diff_R']:.1e})")
    if "load_average" in info:
        print(f"\nload average during the run: {', '.join(f'{x:.1f}' for x in info['load_average'])}")


if __name__ == "__main__":
    main()
