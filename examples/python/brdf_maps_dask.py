#!/usr/bin/env python3
"""BRDF maps of several surfaces with Dask: one task per (surface, incidence), on a LocalCluster or a cluster.

Each task (``iridis.diffraction.brdf_map_of``) loads its surface on the worker (a file path every worker can read, or a built-in such as
``builtin:elaphe?size=12um&pixel=60nm``), computes the BRDF map with iridis (``iridis.diffraction``, the
reference evaluator by default) and sends back the linear XYZ array; the client writes one ``.npz`` with all
maps (and, per map, its sRGB at the given exposure).

    python examples/python/brdf_maps_dask.py                                   # the built-in skins, LocalCluster
    python examples/python/brdf_maps_dask.py scan1.gwy scan2.spm --scheduler tcp://head-node:8786 --out maps.npz
    python examples/python/brdf_maps_dask.py --serial                          # no Dask, for comparison

On a cluster, every worker needs ``pip install ./crates/python`` and the files at the same paths (or use
built-ins); see film_colors_dask.py for starting a scheduler and workers.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

import iridis.color as color
import iridis.diffraction as diffraction

DEFAULT_SURFACES = [
    "builtin:elaphe?size=8um&pixel=80nm",
    "builtin:xenopeltis?size=8um&pixel=80nm",
    "builtin:blazed?size=8um&pixel=80nm",
    "builtin:sine?size=8um&pixel=80nm",
]


def jobs(specs, angles):
    return [(s, a) for s in specs for a in angles]


def serial(specs, angles, size=64, method="reference"):
    return [diffraction.brdf_map_of(s, np.radians(a), size, method) for s, a in jobs(specs, angles)]


def distributed(client, specs, angles, size=64, method="reference"):
    todo = jobs(specs, angles)
    # The task is a library function (importable on every worker), not one of this script's.
    futures = [client.submit(diffraction.brdf_map_of, s, np.radians(a), size, method) for s, a in todo]
    return client.gather(futures)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("surfaces", nargs="*", help="files or builtin:… specs (default: four built-ins)")
    p.add_argument("--angles", default="0,30,60", help="incidence angles θ_i in degrees (default 0,30,60)")
    p.add_argument("--size", type=int, default=64, help="map size in pixels (default 64)")
    p.add_argument("--method", default="reference", choices=["reference", "ground-truth"])
    p.add_argument("--exposure", type=float, default=1500.0, help="for the sRGB previews (default 1500 RU)")
    p.add_argument("--scheduler", help="a Dask scheduler's address; default: a LocalCluster")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--serial", action="store_true")
    p.add_argument("--out", default="brdf_maps.npz")
    a = p.parse_args(argv)
    specs = a.surfaces or DEFAULT_SURFACES
    angles = [float(x) for x in a.angles.split(",")]
    if a.serial:
        t0 = time.perf_counter()
        maps = serial(specs, angles, a.size, a.method)
        where = "this process"
    else:
        from dask.distributed import Client, LocalCluster

        if a.scheduler:
            client, where = Client(a.scheduler), f"the cluster at {a.scheduler}"
        else:
            client = Client(LocalCluster(n_workers=a.workers, threads_per_worker=1, dashboard_address=None))
            where = f"a LocalCluster of {a.workers} workers"
        with client:
            t0 = time.perf_counter()
            maps = distributed(client, specs, angles, a.size, a.method)
    seconds = time.perf_counter() - t0
    names = [f"{s} @ {t:g}°" for s, t in jobs(specs, angles)]
    xyz = np.stack(maps)
    np.savez(a.out, xyz=xyz, srgb=color.xyz_to_srgb(xyz, exposure=a.exposure), names=np.array(names))
    print(f"{len(maps)} maps of {a.size}² ({a.method}) on {where}: {seconds:.2f} s; wrote {a.out}")


if __name__ == "__main__":
    main()
