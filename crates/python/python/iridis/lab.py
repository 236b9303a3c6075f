"""The virtual lab (docs/lab.md): the test bench of the paper's sec. 6.1 (peak viewing angles and the
periodicity of a surface through the grating equation), the comparison of methods in CIELAB (sec. 6.3,
Table 2), convergence sweeps (sec. 7) and the laser experiment (Figure 8). The same library functions as
``iridis testbench``, ``iridis compare``, ``iridis sweep`` and ``iridis experiment laser`` (the facade
``iridis-api``, ``iridis_api::lab_run``); the results are the dicts those commands print with ``--json`` (keys in docs/json.md), plus
the arrays behind them.

``surface`` is an :class:`iridis.surface.Surface` or a SURFACE argument as the CLI takes it. Keyword
``options``: ``coherence_nm``, ``terms``, ``fresnel``, ``fresnel_convention``, ``shadowing``, ``epsilon``
(Stam's ε, the CLI's ``--epsilon``; ``stam_epsilon`` is its former name) and, for SURFACE arguments, ``pixel_size_nm``, ``max_height_nm``, ``channel``, ``height_unit``, ``level``,
``override_units``, ``as_height`` (the CLI's ``--override-units``, ``--as-height``). An option no method of
the call reads raises ValueError, as the CLI refuses it: ``terms`` for the ground truths and Stam's models,
``epsilon`` without a Stam periodic model, ``coherence_nm`` in ``laser`` (its window is ``aperture_nm``).
Angles in radians, lengths in nm.

Example:
    >>> import numpy as np, iridis.lab as lab
    >>> r = lab.testbench("builtin:blazed?size=20um&pixel=50nm", wavelengths=(500, 700, 50),
    ...                   angles_deg=(-60, 74, 0.1))
    >>> round(r["periodicity_nm"]["mean"] / 100) * 100                      # the 2500 nm blazed grating
    2500
    >>> r["matrix"].shape                                   # reflectance over (λ, θ_r)
    (5, 1341)
"""
from __future__ import annotations

import json
import math
import os

from . import _native
from ._gpu import ensure_gpu_environment
from ._answer import count, flag, keywords, whole, with_text
from .surface import Surface

__all__ = ["testbench", "compare", "sweep", "laser", "METHODS"]

#: The methods every lab function accepts (``iridis compare --help``).
METHODS = ("ground-truth", "ground-truth-periodic", "reference", "lookup", "nmm", "pq", "stam-periodic",
           "stam-periodic-triangular", "stam-gaussian")


def _surface(s):
    if isinstance(s, Surface):
        return s._h
    if isinstance(s, (str, os.PathLike)):
        return os.fspath(s)
    raise TypeError(f"surface must be an iridis.surface.Surface or a SURFACE argument (str), got {type(s).__name__}")


