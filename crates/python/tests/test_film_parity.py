"""What the CLI does for thin films, from Python: ``iridis.thinfilm.fit`` and ``profile`` against the CLI's
``--json`` on committed fixtures (crates/python/tests/fixtures/make_cli_fixtures.sh), per-wavelength index
arrays, and every array argument checked with a ValueError that says what to do."""
import json
import os

import numpy as np
import pytest

import iridis.thinfilm as tf

FIX = os.path.join(os.path.dirname(__file__), "fixtures")


def cli(name):
    with open(os.path.join(FIX, name + ".json")) as f:
        return json.load(f)


def test_fit_from_a_file_reproduces_the_cli():
    ref = cli("fit_sio2")
    out = tf.fit(os.path.join(FIX, "measured_sio2_si.txt"), "air | SiO2 {d=120nm:50nm..300nm} | Si", to_nm=826,
                 sigma=0.1)
    for key in ("values", "sigma", "fitted", "wavelength_nm", "measured"):
        np.testing.assert_allclose(out[key], ref[key], rtol=1e-10, atol=0, err_msg=key)
    np.testing.assert_allclose(out["correlation"], ref["correlation"], rtol=1e-10)
    for key in ("chi2", "reduced_chi2"):
        assert abs(out[key] - ref[key]) <= 1e-10 * ref[key], key
    for key in ("names", "units", "dof", "sigma_given", "at_bound", "starts", "jacobian", "quantity"):
        assert out[key] == ref[key] or list(out[key]) == ref[key], key
    assert out["read"] == ref["read"]
    assert out["read"]["percent"] and "divided by 100" in out["read"]["notes"][1]


def test_fit_from_arrays_finds_the_thickness_and_its_uncertainty():
    # The model's own spectrum with Gaussian noise of σ = 0.002: the fit returns the thickness within its 1σ
    # (3σ to keep the test deterministic-safe) and σ/dof near 1 (scipy's least_squares agrees, filmfit tests).
    rng = np.random.default_rng(29)
    wl = np.linspace(420, 780, 121)
    truth = tf.Stack("air | n=1.46 312nm | si-green").reflectance(wl)
    r = truth + rng.normal(0, 0.002, wl.size)
    out = tf.fit((wl, r), "air | n=1.46 {d=250nm:200nm..400nm} | si-green", sigma=0.002)
    d, s = out["values"][0], out["sigma"][0]
    assert abs(d - 312.0) < 3 * s and 0 < s < 1.0, (d, s)
    assert 0.7 < out["reduced_chi2"] < 1.3
    # The same in percent, said so; values above 1 without it are refused with the hint.
    same = tf.fit((wl, 100 * r), "air | n=1.46 {d=250nm:200nm..400nm} | si-green", sigma=0.2, percent=True)
    assert abs(same["values"][0] - d) < 1e-8
    with pytest.raises(ValueError, match="percent=True"):
        tf.fit((wl, 100 * r), "air | n=1.46 {d=250nm:200nm..400nm} | si-green")
    # A window, and wavelengths in µm refused with the factor to use.
    win = tf.fit((wl, r), "air | n=1.46 {d=250nm:200nm..400nm} | si-green", from_nm=500, to_nm=700)
    assert win["wavelength_nm"].min() >= 500 and win["wavelength_nm"].max() <= 700
    # 500–700 nm of 420–780 in 3 nm steps: 67 of the 121 kept, as the file reader says it.
    assert win["wavelength_nm"].size == 67
    assert "54 of 121 rows outside the wavelength window left out" in win["read"]["notes"]


def test_fit_from_arrays_is_read_and_warned_as_a_file_is():
    """Arrays go through the library's reader and fit (iridis_api::film_fit::fit_arrays): what a file's reading
    would refuse or say, arrays get too, instead of keywords being dropped."""
    wl = np.linspace(420, 780, 121)
    r = tf.Stack("air | n=1.46 312nm | si-green").reflectance(wl)
    stack = "air | n=1.46 {d=250nm:200nm..400nm} | si-green"
    with pytest.raises(ValueError, match="columns '1,2' would be ignored: the measurement was given as arrays"):
        tf.fit((wl, r), stack, columns="1,2")
    with pytest.raises(ValueError, match="sigma 'R_err': with arrays give a number"):
        tf.fit((wl, r), stack, sigma="R_err")
    with pytest.raises(ValueError, match="uncertainty given twice"):
        tf.fit((wl, r, np.full(wl.size, 0.01)), stack, sigma=0.01)
    with pytest.raises(ValueError, match="no wavelength of the arrays"):
        tf.fit((wl, r), stack, from_nm=800, to_nm=900)
    # A thickness range that ends below the truth: the fit stops on the bound, and says so, as for a file.
    with pytest.warns(UserWarning, match="d ended on a bound of its range"):
        out = tf.fit((wl, r), "air | n=1.46 {d=250nm:200nm..300nm} | si-green", grid=1)
    assert out["at_bound"] == [True] and abs(out["values"][0] - 300.0) < 1e-6
    # Weights as a number: w = 1/σ², the same fit as σ.
    a = tf.fit((wl, r), stack, sigma=0.01)
    b = tf.fit((wl, r), stack, weights=1e4)
    np.testing.assert_allclose(a["sigma"], b["sigma"], rtol=1e-12)
    with pytest.raises(ValueError, match="multiply by 1000"):
        tf.fit((wl / 1000, r), "air | n=1.46 {d=250nm:200nm..400nm} | si-green")


