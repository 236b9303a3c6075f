"""iridis.surface against numpy (files numpy wrote, read by numpy itself) and closed forms."""
import os
import shutil

import numpy as np
import pytest

import iridis.surface as surface
from conftest import ROOT

FIX = os.path.join(ROOT, "crates", "surface", "tests", "fixtures")


def test_npy_written_by_numpy_reads_exactly():
    # numpy_f64.npy has a sidecar (numpy_f64.npy.json): 100 × 80 nm pixels, heights in nm.
    s = surface.load(os.path.join(FIX, "numpy_f64.npy"))
    np.testing.assert_array_equal(s.heights_nm, np.load(os.path.join(FIX, "numpy_f64.npy")))
    assert s.pixel_nm == (100.0, 80.0)


def test_npz_channels_and_units(tmp_path):
    z = np.random.default_rng(3).normal(size=(12, 9))
    path = tmp_path / "scan.npz"
    np.savez(path, height=z, phase=z * 0.0 + 1.0)
    s = surface.load(str(path), channel="height", pixel_size_nm=20.0, height_unit="um")
    np.testing.assert_allclose(s.heights_nm, z * 1000.0, rtol=1e-15)
    assert s.pixel_nm == (20.0, 20.0)
    with pytest.raises(ValueError, match="channel"):
        surface.load(str(path), channel="nope", pixel_size_nm=20.0, height_unit="nm")
    assert s.meta["channel"] is None  # an .npz array is chosen by name, not as an instrument's channel


def test_meta_says_which_channel_was_read_as_the_cli_does():
    """Surface.meta["channel"] is `iridis surface info --json`'s `channel` (the same ChannelChoice): of a
    two-channel Gwyddion file, the default reads the first one named Height and says why."""
    gwy = os.path.join(FIX, "gwyfile_two_channels.gwy")
    c = surface.load(gwy).meta["channel"]
    assert (c["index"], c["name"], c["of"]) == (0, "Height", 2)
    assert c["heights"] == ["0: Height", "1: Height (um)"]
    assert c["reason"].startswith("the default: the channel named Height")
    assert surface.load(gwy, channel=1).meta["channel"]["reason"] == "as asked (--channel 1)"


def test_roughness_equals_numpy_formulas():
    z = np.random.default_rng(5).gamma(2.0, 10.0, size=(64, 48))
    r = surface.Surface(z, 10.0).roughness()
    c = z - z.mean()
    sq = np.sqrt(np.mean(c**2))
    assert abs(r["sq_nm"] - sq) < 1e-12 * sq
    assert abs(r["sa_nm"] - np.mean(np.abs(c))) < 1e-12 * sq
    assert abs(r["skewness"] - np.mean(c**3) / sq**3) < 1e-12
    assert abs(r["excess_kurtosis"] - (np.mean(c**4) / sq**4 - 3.0)) < 1e-11
    assert r["sz_nm"] == z.max() - z.min()


def test_builtin_sine_has_the_closed_form_rms():
    s = surface.generate("sine", size="11um", pixel="100nm", period="1100nm", depth="100nm")
    assert s.heights_nm.shape == (110, 110)
    assert abs(s.roughness()["sq_nm"] - 50.0 / np.sqrt(2.0)) < 1e-9


def test_plane_levelling_removes_a_tilt():
    y, x = np.mgrid[0:40, 0:30].astype(float)
    bumps = np.sin(x / 3.0) * np.cos(y / 5.0)
    tilted = surface.Surface(bumps + 0.7 * x - 0.2 * y + 5.0, 10.0)
    flat = tilted.level("plane").heights_nm
    # the least-squares plane of the bumps alone is what remains of them after levelling the tilted field
    a = np.c_[x.ravel(), y.ravel(), np.ones(x.size)]
    coef, *_ = np.linalg.lstsq(a, bumps.ravel(), rcond=None)
    np.testing.assert_allclose(flat, bumps - (a @ coef).reshape(bumps.shape), atol=1e-9)


def test_bad_input():
    with pytest.raises(OSError, match="cannot load surface"):
        surface.load("/no/such/file.gwy")
    with pytest.raises(ValueError):
        surface.load("builtin:nothing")
    with pytest.raises(ValueError, match="2-D"):
        surface.Surface(np.zeros(5), 1.0)
    with pytest.raises(TypeError, match="real numbers"):
        surface.Surface(np.array([["a", "b"], ["c", "d"]]), 1.0)
    with pytest.raises(ValueError):
        surface.Surface(np.zeros((4, 4)), -1.0)
    with pytest.raises(ValueError, match="level"):
        surface.Surface(np.zeros((4, 4)), 1.0).level("sideways")
    # Options the SURFACE has no use for: refused as the CLI refuses them, not ignored.
    with pytest.raises(ValueError, match=r"channel, as_height would be ignored: .*builtin:sine"):
        surface.load("builtin:sine?size=1um&pixel=100nm", channel=1, as_height=True)
    npy = os.path.join(ROOT, "crates", "surface", "tests", "fixtures", "numpy_f32_fortran.npy")
    with pytest.raises(ValueError, match=r"max_height_nm would be ignored: .*npy format"):
        surface.load(npy, pixel_size_nm=10.0, max_height_nm=5.0)
    with pytest.raises(ValueError, match=r"as_height would be ignored: .*npy format"):
        surface.load(npy, pixel_size_nm=10.0, as_height=True)
    sxm = os.path.join(FIX, "nanonis_synthetic.sxm")
    with pytest.raises(ValueError, match="override_units would be ignored: .*none is given"):
        surface.load(sxm, override_units=True)
    with pytest.raises(ValueError, match="as_height would be ignored: channel 0 'Z_forward' is a height already"):
        surface.load(sxm, as_height=True)
    # A seed for a structure with no randomness would change nothing.
    with pytest.raises(ValueError, match="seed 3 would be ignored: sine has no randomness"):
        surface.generate("sine", size="2um", pixel="50nm", seed=3)


