"""The Python package and the CLI call the same facade (crates/api): the same inputs give the CLI's --json
numbers (fixtures written by tests/fixtures/make_cli_fixtures.sh from `iridis`), and the same messages."""
import json
import math
import os
import warnings

import numpy as np
import pytest

import iridis.diffraction as diffraction
import iridis.lab as lab
import iridis.surface as surface
import iridis.thinfilm as tf

FIXTURES = os.path.join(os.path.dirname(__file__), "fixtures")


def cli(name):
    with open(os.path.join(FIXTURES, name + ".json")) as f:
        return json.load(f)


def close(a, b, rtol=1e-12, atol=1e-15):
    np.testing.assert_allclose(np.asarray(a, dtype=float), np.asarray(b, dtype=float), rtol=rtol, atol=atol)


# --- rough films: iridis thinfilm color|spectrum --roughness --correlation --------------------------------

def test_rough_colours_equal_the_cli():
    ref = cli("rough_color")
    film = tf.Stack("air | water 348nm | Si").rough(25.0, 300.0)
    c = film.color(math.radians(30), light_rad=math.radians(20))
    for key in ("reflected", "transmitted", "specular", "diffuse"):
        close(c[key], ref[key]["XYZ"])
        close(c[key + "_lab"], ref[key]["Lab"], atol=1e-10)
        assert c[key + "_hex"] == ref[key]["hex"]
    assert ref["rough"]["roughness_nm"] == film.roughness_nm and ref["rough"]["correlation_nm"] == film.correlation_nm


def test_rough_spectrum_equals_the_cli():
    ref = cli("rough_spectrum")
    film = tf.Stack("air | water 348nm | Si").rough(25.0, 300.0, d_iterations=5)
    s = film.spectrum(np.arange(400.0, 700.0 + 1e-9, 25.0), math.radians(30))
    for key in ("wavelength_nm", "R_smooth", "specular", "specular_s", "specular_p", "diffuse_per_sr",
                "diffuse_s_per_sr", "diffuse_p_per_sr"):
        close(s[key], ref[key])
    assert s["series_terms_max"] == ref["series_terms_max"]
    close(s["diffuse_error_bound_per_sr"], ref["diffuse_error_bound_per_sr"])


def test_rough_film_energy_and_reciprocity():
    """Physics, independent of the CLI: the specular part plus the diffuse part over the hemisphere,
    k_r + 2π ∫ k_d cos θ sin θ dθ (light at normal incidence), stays below the incident power, and equals what
    the library's own albedo integrator gave for this stack (docs/rough-films.md, at 400 nm, σ = 25 nm,
    τ = 300 nm: 0.716 with single scattering, 0.888 with the default multiple scattering, which returns light
    the film turns back); swapping view and light leaves the diffuse part unchanged (docs/rough-films.md).
    The specular part is not bounded by the smooth film's R: roughness damps the substrate's wave, which can
    undo destructive interference."""
    steps = 180
    theta = (np.arange(steps) + 0.5) * (np.pi / 2) / steps     # midpoints over the view hemisphere
    for transport, want in (("single", 0.716), ("multiple", 0.888)):
        film = tf.Stack("air | n=2.0 80nm | n=0.2+3.4i").rough(25.0, 300.0, diffuse_transport=transport)
        kd = np.array([film.spectrum([400.0], t, light_rad=0.0)["diffuse_per_sr"][0] for t in theta])
        spec = film.spectrum([400.0], 0.0)["specular"][0]
        total = spec + 2 * np.pi * np.sum(kd * np.cos(theta) * np.sin(theta)) * (np.pi / 2) / steps
        assert total <= 1.0
        assert abs(total - want) < 0.005, (transport, total)

    film = tf.Stack("air | n=1.38 120nm | n=1.9+0.05i").rough(20.0, 400.0)
    wl = np.linspace(450, 700, 6)
    a = film.spectrum(wl, 0.3, light_rad=0.7)
    b = film.spectrum(wl, 0.7, light_rad=0.3)
    close(a["diffuse_per_sr"], b["diffuse_per_sr"], rtol=1e-9)


