"""Colours as animals see them: the receptor-noise-limited model of Vorobyev & Osorio (1998) on NumPy arrays —
the same library call and options as ``iridis vision`` (docs/vision.md), so the numbers are the CLI's.

Spectra are rows of ``values`` on ``wavelengths_nm`` (reflectances as fractions). ``analyse`` returns the dict of
``iridis vision --json``: ``visual``, ``receptors``, ``samples`` (each ``quantum_catches``,
``absolute_catches``, ``relative_catches``, ``achromatic_catch``, ``coordinates``), ``distances`` (``a``, ``b``,
``delta_s``, ``delta_l`` in JND) and the conditions (``illuminant``, ``background``, ``noise``, ``notes``).

Example:
    >>> import numpy as np, iridis.vision as vision
    >>> wl = np.arange(300.0, 701.0)
    >>> grey = np.full_like(wl, 0.3)
    >>> a = vision.analyse(wl, [grey, 0.5 * grey], visual="bluetit", names=["grey", "darker"])
    >>> d = a["distances"][0]
    >>> round(d["delta_s"], 12), round(d["delta_l"], 4)        # same colour, ln 2 / 0.1 brighter
    (0.0, 6.9315)
"""
from __future__ import annotations

import json
import warnings

import numpy as np

from . import _native
from ._answer import flag, renamed

__all__ = ["VISUAL_SYSTEMS", "ILLUMINANTS", "analyse", "sensitivities", "vision"]

_systems, _lights = _native._vision_names()
VISUAL_SYSTEMS = dict(_systems)
ILLUMINANTS = dict(_lights)


def _float_array(x, name):
    a = np.asarray(x)
    if a.dtype.kind not in "biuf":
        raise TypeError(f"{name} must hold real numbers, got dtype {a.dtype}")
    return a.astype(np.float64, copy=False)


def _text(x, sep=","):
    if x is None or isinstance(x, str):
        return x
    return sep.join(str(float(v)) for v in np.ravel(x))


def _spec(visual, lambda_max, chromophore, oil_droplets, ocular_media, illuminant, illuminant_units,
          illuminant_scale, background, weber, weber_ref, densities, receptor_noise, noise, achromatic,
          weber_achromatic, space):
    """The analysis options in the words of the CLI (``iridis_vision::Spec``), for ``analyse`` and ``vision``."""
    number = (lambda x: None if x is None else float(x))
    return dict(
        visual=visual, lambda_max=_text(lambda_max), chromophore=chromophore, oil_droplets=oil_droplets,
        ocular_media=ocular_media, illuminant=illuminant, illuminant_units=illuminant_units,
        illuminant_scale=number(illuminant_scale), background=background, weber=number(weber),
        weber_ref=None if weber_ref is None else str(weber_ref), densities=_text(densities, ":"),
        receptor_noise=_text(receptor_noise), noise=noise, achromatic=achromatic,
        weber_achromatic=number(weber_achromatic), space=space)


