"""iridis.render: an example scene into arrays, consistent between colour spaces, deterministic."""
import contextlib
import os
import tempfile

import numpy as np
import pytest

import iridis.color as color
import iridis.render as render
from conftest import ROOT

SCENE = os.path.join(ROOT, "examples", "gold_sphere.toml")


@contextlib.contextmanager
def scene_shader_turn():
    """The GPU tests' turn at the scene shader, a file lock next to Mesa's cache that the CLI's GPU tests take too
    (crates/cli/tests/gpu_cli.rs, `scene_shader_turn`, which says why): tools/test.sh runs them beside these, and
    on lavapipe the shader's first compilation takes about a minute of one core, done again by every process that
    starts it before another has finished. Where files cannot be locked, no turn is taken."""
    folder = os.environ.get("MESA_SHADER_CACHE_DIR") or tempfile.gettempdir()
    try:
        import fcntl  # Unix only

        lock = open(os.path.join(folder, "iridis-scene-shader.lock"), "a")
    except (ImportError, OSError):
        yield
        return
    with lock:
        try:
            fcntl.flock(lock, fcntl.LOCK_EX)
        except OSError:
            pass
        yield


def test_example_scene_renders_into_arrays():
    lin = render.render(SCENE, size=(24, 16), spp=1, space="linear_srgb")
    assert lin.shape == (16, 24, 3) and np.isfinite(lin).all() and lin.max() > 0
    xyz = render.render(SCENE, size=(24, 16), spp=1, space="xyz")
    np.testing.assert_allclose(color.xyz_to_linear_srgb(xyz), lin, atol=1e-9)
    srgb = render.render(SCENE, size=(24, 16), spp=1)
    assert srgb.min() >= 0.0 and srgb.max() <= 1.0
    np.testing.assert_array_equal(render.render(SCENE, size=(24, 16), spp=1, space="linear_srgb"), lin)


def test_render_takes_the_clis_exposure_and_gltf_options():
    """render is `iridis render`'s library call: `exposure` (RU) scales the display values as xyz_to_srgb does,
    and the glTF options reach the loader (a TOML scene refuses them, a glTF without cameras names the camera)."""
    xyz = render.render(SCENE, size=(24, 16), spp=1, space="xyz")
    np.testing.assert_allclose(render.render(SCENE, size=(24, 16), spp=1, exposure=7.0),
                               color.xyz_to_srgb(xyz, exposure=7.0), atol=1e-12)
    with pytest.raises(ValueError, match="a TOML scene has its"):
        render.render(SCENE, size=(8, 8), spp=1, camera="front")
    gltf = os.path.join(ROOT, "examples", "iridescent_spheres.gltf")
    with pytest.raises(ValueError, match="camera front: the file has no camera"):
        render.render(gltf, size=(8, 8), spp=1, camera="front")
    assert render.render(gltf, size=(8, 8), spp=1, ignore_gltf_lights=True).shape == (8, 8, 3)


def test_bad_input():
    with pytest.raises(OSError):
        render.render("/no/such/scene.toml")
    with pytest.raises(ValueError, match="space"):
        render.render(SCENE, space="cmyk")
    with pytest.raises(ValueError, match="spp"):
        render.render(SCENE, size=(4, 4), spp=0)
    with pytest.raises(TypeError, match="size"):
        render.render(SCENE, size=5)


def test_gpu_render_matches_the_cpu():
    """render(gpu=True) is `iridis render --gpu` (the facade's GPU path): the CPU reference's image within
    ΔE00 mean 1, p99 3 (the bound crates/cli/tests/gpu_cli.rs uses), on lavapipe where there is no GPU."""
    scene = os.path.join(ROOT, "examples", "soap_bubble.toml")
    try:
        with scene_shader_turn():
            gpu = render.render(scene, size=(64, 48), spp=2, gpu=True)
    except ValueError as e:
        if "no GPU adapter" in str(e) and os.environ.get("IRIDIS_SKIP_GPU") == "1":
            pytest.skip(f"IRIDIS_SKIP_GPU=1: {e}")
        raise
    cpu = render.render(scene, size=(64, 48), spp=2)
    assert gpu.shape == cpu.shape == (48, 64, 3)
    # The displayed images (after the scene's exposure, as the PNGs the CLI's test compares) back to XYZ.
    to_xyz = np.linalg.inv(color.xyz_to_linear_srgb(np.eye(3)).T)
    lab = []
    for srgb in (cpu, gpu):
        linear = np.where(srgb <= 0.04045, srgb / 12.92, ((srgb + 0.055) / 1.055) ** 2.4)
        lab.append(color.xyz_to_lab(linear @ to_xyz.T))
    d = np.sort(color.delta_e(lab[0], lab[1]).ravel())
    mean, p99 = d.mean(), d[d.size * 99 // 100]
    assert mean < 1.0 and p99 < 3.0, (mean, p99)
    assert (lab[0][..., 0] > 10).sum() > 300  # the image shows something


def test_gpu_run_without_xdg_runtime_dir_prints_no_driver_noise():
    """As the CLI's gpu_cli test: a process started without XDG_RUNTIME_DIR (a service, sudo, env -i) gets a
    private one when it opens the GPU, so the driver prints nothing about it. Any GPU call opens it: a small
    lookup map (a compute and a render pipeline of a few lines) rather than a scene, whose shader lavapipe takes
    seconds to load and which the other GPU tests take turns at."""
    import subprocess
    import sys

    env = {k: v for k, v in os.environ.items() if k != "XDG_RUNTIME_DIR"}
    code = ("import iridis.diffraction as d; "
            "m = d.brdf_map('builtin:sine?size=2um&pixel=100nm', size=8, method='lookup', gpu=True, "
            "uv_resolution=31); print(m.shape)")
    p = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300)
    if p.returncode != 0 and "no GPU adapter" in p.stderr and os.environ.get("IRIDIS_SKIP_GPU") == "1":
        pytest.skip("IRIDIS_SKIP_GPU=1 and no adapter")
    assert p.returncode == 0, p.stderr
    assert "(8, 8, 3)" in p.stdout
    assert "XDG_RUNTIME_DIR" not in p.stderr, p.stderr


def test_export_mesh_writes_the_scenes_triangles_as_glb(tmp_path):
    """export_mesh is `iridis render --export-mesh`: a binary glTF (magic, version 2, its stated length the
    file's) whose index accessors count three indices a triangle, as many triangles as the line says."""
    import json
    import re
    import struct

    glb = tmp_path / "snake.glb"
    line = render.export_mesh(os.path.join(ROOT, "examples", "snake_xenopeltis.toml"), glb)
    data = glb.read_bytes()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    assert (magic, version, length) == (b"glTF", 2, len(data))
    chunk_len, chunk_type = struct.unpack_from("<I4s", data, 12)
    assert chunk_type == b"JSON"
    doc = json.loads(data[20:20 + chunk_len])
    indices = sum(doc["accessors"][p["indices"]]["count"] for m in doc["meshes"] for p in m["primitives"])
    triangles = int(re.search(r"(\d+) triangles", line).group(1))
    assert indices == 3 * triangles and triangles > 1000, line