def test_fit_names_the_material_that_does_not_cover_the_range():
    with pytest.raises(ValueError, match=r"substrate 'si' has data for 206.6–826.6 nm only.*si-green"):
        tf.fit(os.path.join(FIX, "measured_sio2_si.txt"), "air | SiO2 {d=120nm:50nm..300nm} | Si")
    with pytest.raises(OSError):
        tf.fit(os.path.join(FIX, "no_such_file.txt"), "air | SiO2 {d=120nm:50nm..300nm} | Si")


def test_fit_refuses_percent_for_psi_delta(tmp_path):
    # ψ and Δ are angles: a percent setting would change nothing.
    ell = tmp_path / "ellips.csv"
    ell.write_text("wavelength_nm,psi,delta\n400,30,100\n500,31,101\n600,32,102\n")
    stack = "air | n=2.1 {d=150nm:50nm..400nm} | Si"
    for percent, said in ((True, "percent"), (False, "percent=False")):
        with pytest.raises(ValueError, match=f"{said} would be ignored: ψ and Δ are angles"):
            tf.fit(str(ell), stack, np.radians(70), "psi-delta", percent=percent)


def test_profile_reproduces_the_cli():
    ref = cli("profile_gold")
    out = tf.profile("air | Au 30nm | glass", 500.0, np.radians(20.0), "p", points=41)
    for key in ("R", "T", "A_substrate", "balance"):
        assert abs(out[key] - ref[key]) <= 1e-12, key
    np.testing.assert_allclose(out["A_layers"], ref["A_layers"], rtol=1e-12)
    for key in ("z_nm", "E2", "absorption_per_nm", "flux"):
        np.testing.assert_allclose(out[key], ref["profile"][key], rtol=1e-10, atol=1e-15, err_msg=key)
    assert list(out["medium"]) == ref["profile"]["medium"] and out["layers"] == ref["layers"]
    # Energy: what is not reflected or transmitted is absorbed in the gold.
    assert abs(out["R"] + out["T"] + sum(out["A_layers"]) + out["A_substrate"] - 1) < 1e-12


def test_profile_window_note_and_unresolved_layers_warn(caplog):
    # Films on a 1 mm slide: the default window ends 100 nm into the slide (as the CLI's), logged as a note; a
    # 30 nm film that one of five samples falls in is a warning at the caller's line.
    with caplog.at_level("INFO", logger="iridis"):
        out = tf.profile("air | TiO2 60nm | Si 50nm | inc:glass 1mm | air", 550.0)
    assert "note: the depth window ends 100 nm into layer 3 (inc:glass 1000000 nm)" in caplog.text
    assert (out["z_nm"][0], out["z_nm"][-1]) == (-100.0, 210.0) and out["warnings"] == []
    with pytest.warns(UserWarning, match="gets 1 of the 5 depth samples, which are 57.5 nm apart") as rec:
        out = tf.profile("air | Au 30nm | glass", 500.0, points=5)
    assert rec[0].filename == __file__
    assert out["notes"] == [] and len(out["warnings"]) == 1


def test_index_arrays_per_wavelength():
    # A table of TiO2's index at four wavelengths equals the library material at those wavelengths, is linear
    # in between, and is refused outside (as measured data are).
    wl = np.array([400.0, 500.0, 600.0, 700.0])
    n = tf.material_index("TiO2", wl)
    table = tf.Stack.from_lists([1.0, n, 1.52], [60.0], wavelengths_nm=wl)
    lib = tf.Stack("air | TiO2 60nm | n=1.52")
    np.testing.assert_allclose(table.reflectance(wl), lib.reflectance(wl), rtol=1e-13)
    mid = tf.Stack.from_lists([1.0, 0.5 * (n[1] + n[2]), 1.52], [60.0]).reflectance(550.0)
    assert abs(table.reflectance(550.0) - mid) < 1e-13
    with pytest.raises(ValueError, match="400–700 nm only"):
        table.reflectance(750.0)
    # The same as one (media, wavelengths) array; unsorted wavelengths are sorted with their indices.
    arr = np.array([np.ones(4), n, np.full(4, 1.52)])
    two = tf.Stack.from_lists(arr, [60.0], wavelengths_nm=wl)
    np.testing.assert_allclose(two.reflectance(wl), table.reflectance(wl), rtol=1e-13)
    rev = tf.Stack.from_lists([1.0, n[::-1], 1.52], [60.0], wavelengths_nm=wl[::-1])
    np.testing.assert_allclose(rev.reflectance(wl), table.reflectance(wl), rtol=1e-13)
    # colors_of_stacks with one index per medium and wavelength of the grid.
    grid = np.arange(400.0, 701.0, 10.0)
    ni = tf.material_index("TiO2", grid)
    idx = np.array([[np.ones_like(grid), ni, np.full_like(grid, 1.52)]] * 2)
    xyz = tf.colors_of_stacks(idx, [[60.0], [90.0]], grid_nm=grid)["reflected"]
    np.testing.assert_allclose(xyz[1], tf.Stack("air | TiO2 90nm | n=1.52").color(grid_nm=grid)["reflected"],
                               rtol=1e-12)
    with pytest.raises(ValueError, match="give their wavelengths"):
        tf.Stack.from_lists([1.0, n, 1.52], [60.0])
    with pytest.raises(ValueError, match=r"shape \(3,\)"):
        tf.Stack.from_lists([1.0, n[:3], 1.52], [60.0], wavelengths_nm=wl)


