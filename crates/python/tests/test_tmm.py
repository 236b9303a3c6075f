"""iridis.tmm against the tmm package: the committed 1184-case fixture (tools/gen_thinfilm_fixtures.py) to
1e-9, every key of coh_tmm against a live tmm where it is installed, inc_tmm, ellips, the batch, and errors."""
import math

import numpy as np
import pytest

import iridis.thinfilm as tf
import iridis.tmm as itmm


def lists(stack, wavelength):
    """tmm's n_list and d_list of a fixture stack (library materials such as Aspnes' Si at the wavelength)."""
    s = tf.Stack(stack)
    n = s.indices([wavelength])[:, 0]
    return n, [np.inf] + [_thickness(t) for t in stack.split("|")[1:-1]] + [np.inf]


def _thickness(segment):
    word = segment.split()[-1]
    assert word.endswith("nm"), segment
    return float(word[:-2])


def c(v):
    return complex(v[0], v[1])


def test_coh_tmm_matches_the_1184_case_fixture(tmm_reference):
    cases = tmm_reference["cases"]
    assert len(cases) == 1184
    worst = 0.0
    for case in cases:
        n, d = lists(case["stack"], case["wavelength_nm"])
        for pol in "sp":
            x = itmm.coh_tmm(pol, n, d, case["angle_rad"], case["wavelength_nm"])
            ref = case[pol]
            diffs = [abs(x["r"] - c(ref["r"])), abs(x["t"] - c(ref["t"])), abs(x["R"] - ref["R"]),
                     abs(x["T"] - ref["T"])]
            assert max(diffs) < 1e-9, (case["stack"], pol, diffs)
            worst = max(worst, *diffs)
            u = itmm.unpolarized_RT(n, d, case["angle_rad"], case["wavelength_nm"])
    print(f"worst |Δ| against the fixture: {worst:.2e}")


def test_batch_matches_the_fixture(tmm_reference):
    # Each fixture stack at its own point, as a batch of one point repeated; and the per-point (dispersive)
    # form with all the points of the 'seed' stacks, whose Si index changes with λ.
    for case in tmm_reference["cases"][:300]:
        n, d = lists(case["stack"], case["wavelength_nm"])
        for pol in "sp":
            b = itmm.coh_tmm_batch(pol, n, d, np.full(3, case["angle_rad"]), case["wavelength_nm"])
            assert np.all(np.abs(b["r"] - c(case[pol]["r"])) < 1e-9)
            assert np.all(np.abs(b["T"] - case[pol]["T"]) < 1e-9)
    seeds = [cs for cs in tmm_reference["cases"] if cs["kind"] == "seed" and "Si" in cs["stack"]]
    assert len(seeds) > 20
    stack = seeds[0]["stack"]
    same = [cs for cs in seeds if cs["stack"] == stack]
    lam = np.array([cs["wavelength_nm"] for cs in same])
    th = np.array([cs["angle_rad"] for cs in same])
    n = tf.Stack(stack).indices(lam)
    _, d = lists(stack, lam[0])
    for pol in "sp":
        b = itmm.coh_tmm_batch(pol, n, d, th, lam)
        assert np.max(np.abs(b["R"] - [cs[pol]["R"] for cs in same])) < 1e-9


tmm = pytest.importorskip("tmm", reason="the tmm package (pip install tmm) is the reference")


