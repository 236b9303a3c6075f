"""Bad input from Python raises a specific exception, never a Rust panic, an abort, a hang or a silent NaN: the
findings of an audit of every function with malformed arguments (2026-11-29), each fixed."""
import math
import os

import numpy as np
import pytest
from conftest import ROOT

import iridis.bench as bench
import iridis.color as color
import iridis.diffraction as diffraction
import iridis.film as film
import iridis.surface as surface
import iridis.thinfilm as thinfilm
import iridis.tmm as tmm
import iridis.vision as vision

SINE = "builtin:sine?size=3300nm&pixel=100nm&period=1100nm"


def test_sizes_are_checked_before_anything_is_allocated():
    # 10¹² was a PanicException (capacity overflow), 10⁵ an 80 GB allocation that aborted the interpreter.
    for size in (10**12, 100000):
        with pytest.raises(ValueError, match=r"the bench surface's side must be from 8 to 8192"):
            bench.run("diffraction", size=size, map_sizes=[8])
    with pytest.raises(ValueError, match=r"size 1000000: width and height must be from 1 to 16384 pixels"):
        bench.run("render", size=10**6, spp=1)
    with pytest.raises(ValueError, match=r"seconds 1e300: must be positive and at most 300"):
        film.bench(seconds=1e300, no_python=True)


def test_a_wavelength_too_short_for_the_period_is_refused_by_the_rigorous_solver():
    # 0.5 nm (µm meant): ~10 000 orders each side of a 3300 nm cell, an eigenproblem that grew past 6 GB; it is
    # refused as light too short for these models. Light they take can still need more orders than the solver
    # resolves: a 20 µm period at 10 nm has 3199 each side.
    with pytest.raises(ValueError, match=r"0.5 nm is shorter than the light these models take"):
        diffraction.grating(SINE, 0.1, [0.5], method="rigorous")
    with pytest.raises(ValueError, match=r"3199 orders propagate each side along a period of 20000 nm at λ = 10 nm"):
        diffraction.grating("builtin:sine?size=20um&pixel=100nm&period=20um", 0.1, [10], method="rigorous")
    with pytest.raises(TypeError, match=r"wavelengths_nm must be a number or a sequence of numbers"):
        diffraction.grating(SINE, 0.1, "500")


def test_a_fixed_series_count_past_underflow_is_the_same_sum():
    # D-iterations = 10⁹ ran for minutes; past where the weights underflow every term is 0.
    kw = dict(roughness_nm=20, correlation_nm=200, from_nm=500, to_nm=510, step_nm=10)
    huge = film.spectrum("air | SiO2 100nm | Si", d_iterations=10**9, **kw)
    enough = film.spectrum("air | SiO2 100nm | Si", d_iterations=5000, **kw)
    assert huge["diffuse_per_sr"] == enough["diffuse_per_sr"]
    assert huge["series_terms_max"] < 5000


def test_the_light_of_a_directional_vision_must_be_above_the_surface():
    with pytest.raises(ValueError, match=r"light 2578.31\d*°: the light's polar angle must be from 0°"):
        diffraction.vision(SINE, "bluetit", light=45, views_deg=[0, 10])
    with pytest.raises(ValueError, match=r"light NaN°"):
        diffraction.vision(SINE, "bluetit", light=float("nan"), views_deg=[0, 10])
    with pytest.raises(ValueError, match=r"azimuth NaN"):
        diffraction.vision(SINE, "bluetit", light=0.2, azimuth=float("nan"), views_deg=[0, 10])


def test_inc_tmm_checks_the_whole_stack_as_coh_tmm_does():
    n, d, c = [1, 1.5, 1], [np.inf, 1000, np.inf], ["i", "i", "i"]
    with pytest.raises(tmm.TmmInputError, match=r"lam_vac|wavelength"):
        tmm.inc_tmm("s", n, d, c, 0.1, -500)
    with pytest.raises(tmm.TmmInputError, match=r"th_0"):
        tmm.inc_tmm("s", n, d, c, 2.0, 500)
    with pytest.raises(tmm.TmmInputError, match=r"n_list\[1\]"):
        tmm.inc_tmm("s", [1, np.nan, 1], d, c, 0.1, 500)
    # A valid all-incoherent stack still gives tmm's numbers: one slab, R = r + t²r/(1 − r²) (r = 0.04).
    r = ((1.5 - 1) / (1.5 + 1)) ** 2
    assert math.isclose(tmm.inc_tmm("s", n, d, c, 0.0, 500)["R"], r + (1 - r) ** 2 * r / (1 - r * r), rel_tol=1e-12)
    with pytest.raises(ValueError, match=r"\|n\| is beyond 1e6"):
        tmm.coh_tmm("s", [1, 1e300, 1], [np.inf, 100, np.inf], 0.1, 500)


