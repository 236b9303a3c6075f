"""Diffraction from a measured height field (Dhillon et al. 2014): the paper's lookup tables (precompute,
save, load) and BRDF maps as linear XYZ arrays, from the height field (``reference``: Taylor terms + windowed
DFT per wavelength; ``ground-truth``: the direct windowed Fourier sum) or from a table (``lookup``). The same
library code as ``iridis precompute`` and ``iridis brdf-map``; lengths in nm, angles in radians.

Example:
    >>> import numpy as np, iridis.surface as surface, iridis.diffraction as diffraction
    >>> flat = surface.Surface(np.zeros((16, 16)), 100.0)
    >>> m = diffraction.brdf_map(flat, size=9, method="reference")    # a mirror at normal incidence
    >>> round(float(m[4, 4, 1]), 9), float(np.delete(m[..., 1].ravel(), 40).max()) < 1e-6
    (1.0, True)
"""
from __future__ import annotations

import os

from . import _native
from .surface import Surface

__all__ = ["Table", "precompute", "brdf_map", "brdf_map_of"]


class Table:
    """A lookup table: ``Table.load(path)``, ``table.save(path)``, ``table.meta``."""

    def __init__(self, native):
        if not isinstance(native, _native._Table):
            raise TypeError("make a Table with iridis.diffraction.precompute or Table.load")
        self._t = native

    @classmethod
    def load(cls, path):
        return cls(_native._Table.load(os.fspath(path)))

    def save(self, path):
        self._t.save(os.fspath(path))

    @property
    def meta(self):
        return self._t.meta

    def __repr__(self):
        m = self.meta
        return f"Table({m['surface']!r}, {m['uv_resolution']}² grid, N = {m['taylor_terms']})"


def _surface(s):
    if not isinstance(s, Surface):
        raise TypeError(f"surface must be an iridis.surface.Surface, got {type(s).__name__}")
    return s._h


def precompute(surface, coherence_nm=None, terms=None, uv_resolution=501, uv_power=5.0, illuminant="D65",
               observer="1931", step_nm=5.0):
    """The paper's tables ``I_p(u, v)`` of a height field (``terms=None``: as many Taylor terms as the
    heights need, the CLI's ``--terms auto``; default coherence 65 µm)."""
    return Table(_native.precompute(_surface(surface), coherence_nm, terms, int(uv_resolution), float(uv_power),
                                    illuminant, observer, float(step_nm)))


def brdf_map(source, incidence=(0.0, 0.0), size=256, method=None, coherence_nm=None, terms=None,
             illuminant="D65", observer="1931", step_nm=5.0):
    """A BRDF map as linear XYZ of shape ``(size, size, 3)`` (row 0 at the top; outside the unit disk 0).

    ``source``: a :class:`~iridis.surface.Surface` (``method`` ``"reference"``, the default, or
    ``"ground-truth"``) or a :class:`Table` (``"lookup"``). ``incidence``: ``θ_i`` or ``(θ_i, φ_i)`` in radians.
    A normal-incidence mirror has ``Y = 1`` in its specular pixel.
    """
    try:
        theta, phi = (float(incidence), 0.0) if not hasattr(incidence, "__len__") else map(float, incidence)
    except (TypeError, ValueError):
        raise TypeError(f"incidence must be θ or (θ, φ) in radians, got {incidence!r}") from None
    if isinstance(source, Table):
        native, method = source._t, method or "lookup"
    else:
        native, method = _surface(source), method or "reference"
    return _native.brdf_map_xyz(native, method, theta, phi, int(size), coherence_nm, terms, illuminant, observer,
                                float(step_nm))


def brdf_map_of(spec, incidence=(0.0, 0.0), size=256, method="reference", level=None, **options):
    """:func:`brdf_map` of a SURFACE argument as ``iridis brdf-map`` takes it: a file (plane-levelled unless
    ``level`` says otherwise, as the CLI does) or ``builtin:…`` (used as generated). A plain function of its
    arguments, so it is what batch scripts send to Dask workers."""
    from .surface import load

    how = level if level is not None else ("none" if str(spec).startswith("builtin:") else "plane")
    return brdf_map(load(spec, level=how), incidence=incidence, size=size, method=method, **options)