def test_every_key_equals_live_tmm(tmm_reference):
    # Not only r, t, R, T: power_entering, vw_list, kz_list, th_list and the echoed arguments, including
    # total internal reflection (complex angles) and absorbing substrates.
    picked = [cs for cs in tmm_reference["cases"] if cs["kind"] != "seed"][::7]
    assert any(cs["kind"] == "tir" for cs in picked) and any(cs["absorbing_substrate"] for cs in picked)
    for case in picked:
        n, d = lists(case["stack"], case["wavelength_nm"])
        for pol in "sp":
            args = (pol, np.asarray(n), np.asarray(d, float), case["angle_rad"], case["wavelength_nm"])
            a, b = tmm.coh_tmm(*args), itmm.coh_tmm(*args)
            assert sorted(a) == sorted(b)
            for k in a:
                if k in ("pol",):
                    assert a[k] == b[k]
                    continue
                va, vb = np.asarray(a[k]), np.asarray(b[k])
                finite = np.isfinite(va)
                assert np.array_equal(finite, np.isfinite(vb)), k
                scale = max(1.0, float(np.max(np.abs(va[finite]), initial=0.0)))
                assert np.max(np.abs(va[finite] - vb[finite]), initial=0.0) < 1e-9 * scale, (case["stack"], pol, k)
            np.testing.assert_allclose(itmm.absorp_in_each_layer(b), tmm.absorp_in_each_layer(a), atol=1e-9)


def test_ellips_and_unpolarized_equal_tmm(tmm_reference):
    for case in tmm_reference["cases"][::13]:
        n, d = lists(case["stack"], case["wavelength_nm"])
        args = (n, d, case["angle_rad"], case["wavelength_nm"])
        e, f = tmm.ellips(*args), itmm.ellips(*args)
        assert abs(e["psi"] - f["psi"]) < 1e-9
        assert abs(math.sin(e["Delta"] - f["Delta"])) < 1e-9 and math.cos(e["Delta"] - f["Delta"]) > 0
        u, v = tmm.unpolarized_RT(*args), itmm.unpolarized_RT(*args)
        assert abs(u["R"] - v["R"]) < 1e-9 and abs(u["T"] - v["T"]) < 1e-9


def test_inc_tmm_matches_the_fixture(tmm_incoherent):
    for case in tmm_incoherent["inc"]:
        stack = case["stack"]
        n = tf.Stack(stack).indices([case["wavelength_nm"]])[:, 0]
        segs = stack.split("|")
        d = [np.inf] + [_inc_thickness(s) for s in segs[1:-1]] + [np.inf]
        cl = ["i"] + ["i" if "inc:" in s else "c" for s in segs[1:-1]] + ["i"]
        for pol in "sp":
            x = itmm.inc_tmm(pol, n, d, cl, case["angle_rad"], case["wavelength_nm"])
            assert abs(x["R"] - case[pol]["R"]) < 1e-9 and abs(x["T"] - case[pol]["T"]) < 1e-9
            np.testing.assert_allclose(itmm.inc_absorp_in_each_layer(x), case[pol]["absorp"], rtol=0, atol=1e-9)


def _inc_thickness(segment):
    word = segment.split()[-1]
    assert word.endswith("nm")
    return float(word[:-2])


def test_batch_broadcasts_and_equals_single_calls():
    n, d = [1.0, 1.46, 2.35 + 0.01j, 1.52], [np.inf, 95.0, 60.0, np.inf]
    lam = np.linspace(380, 780, 41)[:, None]
    th = np.radians([0, 20, 45, 70, 89])[None, :]
    out = itmm.coh_tmm_batch("p", n, d, th, lam)
    assert out["R"].shape == (41, 5) and out["r"].dtype == np.complex128
    for i in (0, 17, 40):
        for j in range(5):
            one = tmm.coh_tmm("p", n, d, th[0, j], lam[i, 0])
            assert abs(out["r"][i, j] - one["r"]) < 1e-12 and abs(out["T"][i, j] - one["T"]) < 1e-12


def test_an_existing_tmm_script_runs_unchanged():
    # tmm's own README pattern: a loop over wavelengths reading ['R'] (here compared with tmm's loop).
    def script(t):
        d_list = [np.inf, 100, 300, np.inf]
        n_list = [1, 2.2, 3.3 + 0.3j, 1]
        return [t.coh_tmm("s", n_list, d_list, 0, lam)["R"] for lam in np.linspace(400, 900, 50)]

    np.testing.assert_allclose(script(itmm), script(tmm), rtol=0, atol=1e-12)