def test_colour_conversions_refuse_nan_and_a_bad_white():
    with pytest.raises(ValueError, match=r"xyz holds a value that is not finite in colour 0"):
        color.xyz_to_hex([np.nan, 0.5, 0.5])
    # The linear conversions keep NaN as NaN, numpy's way for masked pixels.
    assert np.isnan(color.xyz_to_xyy([[np.nan, 0.5, 0.5], [0.2, 0.3, 0.4]])[0]).any()
    with pytest.raises(ValueError, match=r"white = \[0.0, 0.0, 0.0\]: a white point's X, Y and Z must be positive"):
        color.xyz_to_lab([0.5, 0.5, 0.5], white=[0, 0, 0])
    with pytest.raises(TypeError, match=r"emissive must be True or False, got str 'no'"):
        color.xyz(os.devnull, emissive="no")


def test_sensitivities_take_wavelengths_in_nm_in_the_receptors_range():
    with pytest.raises(ValueError, match=r"looks like µm"):
        vision.sensitivities([0.4, 0.5, 0.6], "bluetit")
    with pytest.raises(ValueError, match=r"wavelengths_nm"):
        vision.sensitivities([400.0, np.nan], "bluetit")
    with pytest.warns(UserWarning, match=r"1 of the wavelengths lie outside the 300–700 nm"):
        _, s = vision.sensitivities([500.0, 800.0], "bluetit")
    assert (s[:, 1] == 0).all() and (s[:, 0] > 0).any()


def test_a_colour_grid_outside_the_visible_is_refused_and_a_partial_one_said():
    with pytest.raises(ValueError, match=r"1000–1500 nm \(from_nm/to_nm\) holds 0.00 % of it"):
        film.color("air | water 348nm | air", from_nm=1000, to_nm=1500)
    with pytest.warns(UserWarning, match=r"integrate over 500–600 nm only .* normalised on this band"):
        film.color("air | water 348nm | air", from_nm=500, to_nm=600)


def test_missing_files_are_os_errors(tmp_path):
    missing = "/nonexistent/iridis-audit.csv"
    for call in (lambda: color.xyz(missing), lambda: vision.vision(missing, "bluetit"),
                 lambda: thinfilm.Stack(f"air | file:{missing} 100nm | Si")):
        with pytest.raises(OSError, match=r"iridis-audit.csv"):
            call()
    # A directory where a file belongs cannot be read either: an OSError too, not the stack's syntax.
    with pytest.raises(OSError, match=r"cannot read"):
        thinfilm.Stack(f"air | file:{tmp_path} 100nm | Si")


def test_stack_shapes_are_said_plainly():
    with pytest.raises(ValueError, match=r"a stack needs at least two media"):
        thinfilm.Stack.from_lists([1.0], [])
    with pytest.raises(ValueError, match=r"one row per stack"):
        thinfilm.colors_of_stacks([1.0, 1.5, 1.0], [100.0])
    with pytest.raises(ValueError, match=r"give one material .* not a stack"):
        thinfilm.material_index("", [500.0])


def test_negative_counts_name_their_argument():
    # The binding's conversion said only "can't convert negative int to unsigned".
    with pytest.raises(ValueError, match=r"size = -5 must be ≥ 0"):
        diffraction.brdf_map(SINE, size=-5)
    with pytest.raises(ValueError, match=r"subsamples = -1 must be ≥ 0"):
        diffraction.brdf_map(SINE, size=16, subsamples=-1)
    with pytest.raises(ValueError, match=r"peaks = -1 must be ≥ 0"):
        surface.load(SINE).info_text(peaks=-1)
    with pytest.raises(ValueError, match=r"points = 2.5 must be a whole number"):
        film.profile("air | water 348nm | air", 550, points=2.5)


def test_a_negative_diffraction_order_is_taken_and_a_negative_size_named():
    import iridis.lab as lab
    import iridis.render as render

    # The CLI takes --order -1: so does Python (a check for counts refused it for a moment).
    r = lab.testbench("builtin:sine?size=11um&pixel=50nm", order=-1, incidence=0.0, wavelengths=(500, 700, 100),
                      angles_deg=(-80, 80, 0.2))
    assert abs(r["periodicity_nm"]["mean"] - 1100) < 22
    with pytest.raises(ValueError, match=r"size's width = -5 must be ≥ 0"):
        render.render(os.path.join(ROOT, "examples", "gold_sphere.toml"), size=(-5, 5))