def _triple(value, name):
    try:
        a, b, c = (float(x) for x in value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be (from, to, step), got {value!r}") from None
    return a, b, c


@keywords
def testbench(surface, method="reference", incidence=math.radians(75.0), azimuth=None, order=1,
              wavelengths=(380.0, 780.0, 5.0), angles_deg=(-89.0, 89.0, 0.05), period_nm=None, max_period_nm=None,
              **options):
    """The test bench (paper sec. 6.1, Table 1): light in the x-z plane at ``incidence``, the viewer in the same
    plane at signed θ_r; for each wavelength the peak of the ``order`` found and the periodicity
    ``d_λ = m λ / (sin θ_i − sin θ_r)`` reported with its mean and variance over λ. ``azimuth`` (radians)
    rotates the surface about its normal (0: periods along x, π/2: along y); ``None`` measures along the
    orientation of the surface's strongest period, as ``Surface.info`` finds it. ``wavelengths`` and
    ``angles_deg`` are ``(from, to, step)``; ``period_nm`` centres the order's window on a known period.
    ``method="rigorous"`` takes the unit cell's orders with Maxwell's efficiencies, over ``material`` (default
    n = 1.5) and ``unit_cell`` (``"whole"`` or ``"auto"``), as ``iridis testbench --method rigorous``.

    Returns ``iridis testbench --json``'s dict (``periodicity_nm``, ``peaks``, ``ridges``, …) with ``matrix``
    (the reflectance over ``wavelength_nm`` × ``angle_deg``) besides. Why a period is not definite is a Python
    warning, as the CLI's.
    """
    out, text, matrix, wl, ang = _native._testbench(
        _surface(surface), str(method), float(incidence), None if azimuth is None else float(azimuth),
        whole(order, "order"),
        _triple(wavelengths, "wavelengths"), _triple(angles_deg, "angles_deg"), period_nm, max_period_nm, options)
    result = with_text(json.loads(out), text)
    result.update(matrix=matrix, wavelength_nm=wl, angle_deg=ang)
    return result


@keywords
def compare(surface, methods=("lookup", "reference", "stam-periodic", "stam-gaussian"), against="model",
            exposures=(1.0, 1000.0, 7500.0), incidence=(0.0, 0.0), size=101, step_nm=5.0, illuminant="d65",
            uv_resolution=None, uv_power=None, table=None, gpu=False, **options):
    """CIELAB errors between methods (paper sec. 6.3, Table 2): each method's BRDF map displayed at each
    exposure and compared per pixel by CIEDE2000 with the ground truth of its own model (``against="model"``,
    the patch's periodic extension), the finite aperture (``"ground-truth"``) or any method.

    Returns ``iridis compare --json``'s dict (``results``: method, against, exposure_ru, mean, p95, max, ratio;
    ``periodic_extension_error``; …) with ``maps`` besides: each method's and each ground truth's map as XYZ of
    shape ``(size, size, 3)``, NaN outside the unit disk. ``gpu=True`` builds the lookup tables and renders the
    ground truths on the GPU (``--gpu``).
    """
    if isinstance(methods, str):
        methods = [m for m in methods.split(",") if m.strip()]
    theta, phi = _incidence(incidence)
    if gpu:
        ensure_gpu_environment()
    out, text, maps = _native._compare(
        _surface(surface), [str(m).strip() for m in methods], str(against), [float(e) for e in exposures], theta,
        phi, count(size, "size"), float(step_nm), str(illuminant), _opt(uv_resolution, int), _opt(uv_power, float),
        None if table is None else os.fspath(table), options, flag(gpu, "gpu"))
    result = with_text(json.loads(out), text)
    result["maps"] = maps
    return result


@keywords
def sweep(surface, param, values, output, method="reference", against="model", exposures=(1000.0,),
          incidence=(0.0, 0.0), size=64, step_nm=None, uv_resolution=None, uv_power=None, plot=None, gpu=False,
          **options):
    """A convergence sweep (paper sec. 7, Figures 14–17; ``iridis sweep``): the method's BRDF map for each of
    ``values`` of ``param`` (``"terms"``, ``"dlambda"``, ``"coherence"`` — lengths in nm —, ``"uv_power"`` (or ``"uv-power"``),
    ``"uv_resolution"``) and its CIEDE2000 error against the ground truth (``against``: ``"model"``,
    ``"ground-truth"`` or ``"ground-truth-periodic"``). Writes the contact sheet to ``output`` and the
    error plot to ``plot`` (default ``output``'s name with ``_error``); returns ``iridis sweep --json``'s dict
    (``points``: ``value``, ``errors`` and ``periodic_extension_error`` per exposure: ``mean``, ``p95``).
    ``step_nm`` (default 5), ``uv_resolution`` (default 201) and ``uv_power`` (default 5) apply where not swept;
    given for the parameter swept (``coherence_nm`` and ``terms`` too), or a u-v grid with another method than
    lookup, they raise ValueError (they would be ignored). ``gpu=True`` builds the tables and renders the ground
    truths on the GPU (``--gpu``)."""
    theta, phi = _incidence(incidence)
    if gpu:
        ensure_gpu_environment()
    # "uv_power" as Python spells its keywords, or the CLI's "uv-power".
    param = str(param).replace("_", "-")
    try:
        out, text = _native._sweep(_surface(surface), param, [float(v) for v in values], os.fspath(output),
                                   str(method), str(against), [float(e) for e in exposures], theta, phi,
                                   count(size, "size"), _opt(step_nm, float), _opt(uv_resolution, int),
                                   _opt(uv_power, float), None if plot is None else os.fspath(plot), options,
                                   flag(gpu, "gpu"))
    except ValueError as e:
        # The library names the parameters as the CLI spells them ('uv-power'); say them as given here.
        said = str(e)
        for cli_name in _SWEPT_WITH_HYPHENS:
            said = said.replace(cli_name, cli_name.replace("-", "_"))
        raise type(e)(said) from None
    return with_text(json.loads(out), text)


# The sweep's parameters whose CLI name has a hyphen.
_SWEPT_WITH_HYPHENS = ("uv-power", "uv-resolution")


@keywords
def laser(surface, output, method="reference", incidence=math.radians(45.0), azimuth=0.0, aperture_nm=65000.0,
          distance_nm=1e8, screen_nm=3e8, size=101, subsamples=3, spectrum=None, coating="gold",
          exposures=(1.0, 1000.0, 7500.0), step_nm=5.0, uv_resolution=None, uv_power=None, table=None, save_table=None,
          **options):
    """The laser experiment of the paper's Figure 8 (``iridis experiment laser``): a beam at ``incidence``
    through a diaphragm of ``aperture_nm`` (the coherence window) onto the sample, the screen ``distance_nm``
    away. Writes one PNG per exposure (``NAME_<E>RU.png`` when several) and returns ``iridis experiment laser
    --json``'s dict with ``xyz`` besides: the screen as XYZ of shape ``(size, size, 3)``. ``uv_resolution`` and
    ``uv_power`` shape the lookup table built for the beam (``method="lookup"``; with another method they raise
    ValueError: they would be ignored)."""
    out, text, xyz = _native._laser(
        _surface(surface), os.fspath(output), str(method), float(incidence), float(azimuth), float(aperture_nm),
        float(distance_nm), float(screen_nm), count(size, "size"), count(subsamples, "subsamples"),
        None if spectrum is None else os.fspath(spectrum), str(coating), [float(e) for e in exposures],
        float(step_nm), _opt(uv_resolution, int), _opt(uv_power, float), None if table is None else os.fspath(table),
        None if save_table is None else os.fspath(save_table), options)
    result = with_text(json.loads(out), text)
    result["xyz"] = xyz
    return result



def _opt(value, kind):
    """``kind(value)``, or None for an option not given (the library then takes its default, and refuses what
    was given where it would be ignored)."""
    return None if value is None else kind(value)


def _incidence(incidence):
    try:
        return (float(x) for x in incidence) if hasattr(incidence, "__len__") else (float(incidence), 0.0)
    except (TypeError, ValueError):
        raise TypeError(f"incidence must be θ or (θ, φ) in radians, got {incidence!r}") from None
