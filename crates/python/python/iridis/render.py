"""Scenes (TOML or glTF, as ``iridis render`` reads them) rendered into NumPy arrays: linear sRGB, CIE XYZ, or
display sRGB with the scene's exposure. Diffraction and thin-film materials, lights, environments: everything
the CPU renderer does (docs/render.md); with ``gpu=True`` the same scene on the GPU (``iridis render --gpu``:
wgpu through Vulkan, Mesa's lavapipe on a machine without a GPU), whose colours match the CPU's (docs/gpu.md).

Example:
    >>> import iridis.render as render
    >>> img = render.render("examples/gold_sphere.toml", size=(32, 24), spp=1)   # doctest: +SKIP
    >>> img.shape                                                                # doctest: +SKIP
    (24, 32, 3)
"""
from __future__ import annotations

import os

import numpy as np

from . import _native
from ._answer import count, flag
from ._gpu import ensure_gpu_environment
from .color import xyz_to_srgb

__all__ = ["render", "export_mesh"]

# XYZ from linear sRGB (IEC 61966-2-1, D65): the inverse of the matrix iridis-color uses.
_SRGB_TO_XYZ = None


def render(scene, size=None, spp=None, space="srgb", gpu=False, exposure=None, spectral_samples=None, camera=None,
           ignore_gltf_lights=False):
    """Renders ``scene`` (a path) as ``iridis render`` does (the same library call). ``size``: ``(width,
    height)``, default the scene's; ``spp``: samples per pixel, default the scene's. ``space``: ``"srgb"``
    (display values in [0, 1] after the exposure, as the PNG ``iridis render`` writes), ``"linear_srgb"`` or
    ``"xyz"`` (linear, before exposure). ``exposure`` (RU, ``--exposure``): default the scene's. ``gpu``: render
    on the GPU (a ValueError naming the driver to install when there is no adapter; rough films render on the
    CPU only), ``spectral_samples`` its direct film evaluation (``--spectral-samples``). A glTF scene's
    ``camera`` by name (``--camera``) and ``ignore_gltf_lights`` (``--ignore-gltf-lights``). Returns an array of
    shape ``(height, width, 3)``."""
    if space not in ("srgb", "linear_srgb", "xyz"):
        raise ValueError(f"space {space!r}: use 'srgb', 'linear_srgb' or 'xyz'")
    w = h = None
    if size is not None:
        try:
            w, h = size
        except (TypeError, ValueError):
            raise TypeError(f"size must be (width, height), got {size!r}") from None
        w, h = count(w, "size's width"), count(h, "size's height")
    gpu = flag(gpu, "gpu")
    if gpu:
        ensure_gpu_environment()
    out = _native.render_scene(os.fspath(scene), w, h, None if spp is None else count(spp, "spp"), gpu,
                               None if exposure is None else float(exposure),
                               None if spectral_samples is None else count(spectral_samples, "spectral_samples"),
                               camera,
                               flag(ignore_gltf_lights, "ignore_gltf_lights"))
    rgb = out["linear_srgb"].astype(np.float64)
    if space == "linear_srgb":
        return rgb
    xyz = _to_xyz(rgb)
    if space == "xyz":
        return xyz
    return xyz_to_srgb(xyz, exposure=out["exposure"])


def export_mesh(scene, path, camera=None, ignore_gltf_lights=False):
    """Writes ``scene``'s triangle meshes (positions, normals, UVs, the orientation field as TANGENT), camera and
    lights as binary glTF (.glb) to ``path``, as ``iridis render SCENE --export-mesh PATH``; a glTF scene's
    ``camera`` and ``ignore_gltf_lights`` as for :func:`render`. Returns the line that says what was written."""
    return _native.export_mesh(os.fspath(scene), os.fspath(path), camera,
                               flag(ignore_gltf_lights, "ignore_gltf_lights"))


def _to_xyz(rgb):
    global _SRGB_TO_XYZ
    if _SRGB_TO_XYZ is None:
        from .color import xyz_to_linear_srgb

        _SRGB_TO_XYZ = np.linalg.inv(xyz_to_linear_srgb(np.eye(3)).T)
    return rgb @ _SRGB_TO_XYZ.T