def test_rough_film_bad_input():
    stack = tf.Stack("air | water 348nm | Si")
    with pytest.raises(ValueError, match="roughness_nm/correlation_nm"):
        stack.rough(-1.0, 300.0).color()
    with pytest.raises(ValueError, match="diffuse transport"):
        stack.rough(25.0, 300.0, diffuse_transport="magic").color()
    with pytest.raises(TypeError, match="roughness_nm"):
        stack.rough("25nm", 300.0)
    with pytest.raises(ValueError, match="d_iterations"):
        stack.rough(25.0, 300.0, d_iterations=2.5)
    with pytest.raises(ValueError, match="1-D"):
        stack.rough(25.0, 300.0).spectrum(np.full((2, 2), 500.0))
    with pytest.raises(TypeError, match="view_rad"):
        stack.rough(25.0, 300.0).spectrum([500.0], view_rad="30deg")


# --- point queries: iridis brdf eval ----------------------------------------------------------------------

def test_point_query_equals_brdf_eval():
    ref = cli("brdf_eval_reference")
    q = diffraction.evaluate("builtin:sine", light=math.radians(30), view=(math.radians(10), math.pi))
    assert q["method"] == ref["method"]
    close(q["wavelength_nm"], ref["wavelength_nm"])
    close(q["reflectance"], ref["reflectance"], rtol=1e-10, atol=1e-14)
    close(q["xyz"], ref["xyz"], rtol=1e-10)
    close(q["light_direction"], ref["light"]["direction"])


def test_point_query_of_a_lab_model_with_a_metal_fresnel_equals_brdf_eval():
    ref = cli("brdf_eval_stam")
    q = diffraction.evaluate("builtin:elaphe?size=6um&pixel=60nm", method="stam-gaussian", coherence_nm=3000.0,
                             light=math.radians(10), view=(math.radians(25), math.pi), fresnel="index:0.2+3.4i")
    assert q["method"] == ref["method"]
    close(q["reflectance"], ref["reflectance"], rtol=1e-10, atol=1e-14)
    close(q["xyz"], ref["xyz"], rtol=1e-10)


def test_point_query_of_a_surface_in_memory_equals_its_argument():
    """A Surface object and the SURFACE argument it was loaded from give the same answer (one facade path)."""
    spec = "builtin:sine?size=6.6um&pixel=100nm&period=1100nm&depth=100nm"
    a = diffraction.evaluate(spec, light=0.2, view=(0.4, math.pi))
    b = diffraction.evaluate(surface.load(spec), light=0.2, view=(0.4, math.pi))
    close(a["reflectance"], b["reflectance"], rtol=1e-14, atol=0)


def test_point_query_obeys_reciprocity():
    """f(ω_i, ω_r) = f(ω_r, ω_i) for the reference evaluator (Helmholtz; the shading factors are symmetric)."""
    g = surface.generate("elaphe", size="6um", pixel="60nm")
    a = diffraction.evaluate(g, light=(0.3, 0.2), view=(0.5, 2.9), coherence_nm=3000.0)
    b = diffraction.evaluate(g, light=(0.5, 2.9), view=(0.3, 0.2), coherence_nm=3000.0)
    # ρ is the BRDF times cos θ_i (docs/diffraction.md, eq. 9): the BRDF ρ / cos θ_light is the symmetric one.
    close(a["reflectance"] / np.cos(0.3), b["reflectance"] / np.cos(0.5), rtol=1e-9, atol=1e-14)


def test_lookup_has_no_spectrum_and_tables_answer_lookup_only():
    g = surface.generate("sine", size="6.6um", pixel="100nm", period="1100nm", depth="100nm")
    t = diffraction.precompute(g, uv_resolution=101)
    q = diffraction.evaluate(t, light=0.0, view=(0.5, 0.0))
    assert q["method"] == "lookup" and q["reflectance"] is None and q["xyz"].shape == (3,)
    with pytest.raises(ValueError, match="needs the height field, not a table"):
        diffraction.evaluate(t, light=0.0, view=0.5, method="reference")


