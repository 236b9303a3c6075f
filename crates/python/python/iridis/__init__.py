"""iridis: structural colour, computed — thin films, colour science and diffraction, NumPy-native.

Modules:
    iridis.tmm       a drop-in for Byrnes' ``tmm`` (coh_tmm, unpolarized_RT, ellips, inc_tmm) plus coh_tmm_batch
    iridis.thinfilm  stacks from the CLI's syntax or lists; R, T, A broadcast over λ × θ × thickness offset; colours
    iridis.surface   height fields from AFM files, numpy, images or generators; levelling; roughness
    iridis.diffraction  lookup tables (precompute, save, load) and BRDF maps as XYZ arrays
    iridis.render    a scene (TOML or glTF) to an RGB or XYZ array on the CPU
    iridis.color     spectrum → XYZ / xyY / Lab / sRGB under any illuminant and observer; ΔE
    iridis.bench     ``python -m iridis.bench``: iridis.tmm against tmm (and tmm_fast) in the same run

Example:
    >>> import iridis.thinfilm as tf
    >>> film = tf.Stack("air | water 348nm | air")
    >>> round(float(film.reflectance(550.0, 0.0)), 4)
    0.0556
"""
from ._native import __version__

__all__ = ["__version__", "color", "diffraction", "render", "surface", "thinfilm", "tmm"]
