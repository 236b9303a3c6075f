"""iridis.diffraction: physical laws (a mirror's specular pixel, the grating equation), lookup against
reference, tables round-tripping through files, bad input."""
import warnings

import numpy as np
import pytest

import iridis.diffraction as diffraction
import iridis.surface as surface


def test_flat_mirror_reflects_only_specularly_with_y_one():
    flat = surface.Surface(np.zeros((16, 16)), 100.0)
    # The paper's 65 µm coherence: a window wider than the patch keeps the flat patch's spectrum one spike (the
    # CLI's default fits the coherence to half a small patch, which widens the spike into its neighbours).
    m = diffraction.brdf_map(flat, size=9, coherence_nm=65000.0)
    assert abs(m[4, 4, 1] - 1.0) < 1e-12  # a normal-incidence mirror has Y = 1 (paper eq. 9, PHYSICS.md)
    np.testing.assert_allclose(m[4, 4] / m[4, 4, 1], [0.9504707, 1.0, 1.0888284], atol=2e-4)  # D65 white
    rest = np.delete(m[..., 1].ravel(), 40)
    assert rest.max() < 1e-6


def sine():
    return surface.generate("sine", size="6.6um", pixel="100nm", period="1100nm", depth="100nm")


def test_sine_grating_orders_obey_the_grating_equation():
    size = 101
    # The paper's 65 µm coherence over whole periods of the patch: the orders are single pixels (the CLI's
    # default, half the 6.6 µm patch, widens them).
    m = diffraction.brdf_map(sine(), size=size, coherence_nm=65000.0)
    x = -1 + (2 * np.arange(size) + 1) / size
    row = m[size // 2, :, 1]  # y = 0: the grating's ridges run along y, its orders lie on this row
    first = (np.abs(x) > 380 / 1100 + 0.02) & (np.abs(x) < 780 / 1100 - 0.02)
    between = (np.abs(x) > 0.08) & (np.abs(x) < 380 / 1100 - 0.04)
    assert row[between].max() < 1e-3 * row[first].max()
    # ± orders are symmetric at normal incidence
    np.testing.assert_allclose(row, row[::-1], rtol=1e-6, atol=1e-9 * row.max())


def test_a_map_too_coarse_for_its_lobes_says_so():
    # 65 µm coherence: a lobe's σ in (u, v) is 380/(2√2π·16250) = 0.0026 at 380 nm; pixels 2/size apart miss
    # lobes past 6σ, i.e. below 127² (the same check as `iridis brdf-map`).
    # Sampled 6σ apart a lobe shows; its light sums to its integral only within 1.5σ.
    with pytest.warns(UserWarning, match=r"subsamples 4 \(each pixel the mean of directions across it\) shows "
                                         r"every lobe; to measure their light .* within 1.5σ: subsamples 16"):
        diffraction.brdf_map(sine(), size=33, method="reference", coherence_nm=65000.0)
    maps = {}
    for size, subsamples in ((132, 1), (33, 4)):
        with warnings.catch_warnings(record=True) as said:
            warnings.simplefilter("always")
            maps[size] = diffraction.brdf_map(sine(), size=size, method="reference", coherence_nm=65000.0,
                                              subsamples=subsamples)
        assert not [w for w in said if "apart in view direction" in str(w.message)], [str(w.message) for w in said]
    # Four samples a pixel side are the 132² map's pixel centres: the 33² map is that map averaged over 4 × 4.
    blocks = maps[132].reshape(33, 4, 33, 4, 3).mean(axis=(1, 3))
    np.testing.assert_allclose(maps[33], blocks, rtol=0, atol=1e-12 * maps[132].max())


def test_lookup_agrees_with_reference_and_tables_round_trip(tmp_path):
    g = sine()
    table = diffraction.precompute(g, uv_resolution=301)
    assert table.meta["uv_resolution"] == 301 and table.meta["taylor_terms"] >= 5
    a = diffraction.brdf_map(table, incidence=(0.3, 0.0), size=33)
    b = diffraction.brdf_map(g, incidence=(0.3, 0.0), size=33)
    assert a.shape == (33, 33, 3)
    # The tables interpolate I_p on a 301² non-linear grid: the map's light agrees within 1 % in total and
    # 5 % pixel by pixel (measured 0.2 % and 4.0 %; docs/diffraction.md gives the ΔE of the same trade-off).
    assert abs(a[..., 1].sum() / b[..., 1].sum() - 1.0) < 0.01
    assert np.abs(a - b).sum() / b.sum() < 0.05
    path = tmp_path / "sine.npz"
    table.save(path)
    loaded = diffraction.Table.load(path)
    c = diffraction.brdf_map(loaded, incidence=(0.3, 0.0), size=33)
    np.testing.assert_array_equal(a, c)
    # The metadata is the file's, whole: what the colours measure and the model behind them among it.
    assert loaded.meta == table.meta
    assert (table.meta["units"], table.meta["wavelength_min_nm"], table.meta["wavelength_max_nm"]) == (
        "relative", 380.0, 780.0)
    # method="lookup" on a height field builds the same tables first, as `iridis brdf-map --method lookup` does.
    d = diffraction.brdf_map(g, method="lookup", incidence=(0.3, 0.0), size=33, uv_resolution=301)
    np.testing.assert_allclose(d, a, rtol=1e-12, atol=0)


def test_bad_input():
    g = surface.Surface(np.zeros((8, 8)), 50.0)
    with pytest.raises(ValueError, match="unknown method"):
        diffraction.brdf_map(g, method="magic", size=5)
    with pytest.raises(ValueError, match="incidence"):
        diffraction.brdf_map(g, incidence=2.0, size=5)
    with pytest.raises(ValueError, match="size"):
        diffraction.brdf_map(g, size=0)
    with pytest.raises(TypeError, match="Surface"):
        diffraction.brdf_map(np.zeros((8, 8)), size=5)
    with pytest.raises(OSError):
        diffraction.Table.load("/no/such/table.npz")
    # A u-v grid builds a table only for the lookup method from a height field; anywhere else it would be
    # ignored, so it raises as the CLI refuses it (and out of range, before any work).
    with pytest.raises(ValueError, match="uv_resolution 101 would be ignored: the reference method builds no"):
        diffraction.brdf_map(g, method="reference", size=8, uv_resolution=101)
    with pytest.raises(ValueError, match="uv_power 2 would be ignored"):
        diffraction.evaluate("builtin:sine?size=4um&pixel=100nm", (0.0, 0.0), (0.3, 0.0), uv_power=2.0)
    t = diffraction.precompute(g, uv_resolution=21)
    with pytest.raises(ValueError, match="this Table is a finished lookup table, so uv_resolution 31 would be"):
        diffraction.brdf_map(t, size=8, uv_resolution=31)
    with pytest.raises(ValueError, match="u-v resolution 2 must be between 3 and 4001"):
        diffraction.precompute(g, uv_resolution=2)
    # precompute is `iridis precompute`'s library call: its --units and --gpu are here, and what it has not (a
    # Fresnel model, energy-conserving lobes) is refused instead of ignored (the table came out the same).
    assert diffraction.precompute(g, uv_resolution=21, units="radiometric").meta["units"] == "radiometric"
    assert t.meta["units"] == "relative"
    with pytest.raises(TypeError, match="unexpected keyword argument 'fresnel'"):
        diffraction.precompute(g, uv_resolution=21, fresnel="gold")
    with pytest.raises(ValueError, match="conserve_energy would be ignored"):
        diffraction.precompute(g, uv_resolution=21, conserve_energy=True)
    with pytest.raises(ValueError, match="units 'watts'"):
        diffraction.precompute(g, uv_resolution=21, units="watts")
