#!/usr/bin/env python3
"""Colours of many thin-film stacks with Dask: the same script on a laptop or on a cluster.

Every stack is "air | layer 1 | layer 2 | glass" with random indices and thicknesses (seeded, so a run is
reproducible); its reflected colour under D65 at the given angle is computed by iridis
(``iridis.thinfilm.colors_of_stacks``, in parallel inside each task, the GIL released). The stacks are split
into chunks and the chunks are spread over the Dask workers.

    python examples/python/film_colors_dask.py                          # 10⁵ stacks on a LocalCluster
    python examples/python/film_colors_dask.py --stacks 1000000 --scheduler tcp://head-node:8786
    python examples/python/film_colors_dask.py --serial                 # no Dask, for comparison

On a cluster: start a scheduler (``dask scheduler``) and workers (``dask worker tcp://head-node:8786``) on
machines that have ``pip install ./crates/python`` (the same iridis version), then pass the scheduler's address
with ``--scheduler``. Results are written with ``--out colors.npz`` (XYZ, Lab, hex, and the stacks).
"""
from __future__ import annotations

import argparse
import functools
import time

import numpy as np

import iridis.color as color
import iridis.thinfilm as tf


def make_stacks(count, seed=0):
    """``count`` two-layer stacks on glass: indices (count, 4) and thicknesses (count, 2) in nm."""
    rng = np.random.default_rng(seed)
    n = np.empty((count, 4), dtype=np.complex128)
    n[:, 0] = 1.0
    n[:, 1] = rng.uniform(1.3, 1.7, count)
    n[:, 2] = rng.uniform(1.8, 2.5, count) + 1j * rng.uniform(0.0, 0.02, count)
    n[:, 3] = 1.52
    d = rng.uniform(20.0, 400.0, (count, 2))
    return n, d


def reflected_xyz(indices, thicknesses, angle_rad):
    """One chunk: the reflected XYZ of its stacks (runs on a worker)."""
    return tf.colors_of_stacks(indices, thicknesses, angle_rad)["reflected"]


def serial(count, angle_rad=0.0, seed=0):
    n, d = make_stacks(count, seed)
    return reflected_xyz(n, d, angle_rad)


def distributed(client, count, angle_rad=0.0, seed=0, chunk=10_000):
    """The same colours, computed by the workers of ``client``, chunk by chunk, in order."""
    n, d = make_stacks(count, seed)
    starts = range(0, count, chunk)
    # The task is a library function (importable on every worker), not one of this script's.
    task = functools.partial(tf.colors_of_stacks, angle_rad=angle_rad)
    # scatter sends each chunk once; map runs one task per chunk on whichever worker is free.
    n_parts = client.scatter([n[s:s + chunk] for s in starts])
    d_parts = client.scatter([d[s:s + chunk] for s in starts])
    futures = client.map(task, n_parts, d_parts)
    return np.concatenate([part["reflected"] for part in client.gather(futures)])


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--stacks", type=int, default=100_000, help="how many stacks (default 100000)")
    p.add_argument("--angle", type=float, default=0.0, help="incidence angle in degrees (default 0)")
    p.add_argument("--chunk", type=int, default=10_000, help="stacks per task (default 10000)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--scheduler", help="a Dask scheduler's address (tcp://host:8786); default: a LocalCluster")
    p.add_argument("--workers", type=int, default=2, help="LocalCluster workers (default 2)")
    p.add_argument("--serial", action="store_true", help="no Dask: compute in this process")
    p.add_argument("--out", help="write XYZ, Lab, hex and the stacks to this .npz")
    a = p.parse_args(argv)
    if a.stacks <= 0 or a.chunk <= 0:
        p.error("--stacks and --chunk must be positive")
    angle = np.radians(a.angle)
    if a.serial:
        t0 = time.perf_counter()
        xyz = serial(a.stacks, angle, a.seed)
        where = "this process"
    else:
        from dask.distributed import Client, LocalCluster

        if a.scheduler:
            client = Client(a.scheduler)
            where = f"the cluster at {a.scheduler}"
        else:
            cluster = LocalCluster(n_workers=a.workers, threads_per_worker=1, dashboard_address=None)
            client = Client(cluster)
            where = f"a LocalCluster of {a.workers} workers"
        with client:
            t0 = time.perf_counter()  # the work, not the cluster's start
            xyz = distributed(client, a.stacks, angle, a.seed, a.chunk)
    seconds = time.perf_counter() - t0
    lab = color.xyz_to_lab(xyz)
    print(f"{a.stacks} stacks at {a.angle}° on {where}: {seconds:.2f} s ({a.stacks / seconds:,.0f} stacks/s)")
    print(f"L* from {lab[:, 0].min():.1f} to {lab[:, 0].max():.1f}; first colours: {color.xyz_to_hex(xyz[:3])}")
    if a.out:
        n, d = make_stacks(a.stacks, a.seed)
        np.savez(a.out, xyz=xyz, lab=lab, hex=np.array(color.xyz_to_hex(xyz)), indices=n, thicknesses_nm=d)
        print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