def test_an_instrument_files_own_units_win_unless_overridden():
    """As `iridis surface info` (crates/cli/tests/surface_cli.rs, the same file): a pixel size or height unit that
    contradicts the file's is not applied silently; override_units applies it; as_height reads a current."""
    sxm = os.path.join(FIX, "nanonis_synthetic.sxm")
    plain = surface.load(sxm)
    kept = surface.load(sxm, pixel_size_nm=50.0, height_unit="um")
    assert kept.pixel_nm == plain.pixel_nm == pytest.approx((10.0, 10.0), rel=1e-12)
    np.testing.assert_array_equal(kept.heights_nm, plain.heights_nm)
    said = " ".join(kept.meta["warnings"])
    assert "pixel_size_nm 50 nm ignored: the file gives 10.00 × 10.00 nm per pixel" in said
    assert "height_unit um ignored: the file gives this channel's heights in m" in said
    over = surface.load(sxm, pixel_size_nm=50.0, height_unit="um", override_units=True)
    assert over.pixel_nm == (50.0, 50.0)
    # Stored in m, read as µm: a millionth of the heights.
    np.testing.assert_allclose(over.heights_nm, plain.heights_nm * 1e-6, rtol=1e-12)
    with pytest.raises(ValueError, match="as_height"):
        surface.load(sxm, channel="Current")
    with pytest.raises(ValueError, match="give height_unit"):
        surface.load(sxm, channel="Current", as_height=True)
    current = surface.load(sxm, channel="Current", as_height=True, height_unit="nm")
    assert "as_height" in " ".join(current.meta["warnings"])
    # The option dicts of the library calls take them too: the GPU bench reads its surfaces before it opens a GPU.
    import iridis.bench as bench

    with pytest.raises(ValueError, match="as_height"):
        bench.run("gpu", build_surface=sxm, channel="Current")
    with pytest.raises(ValueError, match="give height_unit"):
        bench.run("gpu", build_surface=sxm, channel="Current", as_height=True)


def test_info_finds_the_generated_period_and_equals_the_cli():
    """Surface.info is `iridis surface info --json` (the facade's function; fixture from
    tests/fixtures/make_cli_fixtures.sh), and finds the period and direction the sine was generated with."""
    import json

    spec = "builtin:sine?period=1500nm&angle=30deg&size=20um&pixel=20nm"
    info = surface.load(spec).info()
    with open(os.path.join(os.path.dirname(__file__), "fixtures", "surface_info.json")) as f:
        cli = json.load(f)
    assert [(p["period_nm"], p["orientation_deg"], p["power"]) for p in info["peaks"]] == [
        (p["period_nm"], p["orientation_deg"], p["power"]) for p in cli["peaks"]
    ]
    assert info["roughness"] == cli["roughness"]
    # Surface.roughness() has the same keys and, of the plane-levelled field, the same numbers.
    assert {**surface.load(spec).level("plane").roughness(), "levelling": "plane"} == cli["roughness"]
    np.testing.assert_array_equal(info["psdf_radial"]["values_nm4"], cli["psdf_radial"]["values_nm4"])
    top = info["peaks"][0]
    assert abs(top["period_nm"] - 1500.0) < 0.01  # the generator's period (measured 1500.0000008 nm)
    assert abs(top["orientation_deg"] - 30.0) < 1e-4  # its grating vector's direction
    assert top["power"] > 0.9  # a pure sine: (almost) all of the variance in one peak


def test_info_bad_input():
    s = surface.generate("sine", size="2um", pixel="50nm")
    with pytest.raises(ValueError, match="coherence_nm"):
        s.info(coherence_nm=-1.0)
    with pytest.raises(TypeError, match="peaks"):
        s.info(peaks="3")


def test_generate_makes_every_kind_the_cli_makes():
    """generate is `iridis surface generate`'s library call: the same field as the built-in of those parameters,
    and the kinds without a built-in name (rect-bumps, tri-bumps, refused before) too — Stam's boxes are binary,
    every height 0 or the depth."""
    a = surface.generate("elaphe", size="4um", pixel="50nm", seed=3).heights_nm
    np.testing.assert_array_equal(a, surface.load("builtin:elaphe?size=4um&pixel=50nm&seed=3").heights_nm)
    boxes = surface.generate("rect-bumps", size="4um", pixel="50nm", depth="100nm").heights_nm
    assert set(np.unique(boxes)) == {0.0, 100.0}
    assert surface.generate("tri-bumps", size="2um", pixel="50nm").heights_nm.shape == (40, 40)
    with pytest.raises(ValueError, match="unknown kind 'nope'"):
        surface.generate("nope")
