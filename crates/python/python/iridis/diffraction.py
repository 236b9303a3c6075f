"""Diffraction from a measured height field (Dhillon et al. 2014): the paper's lookup tables (precompute,
save, load), BRDF maps as linear XYZ arrays, and point queries (ρ(λ) and XYZ for one pair of directions).

Every method of the CLI: ``reference`` (Taylor terms + windowed DFT per wavelength), ``ground-truth`` (the
direct windowed Fourier sum), ``lookup`` (the precomputed tables), and the lab's ``nmm``, ``pq``,
``stam-periodic``, ``stam-periodic-triangular``, ``stam-gaussian``, and ``rigorous`` (each order's lobe of a
periodic SURFACE carrying Maxwell's efficiency, the C-method; options ``material`` — ``"gold"``,
``"keratin"``, ``"n=1.5"`` (default) — and ``unit_cell`` — ``"whole"`` or ``"auto"``, a scan's dominant
period averaged along its ridges; docs/diffraction.md). The same library functions as
``iridis precompute``, ``iridis brdf-map`` and ``iridis brdf eval`` (the facade ``iridis-api``), with the same
defaults (Taylor terms from the remainder bound 1e-6; coherence 65 µm, the light's, a smaller patch taken as
one unit cell of a periodic surface, said on the ``iridis`` logger) and the same messages. Lengths in nm,
angles in radians. ``grating`` gives the order efficiencies of a unit cell (``iridis grating``).

A ``source`` is an :class:`iridis.surface.Surface`, a :class:`Table`, or a SURFACE or TABLE argument exactly
as the CLI takes it (``"builtin:elaphe"``, ``"scan.gwy"``, ``"table.npz"``: a file is plane-levelled unless
``level=`` says otherwise). Keyword ``options``: ``coherence_nm``, ``terms``, ``illuminant``, ``observer``,
``step_nm``, ``fresnel`` (``"schlick:1.5"``, ``"index:0.2+3.4i"``, ``"gold"``, ``"stack:air | keratin 300nm |
n=1.56"``), ``fresnel_convention`` (``"physical"`` or ``"paper"``), ``shadowing``, ``uv_resolution``,
``uv_power`` (tables built from a height field) and, for SURFACE arguments, ``pixel_size_nm``,
``max_height_nm``, ``channel``, ``height_unit``, ``level``, ``override_units``, ``as_height``. Warnings the CLI
prints (a coarse wavelength step, a patch smaller than the window) are Python warnings.

Example:
    >>> import numpy as np, iridis.surface as surface, iridis.diffraction as diffraction
    >>> flat = surface.Surface(np.zeros((16, 16)), 100.0)
    >>> m = diffraction.brdf_map(flat, size=9, method="reference")    # a mirror at normal incidence
    >>> round(float(m[4, 4, 1]), 9), float(np.delete(m[..., 1].ravel(), 40).max()) < 1e-6
    (1.0, True)
    >>> q = diffraction.evaluate(flat, light=0.3, view=(0.3, np.pi))   # the mirror direction
    >>> q["method"], q["wavelength_nm"].shape, q["reflectance"].shape
    ('reference', (81,), (81,))
"""
from __future__ import annotations

import math
import os

from . import _native
from ._gpu import ensure_gpu_environment
from ._answer import count, flag, keywords, with_text
from .surface import Surface

__all__ = ["Table", "precompute", "brdf_map", "brdf_map_of", "brdf_map_run", "evaluate", "brdf_eval", "grating",
           "vision"]


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


def _native_source(source):
    if isinstance(source, Table):
        return source._t
    if isinstance(source, Surface):
        return source._h
    if isinstance(source, (str, os.PathLike)):
        return os.fspath(source)
    raise TypeError(
        "source must be an iridis.surface.Surface, an iridis.diffraction.Table or a SURFACE or TABLE argument "
        f"as the CLI takes it (str), got {type(source).__name__}"
    )


def _direction(value, name):
    """θ or (θ, φ) in radians."""
    try:
        if hasattr(value, "__len__"):
            theta, phi = (float(x) for x in value)
        else:
            theta, phi = float(value), 0.0
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be θ or (θ, φ) in radians, got {value!r}") from None
    return theta, phi


