"""Every public name of tmm 0.2.0's ``tmm_core`` in ``iridis.tmm``, with tmm's signature and tmm's results on the
committed fixture (tools/gen_tmm_api_fixtures.py), and tmm's own ``examples.py`` run on ``iridis.tmm``."""
import inspect
import json
import math
import os
import pathlib
import sys
import types
import warnings

import numpy as np
import pytest

import iridis.tmm as itmm

HERE = os.path.dirname(__file__)


@pytest.fixture(scope="module")
def api():
    with open(os.path.join(HERE, "fixtures", "tmm_api.json")) as f:
        return json.load(f)


class Raised:
    def __init__(self, text):
        self.text = text


def dec(x):
    if isinstance(x, dict):
        if "c" in x:
            return complex(dec(x["c"][0]), dec(x["c"][1]))
        if "nan" in x:
            return float("nan")
        if "inf" in x:
            return math.inf * x["inf"]
        if "a" in x:
            return np.array([dec(v) for v in x["a"]])
        if "dtype" in x:
            return {"complex": complex, "float": float}[x["dtype"]]
        if "error" in x:
            return Raised(x["error"])
        if "absorp_analytic_fn" in x:
            return {k: dec(v) for k, v in x["absorp_analytic_fn"].items()}
        return {k: dec(v) for k, v in x.items()}
    if isinstance(x, list):
        return [dec(v) for v in x]
    return x


def same(a, b, path="", tol=1e-9):
    """a (iridis) equals b (tmm) to tol, relative to the size of b; NaN equals NaN."""
    if isinstance(b, dict):
        keys = set(b)
        assert keys <= set(a), f"{path}: missing keys {keys - set(a)}"
        for k in keys:
            same(a[k], b[k], f"{path}.{k}", tol)
        return
    numeric = all(isinstance(v, (int, float, complex)) and not isinstance(v, bool) for v in b) if isinstance(
        b, (list, tuple)) else False
    if isinstance(b, (list, tuple)) and not numeric:
        assert len(a) == len(b), f"{path}: {len(a)} vs {len(b)} entries"
        for i, (x, y) in enumerate(zip(a, b)):
            same(x, y, f"{path}[{i}]", tol)
        return
    if isinstance(b, bool) or isinstance(b, str):
        assert a == b, f"{path}: {a!r} vs {b!r}"
        return
    x, y = np.asarray(a, dtype=complex), np.asarray(b, dtype=complex)
    assert x.shape == y.shape, f"{path}: shape {x.shape} vs {y.shape}"
    nan = np.isnan(y)
    assert np.array_equal(np.isnan(x), nan), f"{path}: NaN where tmm has none (or the reverse): {a} vs {b}"
    xs, ys = x[~nan], y[~nan]
    inf = np.isinf(ys)
    assert np.array_equal(xs[inf], ys[inf]), f"{path}: {a} vs {b}"
    diff = np.abs(xs[~inf] - ys[~inf])
    scale = np.maximum(1.0, np.abs(ys[~inf]))
    assert np.all(diff <= tol * scale), f"{path}: {a} vs {b} (|Δ| {diff.max() if diff.size else 0:.2e})"


def check_call(fn, args, expected, label):
    if isinstance(expected, Raised):
        with pytest.raises((ValueError, AssertionError)):
            fn(*args)
        return
    same(fn(*args), expected, label)


def test_every_public_name_with_tmms_signature(api):
    assert len(api["public"]) == 25  # 24 functions and the class absorp_analytic_fn
    for name in api["public"]:
        assert hasattr(itmm, name), f"iridis.tmm has no {name}"
        want = api["functions"][name]["signature"]
        if name == "absorp_analytic_fn":
            for method in ("fill_in", "copy", "run", "flip", "scale", "add"):
                assert callable(getattr(itmm.absorp_analytic_fn, method))
            continue
        assert str(inspect.signature(getattr(itmm, name))) == want, name


SIMPLE = ["make_2x2_array", "is_forward_angle", "snell", "list_snell", "interface_r", "interface_t",
          "interface_R", "interface_T", "R_from_r", "T_from_t", "power_entering_from_r", "coh_tmm",
          "coh_tmm_reverse", "ellips", "unpolarized_RT", "find_in_structure", "find_in_structure_with_inf",
          "layer_starts", "inc_group_layers"]


