"""The report, surface files and the lab's sweeps and laser from Python: the same library calls as `iridis
report`, `iridis surface convert|channels`, `iridis sweep` and `iridis experiment laser`, checked against
numpy, the law of reflection and the other path through the library (`lab.compare`)."""
import json
import math
import os
import warnings

import numpy as np
import pytest

import iridis
import iridis.lab as lab
import iridis.surface as surface

FIXTURES = os.path.join(os.path.dirname(__file__), "..", "..", "surface", "tests", "fixtures")


def test_report_of_an_instrument_file(tmp_path):
    """The synthetic Nanonis scan (5 nm · sin(2π x / 10 px) + a tilt, 10 nm pixels): numpy's plane-levelled Sq
    is 3.4721342 nm (as crates/cli/tests/surface_cli.rs), and its 100 nm period cannot diffract visible light
    (a first order needs d > λ/2 ≥ 190 nm), so no map and no bench."""
    out = tmp_path / "rep"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = iridis.report(os.path.join(FIXTURES, "nanonis_synthetic.sxm"), out, channel="Z_forward", size=16)
    assert (r["info"]["cols"], r["info"]["rows"]) == (40, 24)
    assert r["info"]["roughness"]["sq_nm"] == pytest.approx(3.4721342067, rel=1e-4)
    assert r["diffracts_visible_light"] is False and r["testbench"] is None
    assert "100 nm" in r["verdict"]
    assert r["text"].splitlines()[1] == r["verdict"]
    on_disk = json.loads((out / "report.json").read_text())
    assert on_disk["verdict"] == r["verdict"] and on_disk["commands"] == r["commands"]
    for f in ("index.html", "relief.png", "psdf.png", "acf.png"):
        assert (out / f).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" or f == "index.html"
    assert not (out / "brdf_0deg.png").exists()


def test_report_refuses_what_its_steps_would_before_they_run(tmp_path):
    """As the CLI: the maps' size and the animal before any step, a coherence window narrower than the scan's
    pixels (4 × 100 nm) before the first model step; no file is written."""
    spec = "builtin:sine?size=4um&pixel=100nm"
    with pytest.raises(ValueError, match="size 0 must be between 8 and 8192"):
        iridis.report(spec, tmp_path / "a", size=0)
    with pytest.raises(ValueError, match="unknown visual system 'cat'"):
        iridis.report(spec, tmp_path / "b", visual="cat")
    with pytest.raises(ValueError, match="a coherence length of 300 nm .* give at least 400 nm"):
        iridis.report(spec, tmp_path / "c" / "d", coherence="300nm")
    assert list(tmp_path.iterdir()) == [], "a refused report left a file or the folders it made"


def test_report_of_a_grey_image_takes_max_height(tmp_path, grey_sine_png):
    """A grey PNG holds relative heights: ``max_height`` is the height of white, so the heights are grey / 255 ×
    100 nm and the rms is numpy's of the grey levels, scaled (as crates/cli/tests/surface_cli.rs)."""
    png, grey = grey_sine_png
    opts = dict(pixel_size="50nm", level="mean", size=16, testbench=False)
    with pytest.raises(ValueError, match="give max_height_nm"):
        iridis.report(png, tmp_path / "refused", **opts)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = iridis.report(png, tmp_path / "rep", max_height="100nm", **opts)
    assert r["info"]["rms_nm"] == pytest.approx(grey.std() * 100 / 255, rel=1e-12)
    assert r["info"]["peaks"][0]["period_nm"] == pytest.approx(800, abs=1)
    assert all("--max-height 100nm" in c["command"] for c in r["commands"])
    # Lengths as numbers of nm, the package's convention (the message named max_height_nm, which the function
    # did not take): the same report.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        n = iridis.report(png, tmp_path / "rep_nm", pixel_size_nm=50, max_height_nm=100, level="mean", size=16,
                          testbench=False)
    assert n["info"]["rms_nm"] == r["info"]["rms_nm"] and n["verdict"] == r["verdict"]
    with pytest.raises(ValueError, match="max_height_nm and max_height give the same length"):
        iridis.report(png, tmp_path / "both", max_height_nm=100, max_height="100nm", **opts)
    # A scan that is not there is an OSError, as surface.load's.
    with pytest.raises(OSError, match="no such file"):
        iridis.report(tmp_path / "nope.gwy", tmp_path / "none")