@pytest.mark.parametrize(
    "call, words",
    [
        # issue 29: a thickness offset of −100 nm or NaN gave the bare substrate, color(0, nan) "#000000", a
        # wavelength of 550e-9 (metres) was computed as 0.00000055 nm.
        (lambda s: s.rta(550.0, 0.0, -100.0), "offsets must be ≥ -80 nm"),
        (lambda s: s.rta(550.0, 0.0, np.nan), "finite number"),
        (lambda s: s.color(0, np.nan), "finite number"),
        (lambda s: s.rta(550e-9), "looks like metres"),
        (lambda s: s.rta(0.55), "looks like µm"),
        (lambda s: s.rta([450.0, np.nan]), "wavelengths_nm holds nan"),
        (lambda s: s.rta(550.0, 30.0), "if these are degrees, convert them with numpy.radians"),
        (lambda s: s.color(grid_nm=np.linspace(0.38, 0.78, 81)), "looks like µm"),
        (lambda s: s.indices([-5.0]), "must be > 0"),
        (lambda s: tf.material_index("Si", [np.inf]), "finite number"),
        (lambda s: s.rough(25.0, 300.0).spectrum([550e-9]), "looks like metres"),
        (lambda s: tf.profile(s, 550e-9), "looks like metres"),
        (lambda s: tf.profile(s, 550.0, depth_nm=(10.0, -10.0)), "is empty"),
        (lambda s: tf.Stack.from_lists([1.0, np.nan, 1.5], [80.0]), "NaN"),
        (lambda s: tf.Stack.from_lists([1.0, 2.0, 1.5], [-80.0]), "must be ≥ 0"),
        (lambda s: tf.colors_of_stacks([[1.0, 2.0, np.nan]], [[80.0]]), "NaN"),
        (lambda s: tf.colors_of_stacks([[1.0, 2.0, 1.5]], [[80.0]], angle_rad=45.0), "numpy.radians"),
        (lambda s: tf.fit((np.array([400.0, 500, 600]), np.array([0.1, np.nan, 0.2])), "air | n={n=1.5:1..2}"),
         "finite number"),
    ],
)
def test_bad_arrays_raise_value_errors_that_say_what_to_do(call, words):
    s = tf.Stack("air | n=2.0 80nm | n=1.5")
    with pytest.raises(ValueError) as info:
        call(s)
    assert words in str(info.value)


def test_an_exact_spectrum_has_finite_correlations_and_film_fit_points_arrays_to_thinfilm_fit():
    """A computed spectrum fitted without σ: χ² = 0, so the uncertainties are 0 (σ is estimated from a scatter of
    0), and the correlations — which no scale of σ changes — are those of a fit with σ given (they were NaN).
    ``iridis.film.fit`` reads files as the CLI does; arrays handed to it are pointed to ``iridis.thinfilm.fit``
    (str() of the tuple was read as a file name)."""
    import iridis.film as film
    wl = np.linspace(400, 800, 81)
    r = tf.Stack("air | n=1.46 250nm | si-green").reflectance(wl)
    template = "air | n={n=1.5:1.3..1.7} {d=200nm:50nm..400nm} | si-green"
    exact, given = tf.fit((wl, r), template), tf.fit((wl, r), template, sigma=0.01)
    np.testing.assert_allclose(exact["values"], [1.46, 250.0], rtol=1e-9)
    if exact["chi2"] == 0.0:
        assert list(exact["sigma"]) == [0.0, 0.0]
    np.testing.assert_allclose(exact["correlation"], given["correlation"], atol=1e-6)
    with pytest.raises(TypeError, match=r"for arrays use iridis\.thinfilm\.fit"):
        film.fit((wl, r), template)
    # The other readers of the CLI's files point to their array functions alike.
    import iridis.color as color
    import iridis.vision as vision
    with pytest.raises(TypeError, match=r"for arrays use iridis\.color\.spectrum_to_xyz"):
        color.xyz((wl, r))
    with pytest.raises(TypeError, match=r"for arrays use iridis\.vision\.analyse"):
        vision.vision((wl, r), visual="bluetit")
