"""examples/python/film_colors_dask.py on a two-worker LocalCluster at small size: the same colours as the
serial computation, bit for bit, and as iridis.thinfilm.Stack for single stacks."""
import importlib.util
import os

import numpy as np
import pytest

from conftest import ROOT

distributed = pytest.importorskip("dask.distributed", reason="dask[distributed] is not installed")


def example(name):
    """examples/python/NAME.py as a module."""
    path = os.path.join(ROOT, "examples", "python", f"{name}.py")
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_two_worker_cluster_equals_serial():
    ex = example("film_colors_dask")
    count, angle = 2500, np.radians(25.0)
    expected = ex.serial(count, angle, seed=7)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            got = ex.distributed(client, count, angle, seed=7, chunk=600)
            assert len(client.scheduler_info()["workers"]) == 2
    assert got.shape == (count, 3)
    np.testing.assert_array_equal(got, expected)
    # and each row is the colour of its stack, as the single-stack API computes it
    import iridis.thinfilm as tf

    n, d = ex.make_stacks(count, seed=7)
    for i in (0, 1234, count - 1):
        np.testing.assert_allclose(got[i], tf.Stack.from_lists(n[i], d[i]).color(angle)["reflected"], rtol=0, atol=1e-14)


def test_brdf_maps_on_two_workers_equal_serial():
    ex = example("brdf_maps_dask")
    specs = ["builtin:sine?size=4um&pixel=100nm", "builtin:blazed?size=4um&pixel=100nm"]
    expected = ex.serial(specs, [0.0, 40.0], size=17)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            got = ex.distributed(client, specs, [0.0, 40.0], size=17)
    assert len(got) == 4
    for g, e in zip(got, expected):
        assert g.shape == (17, 17, 3)
        np.testing.assert_array_equal(g, e)
