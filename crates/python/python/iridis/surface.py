"""Height fields: load any file the CLI reads (AFM instrument files, ``.npy``/``.npz``, PNG/TIFF, text
matrices) or a built-in generator, as a NumPy array of heights in nm with the pixel size; level; roughness;
the dominant periods and the rest of ``iridis surface info`` (:meth:`Surface.info`).

Example:
    >>> import iridis.surface as surface
    >>> s = surface.load("builtin:sine?size=11um&pixel=100nm&period=1100nm&depth=100nm")
    >>> s.heights_nm.shape, s.pixel_nm
    ((110, 110), (100.0, 100.0))
    >>> round(s.roughness()["sq_nm"], 3)          # depth/2 / √2 for a sine of depth 100 nm
    35.355
"""
from __future__ import annotations

import json
import os

import numpy as np

from . import _native
from ._answer import count, flag, warn_caller

__all__ = ["Surface", "load", "generate", "channels"]


class Surface:
    """Heights (nm, shape ``(rows, cols)``, row 0 at the top) on a grid of ``dx_nm × dy_nm`` pixels."""

    def __init__(self, heights_nm, dx_nm, dy_nm=None):
        # The reader's warnings already given as Python warnings (by load), not given again by info().
        self._said = ()
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
        """Source, format, the unit heights were stored in (``z_unit``), notes, warnings, and ``channel``: which
        channel of a multi-channel file was read and why (``None`` for single-image formats and built-ins)."""
        return self._h.meta

    def level(self, how="plane"):
        """A levelled copy: ``none``, ``mean``, ``plane``, ``poly`` (degree 2), ``lines`` (median line correction)
        or ``rows`` (line means), as ``--level``."""
        return self._derived(self._h.level(how))

    def _derived(self, h):
        out = Surface(h, 0)
        out._said = self._said
        return out

    def info(self, peaks=5, coherence_nm=65000.0):
        """What ``iridis surface info --json`` reports, as a dict (keys in docs/json.md): ``rows``, ``cols``,
        ``pixel_size_nm``, heights, ``peaks`` (the dominant periods: ``period_nm``, ``orientation_deg``,
        ``power``, …, at most ``peaks``), ``roughness`` and the radial PSDF / ACF of the plane-levelled
        field (their ``values_*`` as arrays), and the warnings for a coherence window of ``coherence_nm`` (also
        given as Python warnings, as the CLI says them on stderr).

            >>> g = generate("sine", size="11um", pixel="50nm", period="1100nm", depth="100nm")
            >>> round(g.info()["peaks"][0]["period_nm"])
            1100
        """
        out = json.loads(self._info_json(peaks, coherence_nm))
        out["psdf_radial"]["values_nm4"] = np.asarray(out["psdf_radial"]["values_nm4"], dtype=float)
        out["acf_radial"]["values_nm2"] = np.asarray(out["acf_radial"]["values_nm2"], dtype=float)
        return out

    def info_text(self, peaks=5, coherence_nm=65000.0):
        """The table ``iridis surface info`` prints for this field; its warnings, which the CLI says on stderr,
        as Python warnings (and in ``info()["warnings"]``)."""
        return self._h.info_text_of(self._info_json(peaks, coherence_nm))

    def _info_json(self, peaks, coherence_nm):
        """``surface info --json``'s text, computed once, its warnings given as Python warnings (the CLI says
        them on stderr)."""
        text = self._h.info_json(count(peaks, "peaks"), float(coherence_nm))
        for w in json.loads(text)["warnings"]:
            if w not in self._said:
                warn_caller(w)
        return text

    def figures(self, name="surface", image=None, psdf=None, acf=None):
        """Writes ``iridis surface info``'s figures as PNG: ``image`` the shaded relief with axes and a scale
        bar, ``psdf`` the 2-D power spectral density (log scale) and ``acf`` the 2-D autocorrelation of the
        plane-levelled field; ``name`` goes into the titles."""
        path = lambda p: None if p is None else os.fspath(p)  # noqa: E731
        self._h.figures(str(name), path(image), path(psdf), path(acf))

    def write(self, path):
        """Writes the field as ``iridis surface convert`` does, in the format the extension names (.gwy, .gsf,
        .npy, .npz, .png, .txt; a JSON sidecar with the units where the format has none)."""
        self._h.write(os.fspath(path))

    def reshape(self, crop=None, resample_nm=None, tile=None, pad=None):
        """``iridis surface convert``'s steps, in this order: ``crop`` ``"ROW,COL,ROWS,COLS"``, ``resample_nm``
        (new pixel size, the extent kept), ``tile`` ``"NYxNX"``, ``pad`` ``"ROWSxCOLS"`` (with the mean height)."""
        return self._derived(self._h.reshape(crop, None if resample_nm is None else float(resample_nm), tile, pad))

    def roughness(self):
        """Sq, Sa, skewness, excess kurtosis, Sz and the correlation length of the field as it is (level it first),
        under the keys of ``iridis surface info --json``'s ``roughness``: ``sq_nm``, ``sa_nm``, ``skewness``,
        ``excess_kurtosis``, ``sz_nm``, ``correlation_length_nm`` (``None`` when the autocorrelation never falls
        to 1/e within half the patch)."""
        return self._h.roughness()

    def __repr__(self):
        r, c = self.heights_nm.shape
        return f"Surface({r}×{c} at {self.pixel_nm[0]:g} × {self.pixel_nm[1]:g} nm from {self.meta['source']!r})"