@pytest.mark.parametrize("name", SIMPLE)
def test_results_equal_tmms(api, name):
    for i, case in enumerate(api["functions"][name]["cases"]):
        args = dec(case["args"])
        want = dec(case["result"])
        if isinstance(want, dict) and name in ("coh_tmm", "coh_tmm_reverse"):
            # Light arriving as an evanescent wave (the Kretschmann stack turned around: total internal reflection
            # at its far side) carries no flux: R, T and power_entering per unit incident flux divide by ~1e-17
            # and are rounding noise in tmm (4e16 here); amplitudes, angles and k_z are still compared.
            for key in ("R", "T", "power_entering"):
                if abs(want[key]) > 1e3:
                    del want[key]
        # tmm's functions take NumPy arrays where the fixture has them, lists where it has lists.
        check_call(getattr(itmm, name), args, want, f"{name} case {i}")


def stack(api, i):
    pol, n, d, th, lam = dec(api["functions"]["STACKS"])[i]
    return itmm.coh_tmm(pol, np.array(n), np.array(d, float), th, lam)


def test_position_resolved_and_absorption_per_layer(api):
    for case in api["functions"]["position_resolved"]["cases"]:
        layer, z = dec(case["args"])
        same(itmm.position_resolved(layer, z, stack(api, case["stack"])), dec(case["result"]),
             f"position_resolved stack {case['stack']} ({layer}, {z})")
    for case in api["functions"]["absorp_in_each_layer"]["cases"]:
        same(itmm.absorp_in_each_layer(stack(api, case["stack"])), dec(case["result"]), "absorp_in_each_layer")
    with pytest.raises((ValueError, AssertionError), match="outside the stack"):
        itmm.position_resolved(1, 1e9, stack(api, 0))


def fn_params(f):
    return {k: getattr(f, k) for k in ("A1", "A2", "A3", "a1", "a3", "d")}


def test_absorp_analytic_fn(api):
    for case in api["functions"]["absorp_analytic_fn"]["cases"]:
        data = stack(api, case["stack"])
        a = itmm.absorp_analytic_fn().fill_in(data, case["layer"])
        same(fn_params(a), dec(case["fill_in"]), "fill_in")
        z = dec(case["z"])
        same(a.run(z), dec(case["run"]), "run")
        b = a.copy().flip()
        same(fn_params(b), dec(case["flip"]), "flip")
        same(b.run(z), dec(case["flip_run"]), "flip run")
        same(fn_params(a.copy().scale(0.37)), dec(case["scale"]), "scale")
        same(fn_params(a.copy().add(b.copy().flip())), dec(case["add"]), "add")
        # The density integrates to the layer's absorption (absorp_in_each_layer), a law tmm does not state.
        zs = np.linspace(0, a.d, 4001)
        integral = np.trapezoid(a.run(zs).real, zs) if hasattr(np, "trapezoid") else np.trapz(a.run(zs).real, zs)
        assert abs(integral - itmm.absorp_in_each_layer(data)[case["layer"]]) < 1e-6


def test_incoherent_stacks(api):
    for i, case in enumerate(api["functions"]["inc_tmm"]["cases"]):
        pol, n, d, c, th, lam = dec(case["args"])
        want = dec(case["result"])
        if isinstance(want, Raised):
            with pytest.raises((ValueError, AssertionError)):
                itmm.inc_tmm(pol, np.array(n), np.array(d, float), c, th, lam)
            continue
        got = itmm.inc_tmm(pol, np.array(n), np.array(d, float), c, th, lam)
        got_slim = dict(got)
        got_slim["coh_R"] = [x["R"] for x in got["coh_tmm_data_list"]]
        got_slim["coh_bT"] = [x["T"] for x in got["coh_tmm_bdata_list"]]
        same(got_slim, want, f"inc_tmm case {i}")
        same(itmm.inc_absorp_in_each_layer(got), dec(case["inc_absorp_in_each_layer"]), f"inc_absorp case {i}")
        assert abs(sum(itmm.inc_absorp_in_each_layer(got)) - 1) < 1e-9
        for a in case["inc_find_absorp_analytic_fn"]:
            if "error" in a:
                continue  # tmm compares the two k_z exactly and can fail on rounding; iridis may succeed
            f = itmm.inc_find_absorp_analytic_fn(a["layer"], got)
            same(fn_params(f), dec(a["fn"]), f"inc_find_absorp_analytic_fn case {i} layer {a['layer']}")