def test_reshape_and_write_follow_numpy(tmp_path):
    s = surface.generate("sine", size="2um", pixel="100nm", period="500nm", depth="40nm")
    h = s.heights_nm
    tiled = s.reshape(tile="2x3")
    np.testing.assert_array_equal(tiled.heights_nm, np.tile(h, (2, 3)))
    cropped = s.reshape(crop="2,3,5,7")
    np.testing.assert_array_equal(cropped.heights_nm, h[2:7, 3:10])
    path = tmp_path / "s.npy"
    s.write(path)
    back = surface.load(path)
    np.testing.assert_allclose(back.heights_nm, h, rtol=0, atol=1e-12)
    assert back.pixel_nm == pytest.approx(s.pixel_nm)
    with pytest.raises(ValueError, match="crop"):
        s.reshape(crop="1,2")


def test_info_text_and_channels():
    s = surface.generate("sine", size="11um", pixel="100nm", period="1100nm", depth="100nm")
    text = s.info_text()
    assert "samples      110 rows × 110 columns" in text
    period = s.info()["peaks"][0]["period_nm"]
    assert abs(period - 1100.0) < 5.0 and "periods      period (nm)" in text
    c = surface.channels(os.path.join(FIXTURES, "gwyfile_two_channels.gwy"))
    assert len(c["channels"]) == 2 and ": 2 channels" in c["text"].splitlines()[0]
    assert sum(ch["height"] for ch in c["channels"]) == sum("(not a height)" not in l for l in c["text"].splitlines()[2:4])


def test_figures_are_written(tmp_path):
    s = surface.generate("sine", size="4um", pixel="100nm", period="1000nm")
    s.figures("sine", image=tmp_path / "r.png", psdf=tmp_path / "p.png", acf=tmp_path / "a.png")
    for f in ("r.png", "p.png", "a.png"):
        assert (tmp_path / f).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_testbench_with_the_rigorous_method():
    """`testbench(method="rigorous")` is `iridis testbench --method rigorous` (Python refused the method): a
    1000 nm sine's first order gives its period by the grating equation, over the material given; the material
    is refused with another method, as the CLI refuses it."""
    spec = "builtin:sine?size=4um&pixel=50nm&period=1000nm"
    r = lab.testbench(spec, method="rigorous", wavelengths=(500.0, 600.0, 50.0), material="n=1.5")
    assert r["method"] == "rigorous" and r["rigorous"]["material"] == "n=1.5"
    assert r["periodicity_nm"]["mean"] == pytest.approx(1000.0, abs=r["periodicity_nm"]["uncertainty"] + 1.0)
    with pytest.raises(ValueError, match="material and unit_cell auto are the rigorous method's"):
        lab.testbench(spec, method="reference", material="gold", wavelengths=(500.0, 600.0, 50.0))
    with pytest.raises(ValueError, match="unknown method 'fdtd'; expected one of: .*stam-gaussian, rigorous"):
        lab.testbench(spec, method="fdtd")


def test_laser_mirror_reflection_hits_the_screen_centre(tmp_path):
    """A mirror (a sine 0.1 nm deep, flat to the light; the generator refuses depth 0): the law of reflection
    puts the beam's reflection on the screen's centre, the pixel the screen is laid out around."""
    r = lab.laser("builtin:sine?size=4um&pixel=100nm&depth=0.1nm", tmp_path / "screen.png", aperture_nm=4000.0,
                  size=11, subsamples=1, exposures=(1000.0,), coating="none", step_nm=10.0)
    y = np.nan_to_num(r["xyz"][:, :, 1])
    assert np.unravel_index(np.argmax(y), y.shape) == (5, 5)
    assert r["max_y"] == pytest.approx(float(y.max()), rel=1e-12)
    assert r["gold_mirror_relative_brightness"] == pytest.approx(1.0)
    assert (tmp_path / "screen.png").exists()
    # The view samples against the lobes (`sampling`): 300 mm over 11 pixels at 100 mm; σ of the window's |G|² at
    # 380 nm, λ/(2√2 π σ_s) with σ_s a quarter of the coherence length, and 6σ the most the samples may be apart.
    s = r["sampling"]
    assert s["view_spacing_mrad"] == pytest.approx(300.0 / 11 / 100.0 * 1e3, rel=1e-12)
    sigma_mrad = 380.0 / (2.0 * math.sqrt(2.0) * math.pi * s["lobe_coherence_um"] * 1e3 / 4.0) * 1e3
    assert s["lobe_sigma_mrad"] == pytest.approx(sigma_mrad, rel=1e-12)
    assert s["finer_by"] == pytest.approx(s["view_spacing_mrad"] / (6.0 * sigma_mrad), rel=1e-12)