def test_point_query_bad_input():
    with pytest.raises(ValueError, match="above the surface"):
        diffraction.evaluate("builtin:sine", light=2.0, view=0.1)
    with pytest.raises(TypeError, match="light"):
        diffraction.evaluate("builtin:sine", light="30deg", view=0.1)
    with pytest.raises(ValueError, match="unknown method 'magic'"):
        diffraction.evaluate("builtin:sine", light=0.1, view=0.1, method="magic")
    with pytest.raises(ValueError, match="fresnel 'schlick:1'"):
        diffraction.evaluate("builtin:sine", light=0.1, view=0.1, fresnel="schlick:1")
    # The CLI's --coherence is coherence_nm here: the error names it, among the function's own keywords too.
    with pytest.raises(TypeError, match=r"evaluate\(\) got an unexpected keyword argument 'coherence' \(did you "
                                        r"mean coherence_nm\? it takes: .*light.*method.*terms"):
        diffraction.evaluate("builtin:sine", light=0.1, view=0.1, coherence=3000.0)
    with pytest.raises(TypeError, match="coherence_nm must be a number"):
        diffraction.evaluate("builtin:sine", light=0.1, view=0.1, coherence_nm="3um")
    with pytest.raises(ValueError, match="coherence_nm"):
        diffraction.evaluate("builtin:sine", light=0.1, view=0.1, coherence_nm=-1.0)
    with pytest.raises(OSError, match="cannot load surface /no/such/scan.gwy"):
        diffraction.evaluate("/no/such/scan.gwy", light=0.1, view=0.1)
    with pytest.raises(TypeError, match="source must be"):
        diffraction.evaluate(np.zeros((4, 4)), light=0.1, view=0.1)


def test_warnings_of_the_cli_are_python_warnings():
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        diffraction.evaluate("builtin:sine", light=0.1, view=0.1, step_nm=10.0)
    assert any("shows colour artefacts" in str(x.message) for x in w), [str(x.message) for x in w]


# --- the lab: iridis testbench, iridis compare ------------------------------------------------------------

def test_testbench_equals_the_cli():
    ref = cli("testbench_blazed")
    r = lab.testbench("builtin:blazed?size=20um&pixel=50nm", wavelengths=(500, 700, 50), angles_deg=(-60, 74, 0.1))
    close(r["periodicity_nm"]["mean"], ref["periodicity_nm"]["mean"], rtol=1e-10)
    close(r["periodicity_nm"]["variance"], ref["periodicity_nm"]["variance"], rtol=1e-8, atol=1e-12)
    assert [p["wavelength_nm"] for p in r["peaks"]] == [p["wavelength_nm"] for p in ref["peaks"]]
    close([p["angle_deg"] for p in r["peaks"]], [p["angle_deg"] for p in ref["peaks"]], rtol=1e-10)
    assert r["method"] == ref["method"] and r["surface"] == ref["surface"]
    # The grating equation (independent of the CLI): d (sin θi − sin θr) = m λ with the blazed grating's 2500 nm.
    for p in r["peaks"]:
        d = p["wavelength_nm"] / (math.sin(math.radians(75)) - math.sin(math.radians(p["angle_deg"])))
        assert abs(d - 2500.0) / 2500.0 < 0.01
    assert r["matrix"].shape == (r["wavelength_nm"].size, r["angle_deg"].size) == (5, 1341)


def test_compare_equals_the_cli():
    ref = cli("compare_elaphe")
    r = lab.compare("builtin:elaphe?size=6um&pixel=60nm", methods=["reference", "stam-gaussian"], coherence_nm=3000.0,
                    size=24)
    assert len(r["results"]) == len(ref["results"])
    for a, b in zip(r["results"], ref["results"]):
        assert (a["method"], a["against"], a["exposure_ru"]) == (b["method"], b["against"], b["exposure_ru"])
        close([a["mean"], a["p95"], a["max"]], [b["mean"], b["p95"], b["max"]], rtol=1e-9, atol=1e-12)
    close([e["mean"] for e in r["periodic_extension_error"]], [e["mean"] for e in ref["periodic_extension_error"]],
          rtol=1e-9)
    assert set(r["maps"]) == {"reference", "stam-gaussian", "ground-truth", "ground-truth-periodic"}
    m = r["maps"]["reference"]
    assert m.shape == (24, 24, 3) and np.isnan(m[0, 0]).all() and np.isfinite(m[12, 12]).all()


