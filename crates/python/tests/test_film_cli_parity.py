"""``iridis.film``, ``iridis.color.xyz``/``delta_e`` and ``iridis.vision.vision`` give what ``iridis thinfilm …``,
``iridis color …`` and ``iridis vision`` print: the same text byte for byte and the same numbers, against the
CLI's output committed in fixtures/film_cli/ (made by fixtures/make_film_cli_fixtures.sh), and the spectra
against the independent ``tmm`` package (Byrnes) where it is installed."""
import json
import math
import os

import numpy as np
import pytest

import iridis.color as color
import iridis.film as film
import iridis.vision as vision

FIX = os.path.join(os.path.dirname(__file__), "fixtures", "film_cli")
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
SOAP = dict(stack="air | water 635nm | air", angle_rad=math.radians(1), from_nm=400, to_nm=690, step_nm=10)


def text(name):
    with open(os.path.join(FIX, name), encoding="utf-8") as f:
        return f.read()


def cli_json(name):
    out = json.loads(text(name))
    out.pop("inputs", None)
    return out


def same(py, cli, path="$"):
    """Equal JSON values: numbers to 1e-12 relative (the CLI prints shortest round-trip floats), the rest exactly."""
    if isinstance(cli, dict):
        assert isinstance(py, dict) and sorted(py) == sorted(cli), path
        for k in cli:
            same(py[k], cli[k], f"{path}.{k}")
    elif isinstance(cli, list):
        assert len(py) == len(cli), path
        for i, (a, b) in enumerate(zip(py, cli)):
            same(a, b, f"{path}[{i}]")
    elif isinstance(cli, float) or isinstance(py, float):
        assert py == pytest.approx(cli, rel=1e-12, abs=1e-15), path
    else:
        assert py == cli, path


def test_spectrum_json_and_text_are_the_clis():
    s = film.spectrum(**SOAP)
    same(dict(s), cli_json("spectrum_soap.json"))
    assert s.text == text("spectrum_soap.txt")


def test_spectrum_of_an_incoherent_stack_is_the_clis_csv_and_tmm_inc_tmm():
    s = film.spectrum("air | MgF2 100nm | inc:BK7 1mm | air", math.radians(45), step_nm=20, polarization="p")
    assert s.csv == text("spectrum_inc.csv")
    assert s["delta_deg"] is None  # no phase survives an incoherent layer


def test_spectrum_agrees_with_tmm():
    tmm = pytest.importorskip("tmm")
    s = film.spectrum("air | n=1.38 100nm | n=0.2+3.4i", math.radians(45), 400, 700, 50, polarization="p")
    for i, lam in enumerate(s["wavelength_nm"]):
        ns, ds = [1.0, 1.38, 0.2 + 3.4j], [np.inf, 100.0, np.inf]
        p = tmm.coh_tmm("p", ns, ds, math.radians(45), lam)
        psi, delta = (math.degrees(v) for v in tmm.ellips(ns, ds, math.radians(45), lam).values())
        assert s["R"][i] == pytest.approx(p["R"], rel=1e-10)
        # iridis counts light entering an absorbing substrate as absorbed (T = 0); the balance holds.
        assert s["R"][i] + s["T"][i] + s["A"][i] == pytest.approx(1.0, abs=1e-12)
        assert s["psi_deg"][i] == pytest.approx(psi, rel=1e-9)
        assert math.cos(math.radians(s["delta_deg"][i] - delta)) == pytest.approx(1.0, abs=1e-12)


def test_rough_spectrum_text_is_the_clis():
    s = film.spectrum("air | water 348nm | Si", math.radians(30), 400, 700, 50, roughness_nm=25, correlation_nm=300,
                      d_iterations=5)
    assert s.text == text("rough_spectrum.txt")


def test_tables_are_the_clis_csv():
    t = film.table("air | water 635nm | air", "0deg:60deg:30deg", 400, 700, 50)
    assert t.csv == text("table.csv")
    assert t["angle_deg"].tolist() == [0.0] * 7 + [30.0] * 7 + [60.0] * 7
    r = film.table("air | water 348nm | Si", "0deg:60deg:30deg", 400, 700, 100, roughness_nm=25, correlation_nm=300,
                   d_iterations=5)
    assert r.csv == text("rough_table.csv")


