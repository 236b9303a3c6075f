"""iridis.vision against the numpy implementation written from the papers (the Rust crate's fixtures, which
reproduce pavo's numbers; tools/gen_vision_fixtures.py) and the CLI's defaults."""
import numpy as np
import pytest

import iridis.vision as vision
from conftest import ROOT, load


@pytest.fixture(scope="module")
def fixture():
    return load("crates", "vision", "tests", "fixtures", "vision_numpy.json")


def _spectra():
    import csv
    import os
    with open(os.path.join(ROOT, "data", "examples", "vision_spectra.csv")) as f:
        rows = list(csv.reader(f))
    names = rows[0][1:]
    data = np.array(rows[1:], float)
    return data[:, 0], data[:, 1:].T, names


def test_bluetit_and_bee_match_the_independent_implementation(fixture):
    wl, values, names = _spectra()
    for case in fixture["cases"]:
        if case["system"] not in ("bluetit", "ball-python"):
            continue
        d = case["densities"]
        a = vision.analyse(wl, values, case["system"], names, illuminant=case["illuminant"],
                           background="grey:%r" % case["background"], weber=case["weber"],
                           weber_ref=case["reference"] + 1, densities=d, space=case["space"])
        got = np.array([x["delta_s"] for x in a["distances"]])
        want = np.array([x["delta_s"] for x in case["distances"]])
        np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-12)
        for s, w in zip(a["samples"], case["samples"]):
            np.testing.assert_allclose(s["relative_catches"], w["relative_catches"], rtol=1e-9)


def test_identical_spectra_and_bad_input():
    wl, values, names = _spectra()
    a = vision.analyse(wl, values, "honeybee", names)
    d = [x for x in a["distances"] if {x["a"], x["b"]} == {"uv_blue", "uv_blue_copy"}][0]
    assert d["delta_s"] == 0.0 and d["delta_l"] == 0.0
    assert a["colour_space"] == "hexagon" and len(a["samples"][0]["coordinates"]["position"]) == 2
    with pytest.raises(ValueError, match="unknown visual system 'cat'"):
        vision.analyse(wl, values, "cat", names)
    with pytest.raises(ValueError, match="densities"):
        vision.analyse(wl, values, "bluetit", names, densities=[1, 2])
    with pytest.raises(TypeError):
        vision.analyse(wl, np.array([["a"] * wl.size]), "bluetit")
    # The units of an illuminant CSV, given with a built-in light: refused as the CLI refuses them.
    with pytest.raises(ValueError, match="illuminant_units would be ignored: .*bluesky is a built-in light"):
        vision.analyse(wl, values, "bluetit", names, illuminant="bluesky", illuminant_units="energy")
    # A Weber fraction for an achromatic channel that is not there: refused as the CLI refuses it.
    with pytest.raises(ValueError, match="weber_achromatic 0.2 would be ignored: achromatic none"):
        vision.analyse(wl, values, "bluetit", names, achromatic="none", weber_achromatic=0.2)
    with pytest.warns(DeprecationWarning, match="achromatic_weber= is now weber_achromatic="):
        with pytest.raises(ValueError, match="weber_achromatic 0.2 would be ignored"):
            vision.analyse(wl, values, "bluetit", names, achromatic="none", achromatic_weber=0.2)


def test_sensitivities_have_unit_area_and_peak_at_lambda_max():
    wl = np.arange(300.0, 701.0)
    names, s = vision.sensitivities(wl, lambda_max=[344, 436, 556])
    assert names == ["λ344", "λ436", "λ556"] and s.shape == (3, wl.size)
    np.testing.assert_allclose(s.sum(axis=1), 1.0, rtol=1e-12)
    assert [abs(wl[np.argmax(r)] - l) <= 2 for r, l in zip(s, (344, 436, 556))] == [True] * 3
    assert "bluetit" in vision.VISUAL_SYSTEMS and "forestshade" in vision.ILLUMINANTS


def test_percent_values_are_said_and_leave_delta_s_unchanged():
    wl = np.array([300.0, 500.0, 700.0])
    percent = np.array([[10.0, 40.0, 80.0], [20.0, 30.0, 35.0]])
    a = vision.analyse(wl, percent, "bluetit", names=["a", "b"])
    assert any("reaches 80, read as a reflectance of 8000 %" in n and "divide them by 100" in n for n in a["notes"])
    b = vision.analyse(wl, percent / 100, "bluetit", names=["a", "b"])
    assert not any("percent" in n for n in b["notes"])
    assert a["distances"][0]["delta_s"] == pytest.approx(b["distances"][0]["delta_s"], rel=1e-9)
