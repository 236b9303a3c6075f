"""Warnings the CLI prints reach Python where the same library call runs (an audit of 87 command/function pairs
found these lost): the reader's warnings at `surface.load` (they waited for `info()`), and a black map's
warning from `diffraction.brdf_map` (said only where an exposure followed)."""

import os
import warnings

import numpy as np
import pytest

import iridis.diffraction as diffraction
import iridis.surface as surface

SURFACE_FIXTURES = os.path.join(os.path.dirname(__file__), "..", "..", "surface", "tests", "fixtures")


def _caught(f):
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        out = f()
    return out, [str(w.message) for w in rec], rec


def test_load_warns_what_the_reader_found_once():
    gwy = os.path.join(SURFACE_FIXTURES, "gwyfile_two_channels.gwy")
    s, said, rec = _caught(lambda: surface.load(gwy, pixel_size_nm=10))
    assert any("pixel_size_nm 10 nm ignored" in m for m in said), said
    assert rec[0].filename == __file__
    # info() gives its own warnings, not the reader's again.
    _, again, _ = _caught(lambda: s.level("plane").info())
    assert not any("pixel_size_nm 10 nm ignored" in m for m in again), again


def test_a_black_map_says_so():
    # A 65 µm window's lobes are narrower than a 16² map's pixels: no pixel sees light (the CLI's warning).
    xyz, said, _ = _caught(
        lambda: diffraction.brdf_map("builtin:sine?size=8um&pixel=50nm", method="reference", size=16))
    assert float(abs(xyz).max()) < 1e-20
    assert any(m.startswith("the map is black: no light reaches these view directions") for m in said), said
    assert not any("exposure stays" in m for m in said), said


def test_grating_defaults_are_the_clis():
    # `iridis grating SURFACE` lights it at normal incidence at 550 nm; so does grating(source) alone.
    g = diffraction.grating("builtin:sine?size=1100nm&pixel=10nm")
    orders = g["orders"]
    assert {o["wavelength_nm"] for o in orders} == {550.0}
    # Normal light on the 1100 nm period: orders ±1 leave at asin(550/1100) = 30° (the grating equation).
    first = [o for o in orders if abs(o["m"]) == 1 and o["n"] == 0]
    assert len(first) == 2 and all(abs(o["theta_deg"] - 30.0) < 1e-9 for o in first), first


def test_answers_carry_the_commands_text():
    # docs/python.md: the answer has `.text`, what the CLI prints, where the command prints one (these returned
    # plain dicts).
    import math

    import iridis.lab as lab

    g = diffraction.grating("builtin:sine?size=1100nm&pixel=10nm", detector_theta=math.radians(30),
                            acceptance=math.radians(2))
    assert "efficiencies in % of the incident power" in g.text and "λ = 550 nm" in g.text, g.text
    assert "detector (30deg,0deg, ±2.00°)" in g.text, g.text
    e = diffraction.brdf_eval("builtin:sine?size=1100nm&pixel=10nm", 0.0, (math.radians(30), 0.0))
    assert "(of ρ under D65, CIE 1931 observer; a normal-incidence mirror: Y = 1)" in e.text, e.text
    t = lab.testbench("builtin:blazed?size=10um&pixel=50nm", wavelengths=(450.0, 650.0, 100.0),
                      angles_deg=(-89.0, 89.0, 0.5))
    assert t.text.splitlines()[1].startswith("periodicity  mean ") and "nm ±" in t.text, t.text


def test_evaluate_states_the_scalar_models_error_as_brdf_eval_does():
    # The Elaphe-like rows (period ≈ 1100 nm, as deep as snake skin) put the scalar model above its threshold:
    # `evaluate` warns and returns the estimate, on a SURFACE argument and on a Surface alike, with brdf_eval's
    # numbers (one library call, `scalar_error_said`).
    skin = "builtin:elaphe?size=10um&pixel=50nm"
    light, view = 0.0, (10 * 3.141592653589793 / 180, 3.141592653589793 / 2)
    q, said, _ = _caught(lambda: diffraction.evaluate(skin, light, view, step_nm=20))
    e = q["scalar_error"]
    assert abs(e["period_nm"] - 1100) < 20 and e["above_threshold"], e
    assert any("not to be trusted" in m for m in said), said
    cli = diffraction.brdf_eval(skin, light, view, step_nm=20)["scalar_error"]
    assert e["worst_relative_error"] == cli["worst_relative_error"]
    on_field, _, _ = _caught(lambda: diffraction.evaluate(surface.load(skin), light, view, step_nm=20))
    assert on_field["scalar_error"]["worst_relative_error"] == cli["worst_relative_error"]
    # A 0.01 nm deep sine: the scalar model holds (no warning, the estimate still returned); a flat patch has
    # no period to check.
    shallow, said, _ = _caught(lambda: diffraction.evaluate("builtin:sine?size=6um&pixel=60nm&depth=0.01nm",
                                                             light, view, step_nm=20))
    assert not shallow["scalar_error"]["above_threshold"], shallow["scalar_error"]
    assert not any("not to be trusted" in m for m in said), said
    flat = surface.Surface(np.zeros((16, 16)), 100.0)
    assert diffraction.evaluate(flat, light, (0.0, 0.0))["scalar_error"] is None