def test_colours_are_the_clis():
    c = film.color("air | gasoline 216nm | water 220nm | asphalt", math.radians(30))
    same(dict(c), cli_json("color_oil.json"))
    assert c.text == text("color_oil.txt")
    assert film.color("air | water 348nm | air", from_nm=300, to_nm=700, visual="bluetit").text == text(
        "color_visual.txt")
    r = film.color("air | water 348nm | Si", math.radians(30), roughness_nm=25, correlation_nm=300,
                   light_angle_rad=math.radians(20), d_iterations=5, step_nm=20)
    assert r.text == text("rough_color.txt")


def test_chart_is_the_clis():
    c = film.chart("air | water {d} | air", "0nm:1000nm:20nm")
    assert c.csv == text("chart.csv")
    assert f"wrote CHART_PNG {c.summary}\nwrote CHART_CSV\n" == text("chart.txt")
    # The top band is the reflected colour exposed so that the brightest one reaches Y = 1.
    assert c.exposure == pytest.approx(1.0 / max(c["R_Y"]), rel=1e-12)
    assert c.image.shape == (360, 1200, 3) and c.image.dtype == np.uint8


def test_materials_profile_are_the_clis():
    m = film.materials(550)
    assert m.text == text("materials.txt")
    with pytest.raises(ValueError, match="must be a positive, finite length"):
        film.materials(-1)
    same(dict(m), cli_json("materials.json"))
    p = film.profile("air | TiO2 60nm | Si 50nm | inc:glass 1mm | air", 550, depth="-20nm:200nm", points=23)
    assert p.csv == text("profile.csv")
    g = film.profile("air | Au 30nm | glass", 500, math.radians(20))
    assert g.text == text("profile.txt")
    # Energy conservation: everything reflected, absorbed or transmitted.
    assert g["R"] + g["T"] + sum(g["A_layers"]) + g["A_substrate"] == pytest.approx(1.0, abs=1e-12)


def test_profile_plot_and_bad_input():
    p = film.profile("air | Au 30nm | glass", 500, points=11, plot=True)
    assert p.image.ndim == 3 and p.image.shape[2] == 3
    with pytest.raises(ValueError, match="depth"):
        film.profile("air | Au 30nm | glass", 500, depth="200nm:0nm")
    # A range's end is a sample: a step that does not divide it raises, as the CLI refuses it.
    with pytest.raises(ValueError, match="400–700 nm is not a whole number of 7 nm steps: the last wavelength would"):
        film.spectrum("air | water 300nm | air", from_nm=400.0, to_nm=700.0, step_nm=7.0)
    with pytest.raises(ValueError, match=r"angles: .* = 2\.667 is not a whole number"):
        film.table("air | water 300nm | air", angles="0deg:80deg:30deg")


def test_rough_keywords_without_roughness_raise():
    """As the CLI refuses them: the diffuse light's keywords (and the table's colour scale without a plot) would
    be ignored on a smooth film."""
    stack = "air | water 300nm | air"
    with pytest.raises(ValueError, match=r"light_angle_rad would be ignored: .*give roughness_nm and correlation_nm"):
        film.spectrum(stack, light_angle_rad=0.5)
    with pytest.raises(ValueError, match=r"d_iterations, azimuth_rad would be ignored"):
        film.color(stack, azimuth_rad=1.0, d_iterations=5)
    with pytest.raises(ValueError, match=r"diffuse_transport would be ignored"):
        film.chart("air | water {d} | air", thickness="0nm:100nm:50nm", diffuse_transport="single")
    with pytest.raises(ValueError, match=r"light_angles would be ignored"):
        film.table(stack, angles="0deg:10deg:5deg", light_angles="0deg:10deg:5deg")
    with pytest.raises(ValueError, match=r"give plot=True"):
        film.table(stack, angles="0deg:10deg:5deg", scale="log")
    with pytest.raises(ValueError, match=r"azimuth_rad would be ignored"):
        film.bench(seconds=0.01, no_python=True, azimuth_rad=1.0)