@keywords
def precompute(surface, coherence_nm=None, terms=None, uv_resolution=None, uv_power=None, illuminant=None,
               observer=None, step_nm=None, name=None, units=None, gpu=False, **options):
    """The paper's tables ``I_p(u, v)`` of a height field (a Surface or a SURFACE argument), as
    ``iridis precompute`` (the same library call): ``terms=None`` takes as many Taylor terms as the heights need
    (``--terms auto``), the coherence, the u-v grid (501², exponent 5) and the spectral setup default as the CLI's
    (D65, CIE 1931, 5 nm); ``units="radiometric"`` tables the BRDF instead of the paper's relative reflectance
    (``--units``), ``gpu=True`` builds them on the GPU (``--gpu``, values in f32)."""
    options.update(coherence_nm=coherence_nm, terms=terms, uv_resolution=uv_resolution, uv_power=uv_power,
                   illuminant=illuminant, observer=observer, step_nm=step_nm, units=units, gpu=flag(gpu, "gpu"))
    if gpu:
        ensure_gpu_environment()
    return Table(_native.precompute(_native_source(surface), name, options))


@keywords
def brdf_map(source, incidence=(0.0, 0.0), size=256, method=None, per_sr=False, gpu=False, subsamples=1,
             **options):
    """A BRDF map as linear XYZ of shape ``(size, size, 3)`` (row 0 at the top; outside the unit disk 0), as
    ``iridis brdf-map --raw`` writes it; with ``per_sr=True`` the BRDF f_r in sr⁻¹ as XYZ instead (Y the
    luminous BRDF), as ``iridis brdf-map --brdf`` writes it (reference, ground truths, rigorous).

    ``method``: default ``"lookup"`` for a :class:`Table`, ``"reference"`` for a height field (a SURFACE
    argument that is a table file counts as a table). ``incidence``: ``θ_i`` or ``(θ_i, φ_i)`` in radians.
    A normal-incidence mirror has ``Y = 1`` in its specular pixel. ``gpu=True`` renders the lookup method or a
    ground truth on the GPU (``iridis brdf-map --gpu``; a SURFACE or TABLE argument, ``table_precision``
    ``"cheb12"`` by default; a ValueError naming the driver to install when there is no adapter); ``f32=True``
    evaluates the lookup sum in f32. Those take :func:`brdf_map_run`'s path, the CLI's own call. ``subsamples``
    (1–16): each pixel the mean of ``subsamples²`` view directions across it (``--subsamples``), so that lobes
    narrower than a pixel still show (with ``gpu=True``, the GPU's map ``subsamples`` times the size averaged over
    blocks); a map too coarse for its lobes says so in a warning.
    """
    if gpu or options.get("f32") or options.get("table_precision") is not None:
        out = brdf_map_run(source, incidence, size, method or "lookup", per_sr=per_sr, gpu=gpu,
                           subsamples=subsamples, **options)
        return out["per_sr"] if per_sr else out["xyz"]
    theta, phi = _direction(incidence, "incidence")
    return _native.brdf_map_xyz(_native_source(source), method, theta, phi, count(size, "size"), options,
                                flag(per_sr, "per_sr"),
                                count(subsamples, "subsamples"))


@keywords
def brdf_map_run(source, incidence=(0.0, 0.0), size=512, method="lookup", **options):
    """``iridis brdf-map`` on a SURFACE or TABLE argument (str), the CLI's own library call, before it writes
    files: a dict with ``xyz`` (linear XYZ of ρ), ``per_sr`` (f_r in sr⁻¹ as XYZ with ``per_sr=True``, else
    None), ``exposure_ru`` (``exposure_ru``, default 1500, or the one ``auto_exposure=True`` chose: the
    99th-percentile lit pixel white), ``method`` and ``coherence_nm``. Options as :func:`brdf_map`'s plus
    ``gpu``, ``table_precision``, ``f32``, ``uv_resolution``, ``uv_power``, ``material``, ``unit_cell``.
    Sizes 8 to 8192, as the CLI's."""
    if not isinstance(source, (str, os.PathLike)):
        raise TypeError(f"brdf_map_run takes a SURFACE or TABLE argument (str), got {type(source).__name__}")
    theta, phi = _direction(incidence, "incidence")
    if options.get("gpu"):
        ensure_gpu_environment()
    return _native.brdf_map_run(os.fspath(source), method, theta, phi, count(size, "size"), options)