def test_a_whole_float_is_a_count_everywhere():
    # The wrappers' counts and the binding's keyword options read 16.0 alike (the binding refused it before).
    a = diffraction.brdf_map(SINE, size=16.0, uv_resolution=11.0, method="lookup")
    b = diffraction.brdf_map(SINE, size=16, uv_resolution=11, method="lookup")
    assert (a == b).all()
    with pytest.raises(TypeError, match=r"uv_resolution must be a whole number"):
        diffraction.brdf_map(SINE, size=16, uv_resolution=11.5, method="lookup")


def test_units_mistaken_for_nm_are_refused_everywhere(tmp_path):
    # µm or metres read as nm gave a white or grey colour with a range warning, an undefined von Kries, a
    # message about 5 nm steps, or the bare substrate; degrees for radians a bare range error.
    import iridis.color as color
    import iridis.thinfilm as tf
    wl = np.arange(400, 701, 10.0)
    r = 0.3 + 0.2 * np.sin(wl / 50)
    um = tmp_path / "um.csv"
    um.write_text("wavelength,R\n" + "".join(f"{w / 1000},{x}\n" for w, x in zip(wl, r)))
    for call in (lambda: color.spectrum_to_xyz(wl / 1000, r), lambda: color.xyz(str(um)),
                 lambda: vision.analyse(wl / 1000, r, visual="bluetit")):
        with pytest.raises(ValueError, match=r"reach only 0.7 nm: that looks like µm"):
            call()
    with pytest.raises(ValueError, match=r"looks like metres"):
        film.spectrum("air | water 348nm | air", from_nm=400e-9, to_nm=700e-9)
    with pytest.raises(ValueError, match=r"thicknesses_nm reach only 3.48e-07: that looks like metres"):
        tf.Stack.from_lists([1, 1.33, 1], [348e-9])
    with pytest.raises(ValueError, match=r"30 looks like degrees: give numpy.radians\(30\)"):
        diffraction.evaluate("builtin:sine?size=4um&pixel=100nm", 30, (0.2, 0))


def test_write_errors_name_the_file_and_are_os_errors(tmp_path):
    # Table.save named its temporary file (".iridis-vOwVAq.tmp"); Surface.write to a missing folder was a
    # ValueError where open() raises OSError.
    t = diffraction.precompute("builtin:sine?size=4um&pixel=100nm", uv_resolution=11)
    missing = tmp_path / "nope"
    with pytest.raises(OSError, match=f"cannot write {missing / 'x.npz'}: folder {missing} does not exist"):
        t.save(missing / "x.npz")
    with pytest.raises(OSError, match="folder .* does not exist"):
        surface.load("builtin:sine?size=4um&pixel=100nm").write(missing / "x.npy")
    # An observer given as a number, as delta_e takes formula=2000.
    wl = np.arange(380, 781, 5.0)
    assert np.allclose(color.spectrum_to_xyz(wl, np.ones(wl.size), observer=1964),
                       color.spectrum_to_xyz(wl, np.ones(wl.size), observer="1964"))


def test_film_angles_are_refused_by_their_keyword():
    # The core refused them as "incidence angle -17.188734° is outside 0°–90°", naming neither the keyword nor
    # the radians given.
    import iridis.thinfilm as tf
    s = tf.Stack("air | water 348nm | Si")
    with pytest.raises(ValueError, match=r"angles_rad holds -0.3 rad: angles of incidence lie in 0…π/2 rad"):
        s.rta(500.0, -0.3)
    with pytest.raises(ValueError, match=r"view_rad is 2 rad: it lies in 0…π/2 rad"):
        s.rough(25, 300).spectrum([500.0], view_rad=2.0)
    with pytest.raises(ValueError, match=r"light_rad is 30 rad: .* numpy.radians"):
        s.rough(25, 300).spectrum([500.0], view_rad=0.2, light_rad=30)
    assert s.rough(25, 300).spectrum([500.0], view_rad=0.2, azimuth_rad=4.0)["specular"].shape == (1,)


