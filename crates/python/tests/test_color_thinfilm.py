"""iridis.color against colour-science and Sharma et al. (the Rust crate's fixtures, same tolerances), and
iridis.thinfilm against Sussenbach's printed table, tmm, and the CLI's documented colours."""
import numpy as np
import pytest

import iridis.color as color
import iridis.thinfilm as tf


def test_spectra_match_colour_science(colour_science):
    wl = np.array(colour_science["wavelengths_nm"])
    for e in colour_science["spectra"]:
        v = np.array(colour_science["spectrum_values"][e["name"]])
        xyz = color.spectrum_to_xyz(wl, v, e["illuminant"], e["observer"])
        # colour-science integrates with the rectangle rule, iridis with the trapezoid rule (see the Rust test).
        assert np.max(np.abs(xyz - e["XYZ"])) < 2e-5, e["name"]
        lab = color.xyz_to_lab(xyz, illuminant=e["illuminant"], observer=e["observer"])
        assert np.max(np.abs(lab - e["Lab"])) < 2e-3
        assert np.max(np.abs(color.xyz_to_linear_srgb(xyz) - e["linear_srgb"])) < 1e-4


def test_many_spectra_at_once_equal_one_by_one(colour_science):
    wl = np.array(colour_science["wavelengths_nm"])
    stack = np.array([colour_science["spectrum_values"][k] for k in ("bumps0", "bumps1", "bumps2", "oscillation")])
    both = color.spectrum_to_xyz(wl, stack.reshape(2, 2, -1))
    assert both.shape == (2, 2, 3)
    for i in range(4):
        np.testing.assert_array_equal(both.reshape(4, 3)[i], color.spectrum_to_xyz(wl, stack[i]))


def test_a_spectrum_short_of_the_visible_range_is_warned_about_as_in_the_cli():
    # Known from 400 to 500 nm and flat there: its end values are held, so it is D65's white (Y = 1) — said,
    # as `iridis color xyz` says it.
    with pytest.warns(UserWarning, match="the spectrum covers 400–500 nm, less than the visible 380–780 nm"):
        xyz = color.spectrum_to_xyz([400.0, 500.0], [1.0, 1.0])
    np.testing.assert_allclose(xyz, color.white_point(), atol=1e-9)


def test_white_points_match_colour_science(colour_science):
    for e in colour_science["illuminants"]:
        np.testing.assert_allclose(color.white_point(e["illuminant"], e["observer"]), e["XYZ"], atol=2e-5)
        np.testing.assert_allclose(color.xyz_to_xyy(e["XYZ"])[:2], e["xy"], atol=1e-12)


def test_ciede2000_matches_sharma(sharma):
    a = np.array([p["lab1"] for p in sharma["pairs"]])
    b = np.array([p["lab2"] for p in sharma["pairs"]])
    expected = np.array([p["delta_e_2000"] for p in sharma["pairs"]])
    assert np.max(np.abs(color.delta_e(a, b) - expected)) <= 1e-4
    assert abs(color.delta_e([50, 3, 4], [50, 0, 0], formula="1976") - 5.0) < 1e-15
    # The keyword's former name still reads, with a DeprecationWarning; both names at once are refused.
    with pytest.warns(DeprecationWarning, match="method= is now formula="):
        assert abs(color.delta_e([50, 3, 4], [50, 0, 0], method="1976") - 5.0) < 1e-15
    with pytest.raises(TypeError, match="both formula= and its former name method="):
        color.delta_e([50, 3, 4], [50, 0, 0], formula="2000", method="1976")
    np.testing.assert_allclose(color.lab_to_xyz(color.xyz_to_lab([[0.2, 0.3, 0.4]])), [[0.2, 0.3, 0.4]], atol=1e-12)


# Sussenbach, Figure 3.8: "air | water 635nm | air" at 1°, R and T as printed (6 significant digits).
FIGURE_3_8 = [(400.0, 0.0334109, 0.966589), (450.0, 0.03932, 0.96068), (550.0, 0.00405254, 0.995948),
              (690.0, 0.0752091, 0.924791)]


def test_soap_film_reproduces_figure_3_8():
    soap = tf.Stack("air | water 635nm | air")
    wl = np.array([w for w, _, _ in FIGURE_3_8])
    out = soap.rta(wl, np.radians(1.0))
    assert np.max(np.abs(out["R"] - [r for _, r, _ in FIGURE_3_8])) < 1e-6
    assert np.max(np.abs(out["T"] - [t for _, _, t in FIGURE_3_8])) < 1e-6
    assert np.max(np.abs(out["A"])) < 1e-12