def test_complex_angles_as_tmm_takes_them():
    # issue 29: th_0 = 0.1 + 0j raised TypeError; tmm accepts it, and complex angles of absorbing first media.
    a = itmm.coh_tmm("s", [1, 1.5], [np.inf, np.inf], 0.1 + 0j, 500)
    b = itmm.coh_tmm("s", [1, 1.5], [np.inf, np.inf], 0.1, 500)
    assert a["R"] == b["R"] and a["th_0"] == 0.1 + 0j
    n0 = 1.5 + 0.02j
    th0 = np.emath.arcsin(0.6 / n0)
    x = itmm.coh_tmm("p", [n0, 2.0, 1.0], [np.inf, 100, np.inf], th0, 500)
    assert 0 < x["R"] < 1
    # tmm's check is an assert: a script catching AssertionError (or ValueError) catches ours.
    for caught in (AssertionError, ValueError, itmm.TmmInputError):
        with pytest.raises(caught, match="must be real"):
            itmm.coh_tmm("p", [n0, 2.0, 1.0], [np.inf, 100, np.inf], 0.4, 500)
    for call in (lambda: itmm.unpolarized_RT([n0, 2.0, 1.0], [np.inf, 100, np.inf], 0.4, 500),
                 lambda: itmm.ellips([1, 2.0, 1.0], [np.inf, -100, np.inf], 0.4, 500),
                 lambda: itmm.coh_tmm_batch("s", [n0, 2.0, 1.0], [np.inf, 100, np.inf], 0.4, 500.0)):
        with pytest.raises(AssertionError):
            call()
    with pytest.raises(itmm.TmmInputError, match="gain"):
        itmm.is_forward_angle(1.5 - 0.1j, 0.3)


# --- tmm's examples.py --------------------------------------------------------------------------------------

def fake_pyplot(record):
    """A stand-in for matplotlib.pyplot that keeps the numbers examples.py plots."""
    plt = types.ModuleType("matplotlib.pyplot")

    def keep(kind):
        def f(*args, **kwargs):
            record.append((kind, [np.asarray(a) for a in args if not isinstance(a, str)]))
        return f

    for name in ("plot", "fill"):
        setattr(plt, name, keep(name))
    for name in ("figure", "xlabel", "ylabel", "title", "show", "xlim", "ylim", "yticks", "legend"):
        setattr(plt, name, lambda *a, **k: None)
    mpl = types.ModuleType("matplotlib")
    mpl.pyplot = plt
    return mpl, plt


def run_examples(module, monkeypatch, capsys):
    """tmm's examples.py with its one import of tmm_core pointed at `module`; every sample run, every plotted
    number and every printed line kept."""
    tmm = pytest.importorskip("tmm", reason="tmm's examples.py comes with the tmm package (pip install tmm)")
    pytest.importorskip("scipy", reason="examples.py interpolates with scipy (pip install scipy)")
    source = pathlib.Path(tmm.__file__).with_name("examples.py").read_text()
    assert source.count("from .tmm_core import") == 1
    source = source.replace("from .tmm_core import", f"from {module} import").replace(
        "from . import color", "from tmm import color")
    record = []
    mpl, plt = fake_pyplot(record)
    monkeypatch.setitem(sys.modules, "matplotlib", mpl)
    monkeypatch.setitem(sys.modules, "matplotlib.pyplot", plt)
    namespace = {"__name__": "tmm_examples"}
    with warnings.catch_warnings():
        # tmm 0.2's examples.py writes LaTeX ('$^\circ$') in plain strings: Python's warning about the escape is
        # tmm's, not ours.
        warnings.simplefilter("ignore", DeprecationWarning)
        warnings.simplefilter("ignore", SyntaxWarning)
        code = compile(source, "examples.py", "exec")
    exec(code, namespace)
    samples = sorted(k for k in namespace if k.startswith("sample"))
    for name in samples:
        namespace[name]()
    return samples, record, capsys.readouterr().out


def test_tmms_examples_run_on_iridis_and_plot_the_same_numbers(monkeypatch, capsys):
    samples, ours, printed = run_examples("iridis.tmm", monkeypatch, capsys)
    _, theirs, printed_tmm = run_examples("tmm.tmm_core", monkeypatch, capsys)
    assert samples == ["sample1", "sample2", "sample3", "sample4", "sample5", "sample6"]
    assert printed == printed_tmm
    assert len(ours) == len(theirs) >= 5
    for (kind, a), (kind_t, b) in zip(ours, theirs):
        assert kind == kind_t and len(a) == len(b)
        for x, y in zip(a, b):
            np.testing.assert_allclose(x, y, rtol=1e-9, atol=1e-12)
