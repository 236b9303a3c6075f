"""The library benches (`python -m iridis.bench NAME`, `iridis.bench.run`) and the rest of `iridis brdf-map` /
`iridis brdf eval` in Python: the same facade functions as the CLI (crates/api), so the CLI's --json and files
(fixtures written by tests/fixtures/make_cli_fixtures.sh from `iridis`) come out again, and the documented laws
between the quantities hold."""
import json
import math
import os

import numpy as np
import pytest

import iridis.bench as bench
import iridis.diffraction as diffraction

FIXTURES = os.path.join(os.path.dirname(__file__), "fixtures")
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
SINE = "builtin:sine?size=4um"


def cli(name):
    with open(os.path.join(FIXTURES, name + ".json")) as f:
        return json.load(f)


def close(a, b, rtol=1e-12, atol=1e-15):
    np.testing.assert_allclose(np.asarray(a, dtype=float), np.asarray(b, dtype=float), rtol=rtol, atol=atol)


# --- benches ------------------------------------------------------------------------------------------------

def test_accuracy_bench_reads_a_grey_image_with_its_max_height(tmp_path, grey_sine_png):
    """The accuracy bench reads a scan as every function does: the grey PNG at 100 nm for white gives the
    numbers of the same heights saved by numpy as .npy (as crates/cli/tests/surface_cli.rs)."""
    png, grey = grey_sine_png
    npy = tmp_path / "grey.npy"
    np.save(npy, np.tile(grey / 255 * 100.0, (64, 1)))
    small = dict(level="mean", map_size=8, uv_resolution=31, pixel_size_nm=50.0)
    a = bench.run("diffraction-accuracy", surfaces=[str(png)], max_height_nm=100.0, **small)
    b = bench.run("diffraction-accuracy", surfaces=[str(npy)], height_unit="nm", **small)
    strip = lambda rows: [{k: v for k, v in r.items() if k != "surface"} for r in rows]  # noqa: E731
    assert len(a["results"]) == 15 and strip(a["results"]) == strip(b["results"])


def test_accuracy_bench_equals_the_cli(capsys):
    """`iridis bench diffraction-accuracy` measures no time: Python's run gives the CLI's --json exactly."""
    ref = cli("bench_accuracy_sine")
    ref.pop("inputs")  # the CLI's command line, which every --json answer carries
    got = bench.run("diffraction-accuracy", surfaces=[SINE], map_size=8, uv_resolution=31, exposures=[1.0, 1000.0])
    assert got == ref
    # The same through `python -m iridis.bench NAME --json`, printed as the CLI prints it.
    bench.main(["diffraction-accuracy", "--surface", SINE, "--map-size", "8", "--uv-resolution", "31",
                "--exposures", "1,1000", "--json"])
    assert json.loads(capsys.readouterr().out) == ref
    # The convergence curve ends at N terms: the reference row at 1000 RU is its last point.
    (curve,) = got["convergence"]
    row = next(r for r in got["results"] if r["method"] == "reference" and r["exposure_ru"] == 1000.0)
    assert curve["terms_vs_mean_delta_e"][-1][1] == row["mean"]
    for r in got["results"]:  # CIEDE2000 between displayed colours lies in [0, ~100]
        assert 0.0 <= r["mean"] <= 100.0 and 0.0 <= r["p95"] <= 100.0


def test_render_bench_counts_the_scene():
    """`bench render` on one scene: the CLI's keys; the scene's triangles are the glTF export's count."""
    scene = os.path.join(ROOT, "examples", "gold_sphere.toml")
    text, out = bench.report("render", size=8, scenes=[scene])
    assert set(out) == {"size", "spp", "threads", "scenes"} and (out["size"], out["spp"]) == (8, 1)
    (row,) = out["scenes"]
    assert row["scene"] == "gold_sphere.toml" and set(row) == {"scene", "load_s", "render_s", "triangles"}
    assert text.splitlines()[0] == f"render benchmark: 8×8, 1 spp, {out['threads']} threads"
    assert f"{row['triangles']} triangles" in text.splitlines()[1]


def test_bench_bad_input():
    with pytest.raises(ValueError, match="no bench 'fft'"):
        bench.run("fft")
    with pytest.raises(ValueError, match="map_size 2 must be between 4 and 256"):
        bench.run("diffraction-methods", patch_sizes=[64], map_size=2)
    with pytest.raises(TypeError, match="unexpected keyword argument 'map'"):
        bench.run("diffraction-methods", map=2)
    with pytest.raises(ValueError, match="python and peer_seconds would be ignored: no_python"):
        bench.run("grating", quick=True, no_python=True, peer_seconds=3.0)
    # A scene is timed alone (refused before a GPU is opened): the shaders' options would change nothing.
    with pytest.raises(ValueError, match="gt_size would be ignored: with a SCENE"):
        bench.run("gpu", scene=os.path.join(ROOT, "examples", "gold_sphere.toml"), gt_size=8)