@keywords
def brdf_eval(source, light, view, method=None, **options):
    """``iridis brdf eval --json`` as a dict, the same keys and numbers (the CLI's own library call) on a
    SURFACE or TABLE argument (str): the inputs, ``fresnel_r0``, ``wavelength_nm``, ``brdf_per_sr`` (f_r(λ)
    in sr⁻¹ for s, p and unpolarised light), ``reflectance`` (ρ(λ)), ``xyz``, ``vision`` (with
    ``visual="bluetit"``, …), ``rigorous`` and ``scalar_error``. ``light``, ``view``: θ or (θ, φ) in radians."""
    if not isinstance(source, (str, os.PathLike)):
        raise TypeError(f"brdf_eval takes a SURFACE or TABLE argument (str), got {type(source).__name__}")
    return with_text(*_native.brdf_eval(os.fspath(source), method, _direction(light, "light"),
                                         _direction(view, "view"), options))


@keywords
def evaluate(source, light, view, method=None, **options):
    """ρ(λ) and XYZ of one method for one pair of directions (``θ`` or ``(θ, φ)``, radians, pointing away from
    the surface; the mirror direction of ``(θ, φ)`` is ``(θ, φ + π)``), as ``iridis brdf eval --json``.

    Returns a dict: ``method``, ``wavelength_nm``, ``brdf_per_sr`` (the BRDF f_r(λ) in sr⁻¹, a dict of arrays
    ``s``, ``p``, ``unpolarized``; ``None`` where the method has no window gain or under the paper's R²
    convention), ``reflectance`` (the paper's relative ρ(λ) = f_r cos θ_i λ²/(A_eff R₀), eq. 4 with the
    cos θ_i of eq. 9: 1 at a flat mirror's peak; ``None`` for lookup, which integrates over λ in advance),
    ``coherence_nm``, ``window_effective_area_um2`` (A_eff, 4πσ_s² inside the patch), ``xyz`` (eq. 9) with the
    ``illuminant`` and ``observer`` it was integrated under (a table's own), ``fresnel``, ``fresnel_convention``
    and ``shadowing`` (``None`` for the rigorous method),
    ``fresnel_r0`` (the Fresnel source's normal-incidence reflectance that the relative ρ divides by), ``polarised``
    (whether s and p differ), ``rigorous`` (the rigorous method's material, unit cell, solves and estimated error;
    ``None`` for the others), ``table`` (what a lookup table was built from; ``None`` without one),
    ``light_direction``, ``view_direction``, and ``scalar_error`` (the scalar model's error on a scan's own
    period, as ``brdf_eval``'s, warned where above its threshold; ``None`` for a table, the rigorous method or
    a surface without a dominant period).
    """
    wi = _direction(light, "light")
    wr = _direction(view, "view")
    return _native.eval_point(_native_source(source), method, wi, wr, options)


@keywords
def brdf_map_of(spec, incidence=(0.0, 0.0), size=256, method="reference", level=None, **options):
    """:func:`brdf_map` of a SURFACE argument as ``iridis brdf-map`` takes it: a file (plane-levelled unless
    ``level`` says otherwise, as the CLI does) or ``builtin:…`` (used as generated). A plain function of its
    arguments, so it is what batch scripts send to Dask workers."""
    return brdf_map(os.fspath(spec), incidence=incidence, size=size, method=method, level=level, **options)