def test_lab_bad_input():
    with pytest.raises(ValueError, match="integrates over wavelength in advance"):
        lab.testbench("builtin:blazed?size=20um&pixel=50nm", method="lookup")
    with pytest.raises(ValueError, match="order 0"):
        lab.testbench("builtin:blazed?size=20um&pixel=50nm", order=0)
    with pytest.raises(TypeError, match="wavelengths"):
        lab.testbench("builtin:blazed?size=20um&pixel=50nm", wavelengths=500)
    with pytest.raises(ValueError, match="against"):
        lab.compare("builtin:blazed?size=20um&pixel=50nm", against="magic")
    with pytest.raises(ValueError, match="exposures"):
        lab.compare("builtin:blazed?size=20um&pixel=50nm", exposures=[-1.0])
    with pytest.raises(TypeError, match="surface must be"):
        lab.compare(3.0)
    # A u-v grid where no table is built from it would be ignored: refused, as by the CLI.
    with pytest.raises(ValueError, match="uv_resolution 101 would be ignored: only the lookup method"):
        lab.compare("builtin:blazed?size=6um&pixel=100nm", methods=["reference"], uv_resolution=101)
    with pytest.raises(ValueError, match="uv_power 2 would be ignored: the reference method builds no"):
        lab.sweep("builtin:blazed?size=6um&pixel=100nm", "terms", [2], "/tmp/never.png", uv_power=2.0)
    with pytest.raises(ValueError, match="the parameter swept"):
        lab.sweep("builtin:blazed?size=6um&pixel=100nm", "uv-resolution", [21], "/tmp/never.png", method="lookup",
                  uv_resolution=31)
    with pytest.raises(ValueError, match="dlambda 10nm would be ignored: dlambda is the parameter swept"):
        lab.sweep("builtin:blazed?size=6um&pixel=100nm", "dlambda", [2.0, 5.0], "/tmp/never.png", step_nm=10.0)
    with pytest.raises(ValueError, match="uv_resolution 31 would be ignored: the reference method"):
        lab.laser("builtin:blazed?size=6um&pixel=100nm", "/tmp/never.png", uv_resolution=31)
    # A value named twice, a method compared with itself, a window narrower than a pixel: the library's
    # refusals, as the CLI's.
    with pytest.raises(ValueError, match="methods lists reference twice"):
        lab.compare("builtin:blazed?size=6um&pixel=100nm", methods=["reference", "reference"])
    with pytest.raises(ValueError, match="exposures lists 1 twice"):
        lab.compare("builtin:blazed?size=6um&pixel=100nm", methods=["reference"], exposures=[1.0, 1.0])
    with pytest.raises(ValueError, match="reference would be compared with itself"):
        lab.compare("builtin:blazed?size=6um&pixel=100nm", methods=["reference"], against="reference")
    with pytest.raises(ValueError, match="values lists 2 twice"):
        lab.sweep("builtin:blazed?size=6um&pixel=100nm", "terms", [2, 2], "/tmp/never.png")
    with pytest.raises(ValueError, match="shorter than this scan's 100 nm pixels carry.*at least 400 nm"):
        lab.compare("builtin:blazed?size=6um&pixel=100nm", methods=["reference"], coherence_nm=300.0)


# --- order efficiencies: iridis grating -------------------------------------------------------------------

def test_grating_equals_the_cli():
    ref = cli("grating_rigorous")
    g = diffraction.grating("builtin:sine?size=1100nm&pixel=10nm", light=math.radians(30), wavelengths_nm=550.0,
                            method="rigorous")
    assert g["method"] == "rigorous" and len(g["orders"]) == len(ref["orders"])
    for a, b in zip(g["orders"], ref["orders"]):
        assert (a["m"], a["n"]) == (b["m"], b["n"])
        close([a["efficiency"][k] for k in ("te", "tm")], [b["efficiency"][k] for k in ("te", "tm")], rtol=1e-12)
    # Glass (n = 1.5, the default) is lossless: reflected + transmitted is all the light, TE and TM.
    for pol in ("te", "tm"):
        total = g["reflected_total"][0][pol] + g["transmitted_total"][0][pol]
        assert abs(total - 1.0) < 1e-6, (pol, total)