def analyse(wavelengths_nm, values, visual=None, names=None, *, lambda_max=None, chromophore=None,
            oil_droplets=None, ocular_media=None, illuminant=None, illuminant_units=None, illuminant_scale=None,
            background=None, weber=None, weber_ref=None, densities=None, receptor_noise=None, noise=None,
            achromatic=None, weber_achromatic=None, space=None, achromatic_weber=None):
    """How the spectra look to an animal: catches, coordinates and every pair's ΔS and ΔL in JND.

    ``values``: one spectrum per row (a 1-D array is one spectrum). ``visual``: a built-in system
    (``VISUAL_SYSTEMS``) or a CSV of sensitivities; or ``lambda_max`` (e.g. ``[344, 436, 556]``) with
    ``chromophore`` ("a1"/"a2") and ``oil_droplets`` ("T,C:413,Y:507,R:572"). ``illuminant``: one of
    ``ILLUMINANTS`` or a CSV; ``background``: "grey", "grey:0.2", "none" or a CSV; ``densities``: "1:2:2:4" or a
    sequence; ``receptor_noise``: noise per receptor; ``noise``: "neural" or "quantum"; ``space``: "auto",
    "line", "triangle", "tetrahedron", "hexagon" or "none"; ``weber_achromatic``: the achromatic channel's Weber
    fraction (the CLI's ``--weber-achromatic``, default 0.1; ``achromatic_weber`` is its former name). Unset
    options are the system's or the CLI's defaults.
    """
    weber_achromatic = renamed("analyse", "achromatic_weber", achromatic_weber, "weber_achromatic",
                               weber_achromatic)
    wl = _float_array(wavelengths_nm, "wavelengths_nm")
    if wl.ndim != 1:
        raise ValueError(f"wavelengths_nm must be 1-D, got shape {wl.shape}")
    v = _float_array(values, "values")
    if v.ndim == 1:
        v = v[None, :]
    if v.ndim != 2 or v.shape[1] != wl.size:
        raise ValueError(f"values of shape {v.shape}: need one row of {wl.size} values per spectrum")
    if names is None:
        names = [f"sample{i + 1}" for i in range(v.shape[0])]
    names = [str(n) for n in names]
    out = _native._analyse(np.ascontiguousarray(wl), np.ascontiguousarray(v), names, **_spec(
        visual, lambda_max, chromophore, oil_droplets, ocular_media, illuminant, illuminant_units, illuminant_scale,
        background, weber, weber_ref, densities, receptor_noise, noise, achromatic, weber_achromatic, space))
    return json.loads(out)


def sensitivities(wavelengths_nm, visual=None, *, lambda_max=None, chromophore=None, oil_droplets=None):
    """Each receptor's sensitivity (unit sum over 300-700 nm at 1 nm, times the ocular media) at the
    wavelengths: ``(names, array of shape (receptors, wavelengths))``."""
    from .thinfilm import _wavelengths  # finite, > 0, and not µm or metres by mistake

    wl = _wavelengths(wavelengths_nm)
    if wl.ndim != 1:
        raise ValueError(f"wavelengths_nm must be 1-D, got shape {wl.shape}")
    outside = wl[(wl < 300) | (wl > 700)]
    if outside.size:
        warnings.warn(f"{outside.size} of the wavelengths lie outside the 300–700 nm the receptors are defined on "
                      f"(e.g. {outside[0]:g} nm): their sensitivity is 0 there", UserWarning, stacklevel=2)
    return _native._sensitivities(np.ascontiguousarray(wl), visual=visual, lambda_max=_text(lambda_max),
                                  chromophore=chromophore, oil_droplets=oil_droplets)


def vision(spectra, visual=None, *, percent=False, lambda_max=None, chromophore=None, oil_droplets=None,
           ocular_media=None, illuminant="d65", illuminant_units=None, illuminant_scale=1.0, background="grey",
           weber=None, weber_ref=None, densities=None, receptor_noise=None, noise="neural", achromatic=None,
           weber_achromatic=None, space="auto", achromatic_weber=None):
    """``iridis vision``: the spectra CSV ``spectra`` (pavo's layout: a wavelength column and one column per
    sample; ``percent`` divides by 100) as an animal sees it, with the CLI's defaults — the dict of ``--json``
    and ``.text`` the CLI's text. The options are :func:`analyse`'s."""
    from ._answer import answer, file_path

    weber_achromatic = renamed("vision", "achromatic_weber", achromatic_weber, "weber_achromatic",
                               weber_achromatic)
    path = file_path(spectra, "iridis.vision.vision", "iridis.vision.analyse(wavelengths_nm, values, visual)")
    return answer(_native._vision_file(path, flag(percent, "percent"), **_spec(
        visual, lambda_max, chromophore, oil_droplets, ocular_media, illuminant, illuminant_units, illuminant_scale,
        background, weber, weber_ref, densities, receptor_noise, noise, achromatic, weber_achromatic, space)))
