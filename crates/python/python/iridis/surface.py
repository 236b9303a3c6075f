"""Height fields: load any file the CLI reads (AFM instrument files, ``.npy``/``.npz``, PNG/TIFF, text
matrices) or a built-in generator, as a NumPy array of heights in nm with the pixel size; level; roughness;
the dominant periods and the rest of ``iridis surface info`` (:meth:`Surface.info`).

Example:
    >>> import iridis.surface as surface
    >>> s = surface.load("builtin:sine?size=11um&pixel=100nm&period=1100nm&depth=100nm")
    >>> s.heights_nm.shape, s.pixel_nm
    ((110, 110), (100.0, 100.0))
    >>> round(s.roughness()["Sq_nm"], 3)          # depth/2 / √2 for a sine of depth 100 nm
    35.355
"""
from __future__ import annotations

import numpy as np

from . import _native

__all__ = ["Surface", "load", "generate"]


class Surface:
    """Heights (nm, shape ``(rows, cols)``, row 0 at the top) on a grid of ``dx_nm × dy_nm`` pixels."""

    def __init__(self, heights_nm, dx_nm, dy_nm=None):
        if isinstance(heights_nm, _native._HeightField):
            self._h = heights_nm
            return
        a = np.asarray(heights_nm)
        if a.dtype.kind not in "biuf":
            raise TypeError(f"heights_nm must hold real numbers, got dtype {a.dtype}")
        if a.ndim != 2:
            raise ValueError(f"heights_nm must be 2-D (rows, cols), got shape {a.shape}")
        dy = dx_nm if dy_nm is None else dy_nm
        self._h = _native._HeightField(np.ascontiguousarray(a, dtype=np.float64), float(dx_nm), float(dy))

    @property
    def heights_nm(self):
        return self._h.heights_nm

    @property
    def pixel_nm(self):
        """``(dx, dy)`` in nm."""
        return (self._h.dx_nm, self._h.dy_nm)

    @property
    def meta(self):
        """Source, format, the unit heights were stored in (``z_unit``), notes and warnings."""
        return self._h.meta

    def level(self, how="plane"):
        """A levelled copy: ``none``, ``mean``, ``plane``, ``rows``, ``lines-median`` or ``poly``."""
        return Surface(self._h.level(how), 0)

    def info(self, peaks=5, coherence_nm=65000.0):
        """What ``iridis surface info --json`` reports, as a dict (keys in docs/json.md): ``rows``, ``cols``,
        ``pixel_size_nm``, heights, ``peaks`` (the dominant periods: ``period_nm``, ``orientation_deg``,
        ``power``, …, at most ``peaks``), ``roughness`` and the radial PSDF / ACF of the plane-levelled
        field (their ``values_*`` as arrays), and the warnings for a coherence window of ``coherence_nm``.

            >>> g = generate("sine", size="11um", pixel="50nm", period="1100nm", depth="100nm")
            >>> round(g.info()["peaks"][0]["period_nm"])
            1100
        """
        if isinstance(peaks, bool) or not isinstance(peaks, (int, np.integer)) or peaks < 0:
            raise TypeError(f"peaks must be a whole number ≥ 0, got {peaks!r}")
        import json

        out = json.loads(self._h.info_json(int(peaks), float(coherence_nm)))
        out["psdf_radial"]["values_nm4"] = np.asarray(out["psdf_radial"]["values_nm4"], dtype=float)
        out["acf_radial"]["values_nm2"] = np.asarray(out["acf_radial"]["values_nm2"], dtype=float)
        return out

    def roughness(self):
        """Sq, Sa, Ssk, excess kurtosis, Sz (nm) and the correlation length, as ``iridis surface info``."""
        return self._h.roughness()

    def __repr__(self):
        r, c = self.heights_nm.shape
        return f"Surface({r}×{c} at {self.pixel_nm[0]:g} × {self.pixel_nm[1]:g} nm from {self.meta['source']!r})"


def load(spec, channel=None, pixel_size_nm=None, max_height_nm=None, height_unit=None, level=None):
    """Loads a SURFACE as the CLI does (a path, or ``builtin:NAME[?size=…&pixel=…&seed=…]``).

    ``channel``: index or name in multi-channel files; ``pixel_size_nm`` and ``max_height_nm`` for images;
    ``height_unit`` where the file has none; ``level``: a levelling to apply (see :meth:`Surface.level`).
    A missing file raises OSError, a file that cannot be read ValueError with the CLI's message.
    """
    h = _native.load_height_field(str(spec), None if channel is None else str(channel), pixel_size_nm,
                                  max_height_nm, height_unit)
    s = Surface(h, 0)
    return s if level is None else s.level(level)


def generate(kind, **params):
    """A built-in surface: ``generate("elaphe", size="16um", pixel="50nm", seed=3)`` (parameters as in
    ``iridis surface generate --help``, lengths with units)."""
    query = "&".join(f"{k.replace('_', '-')}={v}" for k, v in params.items())
    return load(f"builtin:{kind}" + (f"?{query}" if query else ""))