def load(spec, channel=None, pixel_size_nm=None, max_height_nm=None, height_unit=None, level=None,
         override_units=False, as_height=False):
    """Loads a SURFACE as the CLI does (a path, or ``builtin:NAME[?size=…&pixel=…&seed=…]``).

    ``channel``: index or name in multi-channel files; ``pixel_size_nm`` and ``max_height_nm`` for images;
    ``height_unit`` where the file has none; ``level``: a levelling to apply (see :meth:`Surface.level`).
    Where an instrument file states its own pixel size or height unit, the file's win and a warning names both,
    unless ``override_units`` (the CLI's ``--override-units``); a channel that is not a height (an amplitude, a
    current) is refused unless ``as_height`` (``--as-height``). What the reader warns about (units assumed or
    ignored, NaN lines filled, a relief below a picometre) is given as Python warnings here, as the CLI says it
    on reading, and kept in ``meta["warnings"]``.
    A missing file raises OSError, a file that cannot be read ValueError with the CLI's message.
    """
    h = _native.load_height_field(str(spec), None if channel is None else str(channel), pixel_size_nm,
                                  max_height_nm, height_unit, flag(override_units, "override_units"),
                                  flag(as_height, "as_height"))
    s = Surface(h, 0)
    s._said = tuple(s.meta["warnings"])
    for w in s._said:
        warn_caller(w)
    return s if level is None else s.level(level)


def generate(kind, **params):
    """A built-in nanostructure as ``iridis surface generate`` makes it (the same library call, every kind:
    sine, blazed, cd, elaphe, xenopeltis, gaussian, rect-bumps, tri-bumps): ``generate("elaphe", size="16um",
    pixel="50nm", seed=3)`` (parameters as in ``iridis surface generate --help``, lengths with units)."""
    pairs = [(k.replace("_", "-"), str(v)) for k, v in params.items()]
    return Surface(_native.generate_height_field(str(kind), pairs), 0)


def channels(path):
    """The channels (images) an instrument file holds, as ``iridis surface channels --json``: a dict with
    ``file``, ``format`` and ``channels`` (``index``, ``name``, ``direction``, size, unit, ``height``);
    ``result["text"]`` is the table the command prints."""
    import json

    out, text = _native.surface_channels(os.fspath(path))
    result = json.loads(out)
    result["text"] = text
    return result
