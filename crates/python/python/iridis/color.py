"""Colour science on arrays: spectrum → XYZ / xyY / CIELAB / sRGB under any built-in illuminant and observer,
and colour differences (CIEDE2000, ΔE*ab). The same library code as ``iridis color xyz`` and
``iridis color delta-e``: XYZ is relative (``Y = 1`` for a perfect reflector), spectra are interpolated onto
the observer's 1 nm grid.

Colours are arrays whose last axis has length 3; any leading shape is kept.

Example:
    >>> import numpy as np, iridis.color as color
    >>> wl = np.arange(380.0, 781.0, 5.0)
    >>> xyz = color.spectrum_to_xyz(wl, np.ones_like(wl))   # a perfect white under D65
    >>> np.round(color.xyz_to_lab(xyz), 6).tolist()
    [100.0, 0.0, 0.0]
    >>> round(float(color.delta_e([50, 2.6772, -79.7751], [50, 0, -82.7485])), 4)   # Sharma et al. 2005, pair 1
    2.0425
"""
from __future__ import annotations

import numpy as np

from . import _native
from ._answer import flag, renamed

__all__ = [
    "ILLUMINANTS",
    "OBSERVERS",
    "spectrum_to_xyz",
    "white_point",
    "xyz_to_xyy",
    "xyz_to_lab",
    "lab_to_xyz",
    "xyz_to_linear_srgb",
    "xyz_to_srgb",
    "xyz_to_hex",
    "delta_e",
    "xyz",
]

ILLUMINANTS, OBSERVERS = (tuple(x) for x in _native.names())


def _float_array(x, name):
    a = np.asarray(x)
    if a.dtype.kind not in "biuf":
        raise TypeError(f"{name} must hold real numbers, got dtype {a.dtype}")
    return a.astype(np.float64, copy=False)


def _colours(x, name, displayed=False):
    a = _float_array(x, name)
    if a.ndim == 0 or a.shape[-1] != 3:
        raise ValueError(f"{name} must have a last axis of length 3 (one colour per row), got shape {a.shape}")
    rows = a.reshape(-1, 3)
    # A displayed colour (sRGB, hex) of NaN came out black without a word; the linear conversions keep NaN as
    # NaN (numpy's way, for masked images).
    bad = np.flatnonzero(~np.isfinite(rows).all(axis=1)) if displayed else ()
    if len(bad):
        raise ValueError(f"{name} holds a value that is not finite in colour {bad[0]}: {rows[bad[0]].tolist()}; "
                         "a displayed colour has none for it")
    return np.ascontiguousarray(rows), a.shape


def white_point(illuminant="D65", observer="1931"):
    """XYZ of a perfect reflector (``Y = 1``) under ``illuminant`` for ``observer``."""
    return np.array(_native.white_point_xyz(str(illuminant), str(observer)))


def spectrum_to_xyz(wavelengths_nm, values, illuminant="D65", observer="1931"):
    """XYZ of reflectance (or transmittance) spectra: ``values[..., k]`` at ``wavelengths_nm[k]``.

    Returns shape ``values.shape[:-1] + (3,)``. ``illuminant``: one of ``ILLUMINANTS``; ``observer``:
    ``"1931"`` (2°) or ``"1964"`` (10°).
    """
    wl = _float_array(wavelengths_nm, "wavelengths_nm")
    if wl.ndim != 1:
        raise ValueError(f"wavelengths_nm must be 1-D, got shape {wl.shape}")
    if wl.size < 2:
        raise ValueError(f"wavelengths_nm holds {wl.size} value(s): a spectrum needs at least two samples")
    v = _float_array(values, "values")
    if v.ndim == 0 or v.shape[-1] != wl.size:
        raise ValueError(f"values of shape {v.shape}: the last axis must match the {wl.size} wavelengths")
    # observer=1964 as an int, as delta_e takes formula=2000.
    out = _native._spectrum_to_xyz(np.ascontiguousarray(wl), np.ascontiguousarray(v.reshape(-1, wl.size)),
                                   str(illuminant), str(observer))
    return out.reshape(v.shape[:-1] + (3,))


def _white(white, illuminant, observer):
    if white is None:
        return tuple(_native.white_point_xyz(str(illuminant), str(observer)))
    w = _float_array(white, "white")
    if w.shape != (3,):
        raise ValueError(f"white must be one XYZ triple, got shape {w.shape}")
    if not (np.isfinite(w).all() and (w > 0).all()):
        raise ValueError(f"white = {w.tolist()}: a white point's X, Y and Z must be positive and finite")
    return tuple(float(x) for x in w)


