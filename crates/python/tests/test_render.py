"""iridis.render: an example scene into arrays, consistent between colour spaces, deterministic."""
import os

import numpy as np
import pytest

import iridis.color as color
import iridis.render as render
from conftest import ROOT

SCENE = os.path.join(ROOT, "examples", "gold_sphere.toml")


def test_example_scene_renders_into_arrays():
    lin = render.render(SCENE, size=(24, 16), spp=1, space="linear_srgb")
    assert lin.shape == (16, 24, 3) and np.isfinite(lin).all() and lin.max() > 0
    xyz = render.render(SCENE, size=(24, 16), spp=1, space="xyz")
    np.testing.assert_allclose(color.xyz_to_linear_srgb(xyz), lin, atol=1e-9)
    srgb = render.render(SCENE, size=(24, 16), spp=1)
    assert srgb.min() >= 0.0 and srgb.max() <= 1.0
    np.testing.assert_array_equal(render.render(SCENE, size=(24, 16), spp=1, space="linear_srgb"), lin)


def test_bad_input():
    with pytest.raises(OSError):
        render.render("/no/such/scene.toml")
    with pytest.raises(ValueError, match="space"):
        render.render(SCENE, space="cmyk")
    with pytest.raises(ValueError, match="spp"):
        render.render(SCENE, size=(4, 4), spp=0)
    with pytest.raises(TypeError, match="size"):
        render.render(SCENE, size=5)