def test_what_the_rough_model_would_ignore_raises():
    """The library's refusals, as the CLI's (crates/cli/tests/rough_cli.rs)."""
    stack, rough = "air | water 348nm | Si", dict(roughness_nm=25.0, correlation_nm=300.0)
    with pytest.raises(ValueError, match="polarization s would be ignored: with a rough substrate the spectrum"):
        film.spectrum(stack, polarization="s", **rough)
    with pytest.raises(ValueError, match="polarization p would be ignored: with a rough substrate the colours"):
        film.color(stack, polarization="p", **rough)
    with pytest.raises(ValueError, match="visual bluetit takes a smooth film's spectra"):
        film.color(stack, visual="bluetit", **rough)
    with pytest.raises(ValueError, match="no_python would be ignored: the rough bench"):
        film.bench(seconds=0.01, no_python=True, **rough)


def test_colour_of_a_spectrum_file_and_delta_e_are_the_clis():
    green = os.path.join(ROOT, "data", "examples", "colorchecker_green.csv")
    c = color.xyz(green, "d50", "1964")
    same(dict(c), cli_json("color_xyz.json"))
    assert color.xyz(green).text == text("color_xyz.txt").replace("data/examples/colorchecker_green.csv", green)
    d = color.delta_e("50,2.6772,-79.7751", "50,0,-82.7485", "1976")
    assert d == cli_json("delta_e.json")["delta_e"]
    # CIEDE2000 of Sharma et al. (2005), pair 1.
    assert round(color.delta_e("50,2.6772,-79.7751", "50,0,-82.7485"), 4) == 2.0425
    with pytest.raises(ValueError, match="not an L,a,b triple"):
        color.delta_e("50,2", "50,0,0")


def test_an_emissive_light_is_seen_against_the_illuminants_white():
    a = os.path.join(ROOT, "data", "cie", "a.csv")
    # Illuminant A against its own white is the white point: L* = 100, a* = b* = 0.
    np.testing.assert_allclose(color.xyz(a, "a", emissive=True)["Lab"], [100, 0, 0], atol=1e-6)
    # Against D65: A's published chromaticity (CIE 15:2004) by the CIELAB formula, D65's as the white.
    xa, w = [np.array([x / y, 1, (1 - x - y) / y]) for x, y in ((0.44757, 0.40745), (0.31271, 0.32902))]
    f = np.cbrt(xa / w)
    expected = [100, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])]
    np.testing.assert_allclose(color.xyz(a, emissive=True)["Lab"], expected, atol=0.1)


def test_vision_of_a_spectra_file_is_the_clis():
    spectra = os.path.join(ROOT, "data", "examples", "vision_spectra.csv")
    v = vision.vision(spectra, "avian-uv", illuminant="forestshade")
    same(dict(v), cli_json("vision.json"))
    t = vision.vision(spectra, "bluetit").text
    assert t == text("vision.txt").replace("data/examples/vision_spectra.csv", spectra)
    # With no achromatic channel, as `--achromatic none` (the Weber fraction's default is the CLI's, not a value
    # given: a given one would be refused as ignored).
    t = vision.vision(spectra, "bluetit", achromatic="none").text
    assert "→ e = 0.200, 0.141, 0.141, 0.100; no achromatic channel" in t


def test_bench_runs_each_measurement_once():
    b = film.bench(seconds=1e-3, no_python=True)
    assert [r["layers"] for r in b["results"]] == [2, 20]
    # The batch: 1000 wavelengths × 1000 angles at 1 s, the same share of the angles below (at least 10).
    assert b["fit"]["parameters"] == 3 and b["batch"]["points"] == 1000 * 10
    assert "batch of 10000 (λ, θ) points" in b.text
    assert "not run (--no-python)" in b.text
    with pytest.raises(ValueError, match="seconds 0: must be positive"):
        film.bench(seconds=0)