def xyz_to_lab(xyz, white=None, illuminant="D65", observer="1931"):
    """CIELAB relative to ``white`` (default: the white point of ``illuminant`` and ``observer``)."""
    a, shape = _colours(xyz, "xyz")
    return _native._xyz_to_lab(a, _white(white, illuminant, observer)).reshape(shape)


def lab_to_xyz(lab, white=None, illuminant="D65", observer="1931"):
    """The inverse of :func:`xyz_to_lab`."""
    a, shape = _colours(lab, "lab")
    return _native._lab_to_xyz(a, _white(white, illuminant, observer)).reshape(shape)


def xyz_to_xyy(xyz):
    """Chromaticity x, y and luminance Y."""
    a, shape = _colours(xyz, "xyz")
    return _native._xyz_to_xyy(a).reshape(shape)


def xyz_to_linear_srgb(xyz):
    """Linear sRGB (IEC 61966-2-1, D65), not clipped."""
    a, shape = _colours(xyz, "xyz")
    return _native._xyz_to_linear_srgb(a).reshape(shape)


def _exposure(exposure):
    # A zero, negative or NaN exposure would make every colour black without a word.
    e = float(exposure)
    if not (np.isfinite(e) and e > 0):
        raise ValueError(f"exposure = {exposure}: must be a positive finite number (XYZ is multiplied by it)")
    return e


def xyz_to_srgb(xyz, exposure=1.0):
    """Display sRGB in [0, 1]: scaled by ``exposure``, clipped, encoded (the CLI's ``srgb``). XYZ that is not
    finite is a ValueError (it would show as black)."""
    a, shape = _colours(xyz, "xyz", displayed=True)
    return _native._xyz_to_srgb(a, _exposure(exposure)).reshape(shape)


def xyz_to_hex(xyz, exposure=1.0):
    """``#rrggbb`` strings (the CLI's ``hex``); a list for several colours, a str for one. XYZ that is not finite
    is a ValueError (it would show as black)."""
    a, shape = _colours(xyz, "xyz", displayed=True)
    out = _native._xyz_to_hex(a, _exposure(exposure))
    return out[0] if len(shape) == 1 else np.array(out).reshape(shape[:-1]).tolist()


def delta_e(lab1, lab2, formula=None, *, method=None):
    """Colour difference between Lab colours (broadcast): CIEDE2000 (``"2000"``, the default) or ΔE*ab
    (``"1976"``), the CLI's ``--formula``. Two texts ``"L,a,b"`` are read as ``iridis color delta-e`` reads them
    (its messages and formula names). ``method=`` is the former name of ``formula=`` (a DeprecationWarning)."""
    formula = renamed("delta_e", "method", method, "formula", formula) or "2000"
    if isinstance(lab1, str) and isinstance(lab2, str):
        return _native._color_delta_e(lab1, lab2, str(formula))
    a = _float_array(lab1, "lab1")
    b = _float_array(lab2, "lab2")
    try:
        a, b = np.broadcast_arrays(a, b)
    except ValueError:
        raise ValueError(f"lab1 of shape {a.shape} and lab2 of shape {b.shape} do not broadcast") from None
    pa, shape = _colours(a, "lab1")
    pb, _ = _colours(b, "lab2")
    out = np.array(_native._delta_e(pa, pb, str(formula)))
    return out.reshape(shape[:-1]) if len(shape) > 1 else out[0]


def xyz(spectrum, illuminant="D65", observer="1931", emissive=False, percent=False):
    """``iridis color xyz``: the colour of the spectrum in a file (two columns, wavelength in nm and value) as
    the CLI reports it — a dict with XYZ, xyY, Lab, linear_srgb, srgb and hex, and ``.text`` the CLI's text.
    A reflectance lit by ``illuminant`` (Y = 1 a perfect white reflector), or with ``emissive`` a light source
    at Y = 1; L*a*b* is relative to the illuminant's white either way (for a light, the white it is judged
    against). ``percent=True``: the reflectance is in percent (``--percent``); values above 1.5 read as fractions
    give a warning. A file that does not cover 380–780 nm gives a warning."""
    from ._answer import answer, file_path

    path = file_path(spectrum, "iridis.color.xyz", "iridis.color.spectrum_to_xyz(wavelengths_nm, values)")
    return answer(_native._color_xyz(path, str(illuminant), str(observer), flag(emissive, "emissive"),
                                     flag(percent, "percent")))