def test_grating_kirchhoff_conserves_energy_and_knows_its_colours():
    g = diffraction.grating("builtin:sine?size=1100nm&pixel=10nm", light=math.radians(75),
                            wavelengths_nm=np.arange(380.0, 781.0, 10.0), material="n=0.0001+30i")
    totals = [t["unpolarized"] for t in g["reflected_total"]]
    assert max(totals) <= 1.0 + 1e-12 and min(totals) > 0.99
    c = g["colour"]
    assert c["illuminant"] == "d65" and 0.0 < c["diffracted_share"] < 1.0
    printed = diffraction.grating("builtin:sine?size=1100nm&pixel=10nm", light=math.radians(75), wavelengths_nm=500.0,
                                  material="n=0.0001+30i", normalisation="kirchhoff")
    assert printed["reflected_total"][0]["unpolarized"] > 1.05  # the printed obliquity creates energy


def test_evaluate_gives_the_brdf_in_per_steradian():
    ref = cli("brdf_eval_reference")
    q = diffraction.evaluate("builtin:sine", light=math.radians(30), view=(math.radians(10), math.pi))
    for k in ("s", "p", "unpolarized"):
        close(q["brdf_per_sr"][k], ref["brdf_per_sr"][k], rtol=1e-10, atol=1e-14)
    # f_r = R₀ ρ A_eff/λ² / cos θ_i (Schlick: s = p = unpolarised).
    area_nm2 = q["window_effective_area_um2"] * 1e6
    expect = 0.04 * q["reflectance"] * area_nm2 / q["wavelength_nm"] ** 2 / math.cos(math.radians(30))
    close(q["brdf_per_sr"]["unpolarized"], expect, rtol=1e-9, atol=1e-14)


def test_grating_says_how_the_patch_holds_its_period():
    # 8 µm over a 1100 nm sine is 7.27 periods: taken as one cell, the nearest of the cell's orders keeps
    # sinc²(0.27) of each of the sine's (numpy's normalised sinc); 7.7 µm holds 7 and keeps all.
    g = diffraction.grating("builtin:sine?size=8um&pixel=50nm&depth=1nm", light=0.0, wavelengths_nm=500.0)
    fit = g["unit_cell"]["period_fit"]
    assert fit["cycles_x"] == pytest.approx(8000.0 / 1100.0, abs=0.01) and not fit["tiles"]
    assert fit["nearest_order_share"] == pytest.approx(np.sinc(fit["cycles_x"] - 7.0) ** 2, rel=1e-9)
    assert fit["nearest_order_share"] == pytest.approx(np.sinc(8000.0 / 1100.0 - 7.0) ** 2, abs=0.005)
    g = diffraction.grating("builtin:sine?size=7.7um&pixel=50nm&depth=1nm", light=0.0, wavelengths_nm=500.0)
    assert g["unit_cell"]["period_fit"]["tiles"]


def test_grating_lists_orders_above_a_floor():
    # orders_above (--orders-above): only the orders of at least that efficiency are listed, the rest counted in
    # unlisted_orders and still in the totals, which are those of the full listing.
    spec = "builtin:sine?size=1100nm&pixel=10nm"
    every = diffraction.grating(spec, light=0.0, wavelengths_nm=550.0)
    some = diffraction.grating(spec, light=0.0, wavelengths_nm=550.0, orders_above=1e-3)
    kept = [o for o in every["orders"] if o["efficiency"]["unpolarized"] >= 1e-3]
    assert [(o["m"], o["n"]) for o in some["orders"]] == [(o["m"], o["n"]) for o in kept]
    assert some["unlisted_orders"]["per_wavelength"] == [len(every["orders"]) - len(kept)]
    assert some["reflected_total"] == every["reflected_total"]
    with pytest.raises(ValueError, match="orders_above 2"):
        diffraction.grating(spec, light=0.0, wavelengths_nm=550.0, orders_above=2.0)