tmm = pytest.importorskip("tmm")


def test_broadcast_over_wavelength_angle_offset_equals_tmm():
    stack = tf.Stack.from_lists([1.0, 1.38, 2.1, 1.52], [110.0, 70.0])
    wl = np.linspace(400, 700, 7)[:, None, None]
    th = np.radians([0.0, 35.0, 70.0])[None, :, None]
    off = np.array([-20.0, 0.0, 15.0])[None, None, :]
    for pol in ("s", "p", "unpolarized"):
        out = stack.rta(wl, th, off, polarization=pol)
        assert out["R"].shape == (7, 3, 3)
        for i, j, k in [(0, 0, 0), (3, 1, 2), (6, 2, 1)]:
            d = [np.inf, 110.0 + off[0, 0, k], 70.0 + off[0, 0, k], np.inf]
            args = ([1.0, 1.38, 2.1, 1.52], d, th[0, j, 0], wl[i, 0, 0])
            ref = tmm.unpolarized_RT(*args) if pol == "unpolarized" else tmm.coh_tmm(pol, *args)
            assert abs(out["R"][i, j, k] - ref["R"]) < 1e-12 and abs(out["T"][i, j, k] - ref["T"]) < 1e-12


def test_rough_and_smooth_colour_of_the_readme():
    # The README's table (the CLI, `iridis thinfilm color --stack "air | water 348nm | Si" --angle 30deg`).
    c = tf.Stack("air | water 348nm | Si").color(np.radians(30.0))
    assert c["reflected_hex"] == "#6d75ad"
    np.testing.assert_allclose(c["reflected_lab"], [50.8, 10.9, -30.6], atol=0.05)


def test_colour_of_a_thickness_sweep_equals_single_stacks():
    base = tf.Stack("air | water 300nm | air")
    sweep = base.color(0.0, np.array([0.0, 48.0, 200.0]))
    for k, d in enumerate([300, 348, 500]):
        one = tf.Stack(f"air | water {d}nm | air").color(0.0)
        np.testing.assert_allclose(sweep["reflected"][k], one["reflected"], rtol=0, atol=1e-14)


@pytest.mark.parametrize(
    "call, exc, words",
    [
        (lambda: tf.Stack("air | water 348 | air"), ValueError, "water"),
        (lambda: tf.Stack(["air"]), TypeError, "Stack takes"),
        (lambda: tf.Stack("air | Si 10nm | air").reflectance(1000.0), ValueError, "no extrapolation"),
        (lambda: tf.Stack("air | water 1nm | air").reflectance(500.0, 2.0), ValueError, "lie in 0…π/2 rad"),
        (lambda: tf.Stack("air | water 1nm | air").reflectance(np.full(3, 500.0), np.zeros(4)), ValueError, "broadcast"),
        (lambda: tf.Stack("air | water 1nm | air").reflectance(["a"]), TypeError, "real numbers"),
        (lambda: tf.Stack("air | water 1nm | air").rta(500.0, polarization="q"), ValueError, "polarization"),
        (lambda: tf.Stack.from_lists([1, 1.5], [10.0]), ValueError, "thicknesses"),
        (lambda: color.spectrum_to_xyz([400, 500], [1, 2, 3]), ValueError, "wavelengths"),
        (lambda: color.spectrum_to_xyz([500, 400], [1, 2]), ValueError, "must increase"),
        (lambda: color.spectrum_to_xyz([400, 500], [1, 2], illuminant="F2"), ValueError, "illuminant"),
        (lambda: color.spectrum_to_xyz([], []), ValueError, "at least two samples"),
        (lambda: color.xyz_to_srgb([0.5, 0.5, 0.5], exposure=-1), ValueError, "positive finite"),
        (lambda: color.xyz_to_hex([0.5, 0.5, 0.5], exposure=float("nan")), ValueError, "positive finite"),
        (lambda: color.xyz_to_lab([1, 2]), ValueError, "length 3"),
        (lambda: color.xyz_to_lab(["a", "b", "c"]), TypeError, "real numbers"),
        (lambda: color.delta_e([1, 2, 3], [1, 2, 3], formula="94"), ValueError, "unknown ΔE formula '94'"),
    ],
)
def test_bad_input_raises_with_a_message(call, exc, words):
    with pytest.raises(exc) as info:
        call()
    assert words in str(info.value)