# --- brdf eval ----------------------------------------------------------------------------------------------

def test_brdf_eval_equals_the_cli_json():
    """`diffraction.brdf_eval` is `iridis brdf eval --json`: every key and number."""
    ref = cli("brdf_eval_reference")
    got = diffraction.brdf_eval("builtin:sine", light=math.radians(30), view=(math.radians(10), math.pi))
    # The fixture predates the keys vision, rigorous and scalar_error; the CLI's "inputs" echo its command line.
    assert set(ref) - {"inputs"} <= set(got) and {"vision", "rigorous", "scalar_error"} <= set(got)
    for k in ("input", "method", "fresnel", "fresnel_convention", "shadowing", "illuminant", "observer"):
        assert got[k] == ref[k]
    for k in ("fresnel_r0", "coherence_nm", "window_effective_area_um2", "wavelength_nm", "reflectance", "xyz"):
        close(got[k], ref[k], rtol=1e-10, atol=1e-14)
    b = got["brdf_per_sr"]
    for k in ("s", "p", "unpolarized"):
        close(b[k], ref["brdf_per_sr"][k], rtol=1e-10, atol=1e-14)
    # Unpolarised light is the mean of s and p; ρ = f_r cos θ_i λ² / (A_eff R₀) (the help's definition).
    close(b["unpolarized"], (np.asarray(b["s"]) + np.asarray(b["p"])) / 2, rtol=1e-12)
    area = got["window_effective_area_um2"] * 1e6
    lam = np.asarray(got["wavelength_nm"])
    rho = np.asarray(b["unpolarized"]) * math.cos(math.radians(30)) * lam**2 / (area * got["fresnel_r0"])
    close(rho, got["reflectance"], rtol=1e-9, atol=1e-14)


def test_a_finished_table_refuses_what_only_shapes_a_build(tmp_path):
    """As `iridis brdf-map` and `brdf eval` (crates/cli/tests/brdf_cli.rs): with a TABLE, a u-v grid or an image's
    pixel size would be ignored, so it is refused, naming it."""
    path = tmp_path / "sine.npz"
    diffraction.precompute(SINE, uv_resolution=11).save(path)
    for key, value, flag in (("uv_resolution", 101, "uv_resolution 101"), ("uv_power", 1.0, "uv_power 1"),
                             ("pixel_size_nm", 50.0, "pixel_size_nm 50nm")):
        with pytest.raises(ValueError, match=f"finished lookup table, so {flag} would be ignored"):
            diffraction.brdf_eval(str(path), light=0.3, view=0.2, **{key: value})
        with pytest.raises(ValueError, match=f"finished lookup table, so {flag} would be ignored"):
            diffraction.brdf_map_run(str(path), size=8, **{key: value})
    assert diffraction.brdf_eval(str(path), light=0.3, view=0.2)["method"] == "lookup"


def test_the_rigorous_method_refuses_the_scalar_models_shading():
    """As the CLI (crates/cli/tests/brdf_cli.rs): its lobes carry Maxwell's efficiencies over the material, so a
    Fresnel factor, the paper's R² and leaving out the shadowing term would change nothing."""
    cell = "builtin:sine?size=1100nm&pixel=10nm"
    for key, value, said in (("fresnel", "index:2.5", "not a Fresnel factor"),
                             ("fresnel_convention", "paper", "the rigorous method has none"),
                             ("shadowing", False, "shadowing=False would be ignored")):
        with pytest.raises(ValueError, match=said):
            diffraction.brdf_eval(cell, light=0.3, view=0.0, method="rigorous", **{key: value})
        with pytest.raises(ValueError, match=said):
            diffraction.brdf_map_run(cell, size=8, method="rigorous", **{key: value})


# --- brdf-map -----------------------------------------------------------------------------------------------

def test_brdf_map_run_and_per_sr_equal_the_cli_files():
    """`brdf-map --raw` and `--brdf` (fixtures from the CLI) come out of `brdf_map_run` and of
    `brdf_map(per_sr=True)`: one library path."""
    raw = np.load(os.path.join(FIXTURES, "brdf_map_sine_raw.npy"))
    fr = np.load(os.path.join(FIXTURES, "brdf_map_sine_fr.npy"))
    out = diffraction.brdf_map_run(SINE, incidence=math.radians(20), size=8, method="reference", per_sr=True,
                                   coherence_nm=2000.0)
    assert out["method"] == "reference" and out["exposure_ru"] == 1500.0 and out["coherence_nm"] == 2000.0
    close(out["xyz"], raw, rtol=1e-12, atol=1e-300)
    close(out["per_sr"], fr, rtol=1e-12, atol=1e-300)
    per_sr = diffraction.brdf_map(SINE, incidence=math.radians(20), size=8, method="reference", per_sr=True,
                                  coherence_nm=2000.0)
    close(per_sr, fr, rtol=1e-9, atol=1e-300)
    # No light leaves below the horizon: the pixels outside the unit disk are black in both quantities.
    x = (np.arange(8) * 2 + 1) / 8 - 1
    outside = (x[None, :] ** 2 + x[:, None] ** 2) > 1
    assert not raw[outside].any() and not fr[outside].any()