def test_grating_bad_input():
    with pytest.raises(ValueError, match="rigorous method needs the material"):
        diffraction.grating("builtin:sine?size=1100nm&pixel=10nm", light=0.1, wavelengths_nm=500.0,
                            method="rigorous", fresnel="schlick:1.5")
    with pytest.raises(ValueError, match="method"):
        diffraction.grating("builtin:sine?size=1100nm&pixel=10nm", light=0.1, wavelengths_nm=500.0, method="fdtd")
    with pytest.raises(ValueError, match="normalisation kirchhoff would be ignored"):
        diffraction.grating("builtin:sine?size=1100nm&pixel=10nm", light=0.1, wavelengths_nm=500.0,
                            method="rigorous", normalisation="kirchhoff")


def test_grating_compare_equals_the_cli():
    ref = cli("grating_compare")
    c = diffraction.grating("builtin:sine?size=1100nm&pixel=10nm", light=math.radians(20),
                            wavelengths_nm=np.arange(380.0, 781.0, 20.0), material="gold", compare=True)
    close(c["worst_relative_error"]["unpolarized"], ref["worst_relative_error"]["unpolarized"], rtol=1e-9)
    close(c["delta_e00_diffracted"], ref["delta_e00_diffracted"], rtol=1e-9)
    assert len(c["orders"]) == len(ref["orders"]) and c["rigorous_converged"]
    with pytest.raises(ValueError, match="no wavelength given"):
        diffraction.grating("builtin:sine", light=0.1, wavelengths_nm=[])
    with pytest.raises(ValueError, match="not -500"):
        diffraction.grating("builtin:sine", light=0.1, wavelengths_nm=[500.0, -500.0])


def test_vision_along_a_plane_equals_the_cli_and_a_sine_is_symmetric():
    v = diffraction.vision("builtin:sine?size=4.4um&pixel=50nm&period=1100nm&depth=100nm", "bluetit",
                           views_deg=(-25, 25), azimuth=0.0)
    a, b = (np.asarray(x["reflectance_factor"]) for x in v["views"])
    assert np.max(np.abs(a - b)) <= 1e-9 * np.max(a)  # |c_m| = |c_-m| for a sine
    assert v["wavelength_nm"][0] == 300.0 and v["vision"]["receptors"] == ["UVS", "SWS", "MWS", "LWS"]
    with pytest.raises(ValueError, match="lists 25 twice"):
        diffraction.vision("builtin:sine", "bluetit", views_deg=(25, 25.0))
    # The model's options are used (the step) or refused (the CIE observer has no place in an animal's eye).
    coarse = diffraction.vision("builtin:sine?size=4.4um&pixel=50nm&period=1100nm&depth=100nm", "bluetit",
                                views_deg=(-25, 25), azimuth=0.0, step_nm=10.0)
    assert coarse["wavelength_nm"] == list(v["wavelength_nm"][::2])
    close(coarse["views"][0]["reflectance_factor"], v["views"][0]["reflectance_factor"][::2], rtol=1e-12)
    with pytest.raises(ValueError, match="observer 1964 would be ignored"):
        diffraction.vision("builtin:sine", "bluetit", views_deg=(25,), observer="1964")


def test_evaluate_says_what_brdf_eval_says():
    # evaluate(method="rigorous") gave f_r without the record of what it rests on (material, unit cell, solves,
    # estimated error), which brdf_eval and `iridis brdf eval --json` give; nor the Fresnel factor's R0.
    cell = "builtin:sine?size=1100nm&pixel=10nm&depth=20nm"
    for method, options in (("rigorous", {"material": "gold"}), ("reference", {"fresnel": "schlick:1.5"})):
        e = diffraction.evaluate(cell, 0.3, (0.2, 3.0), method=method, step_nm=20.0, **options)
        b = diffraction.brdf_eval(cell, 0.3, (0.2, 3.0), method=method, step_nm=20.0, **options)
        for key in ("rigorous", "polarised", "fresnel_r0", "table"):
            assert e[key] == b[key], (method, key, e[key], b[key])
    assert e["fresnel_r0"] == pytest.approx(0.04) and e["polarised"] is False