def test_sweep_point_equals_the_comparison_at_that_value(tmp_path):
    """One sweep value is one comparison: the reference method with 5 Taylor terms against its model's ground
    truth, by `lab.sweep` (iridis_lab::sweep) and by `lab.compare` (iridis_lab::compare), agree."""
    spec = "builtin:elaphe?size=3um&pixel=100nm"
    opts = dict(coherence_nm=1500.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sw = lab.sweep(spec, "terms", [5], tmp_path / "sheet.png", size=16, exposures=(1000.0,), **opts)
        c = lab.compare(spec, methods=["reference"], exposures=(1000.0,), size=16, terms=5, **opts)
    mean_sweep = sw["points"][0]["errors"][0]["mean"]
    mean_compare = c["results"][0]["mean"]
    assert mean_sweep == pytest.approx(mean_compare, rel=1e-9, abs=1e-12)
    assert (tmp_path / "sheet.png").exists() and (tmp_path / "sheet_error.png").exists()
    assert sw["param"] == "terms" and [p["value"] for p in sw["points"]] == [5.0]


def test_options_no_method_reads_are_refused(tmp_path):
    """As the CLI: Taylor terms for methods that use none, Stam's ε without a Stam periodic model and the
    coherence of the laser experiment (its window is ``aperture_nm``) raise, naming what would read them."""
    spec = "builtin:sine?size=4um&pixel=100nm"
    with pytest.raises(ValueError, match=r"terms 3 would be ignored: the methods ground-truth, stam-gaussian use"):
        lab.compare(spec, methods=["ground-truth", "stam-gaussian"], size=8, terms=3)
    with pytest.raises(ValueError, match=r"epsilon 0.2 would be ignored: .*stam-gaussian method has none"):
        lab.laser(spec, tmp_path / "s.png", method="stam-gaussian", epsilon=0.2)
    # The former name still reads, with a DeprecationWarning; both names at once are a TypeError.
    with pytest.warns(DeprecationWarning, match=r"stam_epsilon= is now epsilon="):
        with pytest.raises(ValueError, match=r"epsilon 0.2 would be ignored"):
            lab.laser(spec, tmp_path / "s.png", method="stam-gaussian", stam_epsilon=0.2)
    with pytest.raises(TypeError, match=r"both epsilon= and its former name stam_epsilon="):
        lab.laser(spec, tmp_path / "s.png", method="stam-periodic", epsilon=0.2, stam_epsilon=0.2)
    with pytest.raises(ValueError, match=r"coherence_nm 5um would be ignored: .* aperture_nm 5um"):
        lab.laser(spec, tmp_path / "s.png", coherence_nm=5000.0)
    # The CLI's --aperture is aperture_nm here: the error points to it.
    with pytest.raises(TypeError, match=r"laser\(\) got an unexpected keyword argument 'aperture' \(did you mean "
                                        r"aperture_nm\?"):
        lab.laser(spec, tmp_path / "s.png", aperture="5um")
    assert not (tmp_path / "s.png").exists()


def test_demo_writes_the_sections_asked_for_as_the_cli(tmp_path):
    """``iridis.demo`` is ``iridis demo``'s library call: the sections asked for, in the gallery's order, every
    figure named in index.html written as a PNG and returned; an unknown section raises, naming the sections
    (as the CLI's ``--only``), and writes nothing."""
    out = tmp_path / "gallery"
    r = iridis.demo(out, only="thinfilm,color")
    html = (out / "index.html").read_text()
    assert r["index"] == str(out / "index.html")
    names = [s.split('"')[0] for s in html.split('<img src="')[1:]]
    assert sorted(names) == sorted(os.path.basename(p) for p in r["written"])
    assert len(names) >= 4
    for n in names:
        assert (out / n).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", n
    # Colour before thin films, as in the gallery, and no section that was not asked for.
    assert html.index("cie1931_locus.png") < html.index("thinfilm_soap_chart.png")
    assert "brdf_" not in html and "render_" not in html
    assert iridis.scan_report.DEMO_SECTIONS == ("snakes", "color", "surface", "thinfilm", "brdf", "lab", "render")
    with pytest.raises(ValueError, match="no demo section 'colour'; the sections: snakes, color"):
        iridis.demo(tmp_path / "never", only=["colour"])
    assert not (tmp_path / "never").exists()
