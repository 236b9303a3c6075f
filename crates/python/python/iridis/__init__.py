"""iridis: structural colour, computed — thin films, colour science and diffraction, NumPy-native.

Modules:
    iridis.tmm       a drop-in for Byrnes' ``tmm`` (coh_tmm, unpolarized_RT, ellips, inc_tmm) plus coh_tmm_batch
    iridis.thinfilm  stacks from the CLI's syntax or lists; R, T, A broadcast over λ × θ × thickness offset; colours;
                     rough films (LSRS: specular and diffuse spectra and colours)
    iridis.film      the ``iridis thinfilm`` commands (spectrum, table, color, chart, materials, bench, profile, fit)
    iridis.surface   height fields from AFM files, numpy, images or generators; levelling; roughness
    iridis.diffraction  lookup tables (precompute, save, load), BRDF maps as XYZ arrays, point queries (every method)
    iridis.lab       the test bench (periodicity through the grating equation) and method comparisons in CIELAB
    iridis.render    a scene (TOML or glTF) to an RGB or XYZ array on the CPU or the GPU
    iridis.color     spectrum → XYZ / xyY / Lab / sRGB under any illuminant and observer; ΔE
    iridis.vision    colours as animals see them: quantum catches, colour spaces, ΔS and ΔL in JND (birds, bees, …)
    iridis.bench     ``python -m iridis.bench``: iridis.tmm against tmm (and tmm_fast) in the same run
    iridis.report    the report of a scan (``iridis report``): index.html, report.json and the figures
    iridis.demo      the gallery on built-in data (``iridis demo``): index.html and its figures

Example:
    >>> import iridis.thinfilm as tf
    >>> film = tf.Stack("air | water 348nm | air")
    >>> round(float(film.reflectance(550.0, 0.0)), 4)
    0.0556
"""
from ._native import __version__
from .scan_report import demo, report

__all__ = ["__version__", "demo", "report", "color", "diffraction", "film", "lab", "render", "surface", "thinfilm", "tmm", "vision"]