def test_messages_name_the_python_keywords(tmp_path):
    # The library's messages name the CLI's flags; from Python they name the keywords (an audit found
    # "give --pixel-size" where pixel_size_nm was the remedy), except in a quoted command line, which is the CLI's.
    path = tmp_path / "h.npy"
    np.save(path, np.zeros((8, 8)))
    try:
        surface.load(str(path))
    except ValueError as e:
        said = str(e)
    assert "give pixel_size_nm (e.g. 65)" in said and "--pixel-size" not in said, said
    table = tmp_path / "t.npz"
    diffraction.precompute("builtin:sine?size=4um&pixel=100nm", uv_resolution=11).save(table)
    try:
        diffraction.brdf_eval(str(table), light=0.3, view=0.2, uv_resolution=21)
    except ValueError as e:
        said = str(e)
    # A command the message points to is named by its Python call.
    assert "so uv_resolution 21 would be ignored" in said, said
    assert "pass them to `iridis.diffraction.precompute()` (or give `iridis.diffraction.brdf_eval()` the" in said, said
    with pytest.raises(ValueError, match=r"the peaks of a random surface .*; `Surface\.info\(\)` lists them$"):
        diffraction.grating("builtin:gaussian?size=20um&pixel=50nm", unit_cell="auto")


def test_reading_options_on_a_surface_in_memory_are_refused():
    # A Surface is already read: pixel_size_nm=10 on one of 50 nm pixels changed nothing, in silence.
    import iridis.lab as lab
    sine = surface.load("builtin:sine?size=4um&pixel=100nm&period=1000nm&depth=100nm")
    for call in (lambda: diffraction.evaluate(sine, 0.2, (0.2, 3.14159), pixel_size_nm=10),
                 lambda: diffraction.precompute(sine, uv_resolution=21, level="plane"),
                 lambda: diffraction.grating(sine, height_unit="um"),
                 lambda: lab.testbench(sine, pixel_size_nm=10)):
        try:
            call()
        except ValueError as e:
            assert "would be ignored: it says how to read a file, and this Surface is already read" in str(e), e
        else:
            raise AssertionError("not refused")
    # The same keywords with a SURFACE argument are read.
    q = diffraction.evaluate("builtin:sine?size=4um&pixel=100nm", 0.2, (0.2, 3.14159), level="none", step_nm=20)
    assert q["method"] == "reference"


def test_answers_say_what_their_numbers_rest_on():
    # An audit found dicts whose numbers changed with a keyword that no key recorded: evaluate's XYZ under
    # illuminant A, and film colours without their light, observer or angle.
    import iridis.film as film
    q = diffraction.evaluate("builtin:sine?size=4um&pixel=100nm", 0.2, (0.2, 3.14159), illuminant="A", step_nm=20)
    assert (q["illuminant"], q["observer"], q["shadowing"]) == ("A", "1931", True), q
    assert q["fresnel"] and q["fresnel_convention"] == "physical"
    c = film.color("air | water 348nm | air", angle_rad=0.5, illuminant="A", polarization="s")
    cond = c["conditions"]
    assert cond["illuminant"] == "A" and cond["polarization"] == "s" and cond["observer"] == "1931", cond
    assert abs(cond["angle_deg"] - 28.64788976) < 1e-6 and cond["wavelength_range_nm"] == [380.0, 780.0], cond


def test_laser_and_sweep_take_their_python_words(tmp_path):
    # lab.laser(aperture_nm=0) said "coherence length 0 nm must be positive", distance_nm=-1 named neither keyword;
    # lab.sweep refused "uv_power", the Python spelling of the CLI's uv-power.
    import iridis.lab as lab
    sine = "builtin:sine?size=4um&pixel=100nm"
    with pytest.raises(ValueError, match=r"aperture_nm 0 nm: the diaphragm's aperture must be a positive length"):
        lab.laser(sine, tmp_path / "a.png", aperture_nm=0)
    with pytest.raises(ValueError, match=r"distance_nm -1 nm and screen_nm"):
        lab.laser(sine, tmp_path / "b.png", distance_nm=-1)
    # Its messages spell the parameters as Python does.
    with pytest.raises(ValueError, match=r"the reference method has no parameter 'uv_power'; it applies to: lookup"):
        lab.sweep(sine, "uv_power", [1.0, 5.0], tmp_path / "s")
    with pytest.raises(ValueError, match=r"expected one of: terms, dlambda, coherence, uv_power, uv_resolution$"):
        lab.sweep(sine, "bogus", [1.0], tmp_path / "s")