@keywords
def grating(source, light=0.0, wavelengths_nm=550.0, method=None, material=None, fresnel=None,
            normalisation=None, detector=None, acceptance=None, compare=False, orders_above=None, **options):
    """Order efficiencies of ``source`` taken as one unit cell of a grating (its extent is the period), as
    ``iridis grating --json``: a dict with ``orders`` (every propagating order at every wavelength: ``m``,
    ``n``, ``theta_deg``, ``phi_deg``, ``efficiency`` with ``te``, ``tm``, ``unpolarized``, fractions of the
    incident power), ``reflected_total`` per wavelength, ``detector`` (the orders inside the acceptance cone,
    when ``detector`` is given), ``convergence`` and the model's assumptions.

    ``light`` and ``detector`` are ``θ`` or ``(θ, φ)`` in radians (``light`` default 0: normal incidence, as the
    CLI's ``--light``); ``wavelengths_nm`` a number or a sequence (default 550, as ``--wavelength``);
    ``material`` the medium under the relief as a stack writes it (``"gold"``, ``"n=1.5"``, ``"n=0.2+3.4i"``;
    default n = 1.5) or ``fresnel`` any Fresnel source (``"schlick:1.5"``); ``normalisation`` the scalar model's,
    ``"energy"`` (the default: energy and reciprocity exact) or ``"kirchhoff"`` (the obliquity factor as printed;
    with ``method="rigorous"`` it raises ValueError: it would be ignored); ``acceptance`` the
    detector's half-angle in radians (default 2°). SURFACE options (``pixel_size_nm``, ``level``, …) as
    elsewhere. ``method``: ``"kirchhoff"`` (the default, the scalar model) or ``"rigorous"``, which solves
    Maxwell's equations (the C-method; transmitted orders and the convergence record too); ``compare=True``
    runs both models (``method="rigorous"`` with it raises ValueError) and returns ``iridis grating --compare
    --json``'s dict: every order of both, the worst relative error, CIEDE2000 of the colours. ``unit_cell="auto"`` takes
    the scan's strongest period, its profile averaged along the ridges, as the cell. ``orders_above`` (a
    fraction, ``--orders-above``) lists only the orders of at least that efficiency; the totals count them all.
    """
    theta, phi = _direction(light, "light")
    opts = dict(options, compare=flag(compare, "compare"))
    if method is not None:
        opts["method"] = method
    if normalisation is not None:
        opts["normalisation"] = normalisation
    if material is not None:
        opts["material"] = material
    if fresnel is not None:
        opts["fresnel"] = fresnel
    if detector is not None:
        opts["detector_theta"], opts["detector_phi"] = _direction(detector, "detector")
    if acceptance is not None:
        opts["acceptance"] = _acceptance(acceptance)
    if orders_above is not None:
        opts["orders_above"] = _fraction(orders_above, "orders_above")
    if isinstance(wavelengths_nm, (str, bytes)):  # a str would be read character by character
        raise TypeError(f"wavelengths_nm must be a number or a sequence of numbers (nm), got {wavelengths_nm!r}")
    wl = [float(w) for w in (wavelengths_nm if hasattr(wavelengths_nm, "__len__") else [wavelengths_nm])]
    return with_text(*_native.grating(_native_source(source), (theta, phi), wl, opts))


def _acceptance(x):
    """The detector's half-angle in radians, in (0, π/2); degrees by mistake are named."""
    a = float(x)
    if not 0 < a < math.pi / 2:
        hint = "; if it is in degrees, convert it with math.radians(...)" if math.pi / 2 <= a <= 90 else ""
        raise ValueError(f"acceptance is {a:g} rad: the detector's half-angle lies between 0 and π/2 rad{hint}")
    return a


def _fraction(x, name):
    """A fraction given as a number or, as on the command line, as a percentage ("0.1%")."""
    if isinstance(x, str) and x.strip().endswith("%"):
        try:
            return float(x.strip()[:-1]) / 100.0
        except ValueError:
            pass
    try:
        return float(x)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a fraction (0.001) or a percentage ('0.1%'), got {x!r}") from None


@keywords
def vision(source, visual, light=0.0, views_deg=(-60, -50, -40, -30, -20, -10, 0, 10, 20, 30, 40, 50, 60),
           azimuth=None, illuminant=None, **options):
    """How an animal sees ``source`` from several directions, as ``iridis brdf vision --json``: the reflectance
    factor π f_r(λ) (unpolarised, 300–700 nm, the reference method) at each view angle (degrees, signed, in the
    plane of incidence; positive on the specular side) for light at ``light`` (radians) in the plane of
    ``azimuth`` (radians; default the surface's dominant orientation), analysed by the receptor-noise-limited
    model for ``visual`` (``"bluetit"``, ``"honeybee"``, …; see :mod:`iridis.vision`). Returns a dict with
    ``views`` (``name``, ``theta_r_deg``, ``reflectance_factor``), ``wavelength_nm`` and ``vision`` (the
    analysis: quantum catches, ΔS and ΔL in JND between every pair of directions). ``options``: the model's
    ``coherence_nm``, ``terms``, ``step_nm`` (the 300–700 nm grid's step, default 5; ``taylor_terms`` in the
    result says N) and ``conserve_energy`` (energy-normalised lobes, as ``brdf eval --conserve-energy``; the
    result's ``quantity`` says so), and the surface's; ``observer`` is refused, not ignored."""
    return with_text(*_native.brdf_vision(_native_source(source), str(visual), float(light),
                                           [float(v) for v in views_deg], None if azimuth is None else float(azimuth),
                                           illuminant, options))