def test_results_pickle_and_copy_as_tmms_dict():
    # tmm's coh_tmm returns a dict: pickled (multiprocessing.Pool.map), copied and deep-copied. iridis' mapping
    # raised TypeError on pickle and had no copy(); it now becomes the same dict. `from tmm.tmm_core import …`.
    import copy
    import pickle

    args = ("p", [1, 1.38, 3.9 + 0.02j], [np.inf, 100, np.inf], 0.4, 550)
    ours, theirs = itmm.coh_tmm(*args), tmm.coh_tmm(*args)
    for d in (pickle.loads(pickle.dumps(ours)), ours.copy(), copy.copy(ours), copy.deepcopy(ours)):
        assert type(d) is dict and sorted(d) == sorted(theirs)
        for k, v in theirs.items():
            np.testing.assert_allclose(np.asarray(d[k], dtype=complex) if k != "pol" else 0,
                                       np.asarray(v, dtype=complex) if k != "pol" else 0, rtol=0, atol=1e-12)
        assert d["pol"] == "p"
    from iridis.tmm.tmm_core import coh_tmm as core_coh_tmm
    assert core_coh_tmm is itmm.coh_tmm


@pytest.mark.parametrize(
    "call, exc, words",
    [
        (lambda: itmm.coh_tmm("x", [1, 1.5], [np.inf, np.inf], 0, 500), ValueError, "Polarization must be 's' or 'p'"),
        (lambda: itmm.coh_tmm("s", [1, 1.5], [0, np.inf], 0, 500), ValueError, "d_list must start and end with inf"),
        (lambda: itmm.coh_tmm("s", [1, 1.5, 2], [np.inf, np.inf], 0, 500), ValueError, "Problem with n_list or d_list"),
        (lambda: itmm.coh_tmm("s", [1, 1.5], [np.inf, np.inf], 2.0, 500), ValueError, "Error in n0 or th0"),
        (lambda: itmm.coh_tmm("s", [1 + 0.1j, 1.5], [np.inf, np.inf], 0.3, 500), ValueError, "must be real"),
        (lambda: itmm.coh_tmm("s", [1, 1.5 - 0.1j], [np.inf, np.inf], 0, 500), ValueError, "gain"),
        (lambda: itmm.coh_tmm("s", [1, 1.5], [np.inf, np.inf], 0, -5), ValueError, "lam_vac"),
        (lambda: itmm.coh_tmm("s", [1, "glass"], [np.inf, np.inf], 0, 500), TypeError, "n_list"),
        (lambda: itmm.coh_tmm("s", [1, 1.5], [np.inf, np.inf], "0", 500), TypeError, "th_0"),
        (lambda: itmm.coh_tmm("s", [1, 1.5], [np.inf, np.inf], 0, np.array([500, 600])), ValueError, "not vectorized"),
        (lambda: itmm.coh_tmm("s", np.ones((2, 2)), [np.inf, np.inf], 0, 500), ValueError, "1-D"),
        (lambda: itmm.coh_tmm_batch("s", [1, 1.5], [np.inf, np.inf], np.zeros(3), np.ones(4)), ValueError, "broadcast"),
        (lambda: itmm.coh_tmm_batch("s", np.ones((2, 5)), [np.inf, np.inf], 0, np.ones(4)), ValueError, "per medium"),
        (lambda: itmm.coh_tmm_batch("s", ["a", "b"], [np.inf, np.inf], 0, 500), TypeError, "n_list"),
        (lambda: itmm.inc_tmm("s", [1, 1.5, 1], [np.inf, 1e6, np.inf], ["i", "x", "i"], 0, 500), ValueError, "'i' or 'c'"),
    ],
)
def test_bad_input_raises_with_a_message(call, exc, words):
    with pytest.raises(exc) as info:
        call()
    assert words in str(info.value)