def test_stack_colours_check_their_grid_as_thinfilm_color_does():
    # Stack.color took 300–380 nm (a* 485) and two samples 400 nm apart without a word.
    import iridis.thinfilm as tf
    s = tf.Stack("air | water 348nm | air")
    # The messages name grid_nm, the keyword given, not step_nm, from_nm or to_nm, which color() does not take.
    with pytest.raises(ValueError, match=r"300–380 nm \(grid_nm\) holds 0.0\d % of it"):
        s.color(grid_nm=np.arange(300, 381, 5.0))
    with pytest.raises(ValueError, match=r"so coarsely that its white is off by .*give a finer grid_nm"):
        s.color(grid_nm=np.array([380.0, 780.0]))
    with pytest.raises(ValueError, match=r"grid_nm gives only 500 nm"):
        s.color(grid_nm=[500.0])
    with pytest.warns(UserWarning, match=r"integrate over 380–500 nm only \(grid_nm\)"):
        s.color(grid_nm=np.arange(380, 501, 5.0))
    with pytest.raises(ValueError, match=r"300–380 nm"):
        tf.colors_of_stacks([[1, 1.33, 1]], [[348.0]], grid_nm=np.arange(300, 381, 5.0))


def test_film_spectrum_in_micrometres_or_far_from_the_visible_warns():
    # film.spectrum(from_nm=0.4, to_nm=0.7) answered "R = 0.04" at 0.4–0.7 nm without a word, and the CLI's note
    # that glass's constant index is a visible-band figure went to a logger: both are warnings now.
    with pytest.warns(UserWarning, match=r"the wavelengths end at 0.7 nm: X-rays, and glass is a constant index.*"
                                         r"the range in nm is 400–700"):
        film.spectrum("air | n=1.38 100nm | glass", from_nm=0.4, to_nm=0.7, step_nm=0.1)
    with pytest.warns(UserWarning, match=r"glass is a constant index \(a visible-band figure\), used here at 200–300"):
        film.spectrum("air | n=1.38 100nm | glass", from_nm=200, to_nm=300)


def test_film_commands_name_radians():
    # film.spectrum(angle_rad=30) said "incidence angle 1718.873385° is outside 0°–90°", not that it takes radians.
    with pytest.raises(ValueError, match=r"angle_rad is 30 rad: it lies in 0…π/2 rad .*numpy.radians"):
        film.spectrum("air | water 348nm | air", angle_rad=30)
    with pytest.raises(ValueError, match=r"light_angle_rad is 45 rad"):
        film.color("air | water 348nm | air", roughness_nm=20, correlation_nm=300, light_angle_rad=45)


def test_grating_takes_the_clis_percent_and_names_radians():
    # orders_above="0.1%" raised "could not convert string to float: '0.1%'" (the CLI takes it); acceptance=2,
    # meant as degrees, said "between 0° and 90°" without naming radians.
    sine = "builtin:sine?size=1100nm&pixel=20nm"
    assert diffraction.grating(sine, orders_above="0.1%")["orders"] == diffraction.grating(sine, orders_above=0.001)["orders"]
    with pytest.raises(ValueError, match=r"orders_above must be a fraction \(0.001\) or a percentage \('0.1%'\)"):
        diffraction.grating(sine, orders_above="a tenth")
    with pytest.raises(ValueError, match=r"acceptance is 2 rad: .*convert it with math.radians"):
        diffraction.grating(sine, detector=(0.2, 0.0), acceptance=2)


def test_a_misspelt_keyword_is_pointed_to_its_name_and_warnings_come_once():
    # film.spectrum(angle=0.5) (the CLI's --angle) raised Python's bare "unexpected keyword argument"; evaluate
    # with step_nm=50 warned of its step twice.
    with pytest.raises(TypeError, match=r"unexpected keyword argument 'angle' \(did you mean angle_rad\?"):
        film.spectrum("air | water 348nm | air", angle=0.5)
    import warnings
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        diffraction.evaluate("builtin:sine?size=4um&pixel=100nm", 0.2, (0.2, 3.0), step_nm=50)
    steps = [w for w in said if "a wavelength step of 50 nm" in str(w.message)]
    assert len(steps) == 1, [str(w.message) for w in said]


def test_an_azimuth_in_degrees_is_named():
    # lab.testbench(azimuth=90) measured along 5157° and called 1119 nm definite on a 2500 nm grating; laser,
    # vision and compare took 90 rad the same way.
    import iridis.lab as lab
    with pytest.raises(ValueError, match=r"azimuth 5156.62° is beyond one turn"):
        lab.testbench("builtin:blazed?size=10um&pixel=100nm", azimuth=90)
    with pytest.raises(ValueError, match=r"azimuth φ = 90 rad is beyond one turn .*numpy.radians\(90\)"):
        diffraction.vision("builtin:sine?size=4um&pixel=100nm", "bluetit", azimuth=90)