def test_auto_exposure_makes_the_99th_percentile_white():
    out = diffraction.brdf_map_run(SINE, size=16, method="reference", auto_exposure=True, coherence_nm=2000.0)
    from iridis.color import xyz_to_linear_srgb

    peak = xyz_to_linear_srgb(out["xyz"]).max(axis=-1)
    lit = np.sort(peak[peak > 0])
    assert out["exposure_ru"] == pytest.approx(1.0 / lit[round((lit.size - 1) * 0.99)], rel=1e-12)


def test_brdf_map_run_bad_input():
    with pytest.raises(ValueError, match="size 4 must be between 8 and 8192"):
        diffraction.brdf_map_run(SINE, size=4)
    with pytest.raises(ValueError, match="table_precision chooses how the GPU stores"):
        diffraction.brdf_map_run(SINE, size=8, table_precision="f32")
    with pytest.raises(TypeError, match="SURFACE or TABLE argument"):
        diffraction.brdf_map_run(42)


def test_gpu_options_of_precompute_and_compare():
    """`precompute(gpu=True)` and `lab.compare(gpu=True)` are `--gpu` (Python had neither): the GPU's f32 table
    is the CPU's to single precision, and the comparison's CIEDE2000 the same to 1e-4 of its value."""
    from iridis import lab

    spec = "builtin:sine?size=4um&pixel=50nm"
    try:
        gpu = diffraction.precompute(spec, coherence_nm=4000.0, uv_resolution=31, gpu=True)
    except ValueError as e:
        if "driver" in str(e) or "adapter" in str(e):
            pytest.skip(f"no Vulkan adapter: {e}")
        raise
    cpu = diffraction.precompute(spec, coherence_nm=4000.0, uv_resolution=31)
    a = diffraction.brdf_map(gpu, size=16)
    b = diffraction.brdf_map(cpu, size=16)
    assert float(np.nanmax(np.abs(a - b))) <= 1e-5 * float(np.nanmax(b))
    kw = dict(methods=["lookup"], coherence_nm=4000.0, size=16, uv_resolution=31, exposures=(1000.0,))
    on_gpu, on_cpu = lab.compare(spec, gpu=True, **kw), lab.compare(spec, **kw)
    m_gpu, m_cpu = on_gpu["results"][0]["mean"], on_cpu["results"][0]["mean"]
    assert m_cpu > 1.0 and abs(m_gpu - m_cpu) <= 1e-4 * m_cpu, (m_gpu, m_cpu)


def test_gpu_lookup_map_matches_the_cpu():
    """`brdf_map(gpu=True)` is `brdf-map --gpu` (lavapipe without a GPU): the lookup map's displayed colours at
    1500 RU within 1 % of the CPU's f64 lookup on the same table (the shader sums Chebyshev coefficients in f32;
    docs/gpu.md measures CIEDE2000 ≤ 0.001)."""
    from iridis.color import xyz_to_srgb

    spec = "builtin:elaphe?size=6um"
    try:
        gpu = diffraction.brdf_map(spec, size=16, method="lookup", gpu=True, uv_resolution=31)
    except ValueError as e:
        if "driver" in str(e) or "adapter" in str(e):
            pytest.skip(f"no Vulkan adapter: {e}")
        raise
    cpu = diffraction.brdf_map_run(spec, size=16, method="lookup", uv_resolution=31)["xyz"]
    assert gpu.shape == cpu.shape == (16, 16, 3) and cpu.max() > 0
    assert float(np.max(np.abs(xyz_to_srgb(gpu, exposure=1500) - xyz_to_srgb(cpu, exposure=1500)))) < 0.01
    # subsamples=2: the GPU's 16² map averaged over 2 × 2 blocks against the CPU's 2² view samples a pixel.
    gpu = diffraction.brdf_map(spec, size=8, method="lookup", gpu=True, uv_resolution=31, subsamples=2)
    cpu = diffraction.brdf_map_run(spec, size=8, method="lookup", uv_resolution=31, subsamples=2)["xyz"]
    assert gpu.shape == cpu.shape == (8, 8, 3) and cpu.max() > 0
    assert float(np.max(np.abs(xyz_to_srgb(gpu, exposure=1500) - xyz_to_srgb(cpu, exposure=1500)))) < 0.01
