"""Multilayer thin films: stacks in the CLI's syntax (``"air | water 348nm | air"``) or from lists of
indices and thicknesses; R, T and A for s, p and unpolarised light broadcast over arrays of wavelengths,
angles and thickness offsets; reflected and transmitted colours. The numbers are those of
``iridis thinfilm spectrum`` and ``iridis thinfilm color`` (the same library calls).

Lengths in nm, angles in radians. As everywhere in iridis, T into an absorbing substrate is 0 (use
``iridis.tmm`` for tmm's convention).

Example:
    >>> import numpy as np, iridis.thinfilm as tf
    >>> soap = tf.Stack("air | water 635nm | air")
    >>> round(float(soap.reflectance(400.0, np.radians(1.0))), 6)    # Sussenbach, Figure 3.8: 0.0334109
    0.033411
    >>> out = soap.rta(np.linspace(400, 700, 31)[:, None], np.radians([0, 30, 60]))
    >>> out["R"].shape
    (31, 3)

Rough films (Sussenbach's LSRS model: the stack on a substrate of rms roughness σ and correlation length τ,
the HTSG BRDF at the rough interface) come from :meth:`Stack.rough`, as ``iridis thinfilm spectrum|color
--roughness σ --correlation τ``:

    >>> film = tf.Stack("air | water 348nm | Si").rough(25.0, 300.0)     # Sussenbach, Listing 3.6
    >>> c = film.color(np.radians(30))
    >>> sorted(k for k in c if not k.endswith(("_lab", "_srgb", "_hex")))
    ['diffuse', 'reflected', 'specular', 'transmitted']
    >>> s = film.spectrum([450.0, 550.0, 650.0], np.radians(30))
    >>> bool((s["specular"] < s["R_smooth"]).all())      # here: roughness scatters light out of the mirror
    True
"""
from __future__ import annotations

import logging
import os

import numpy as np

from . import _native
from ._answer import flag, warn_caller
from .color import xyz_to_hex, xyz_to_lab, xyz_to_srgb, white_point

__all__ = ["Stack", "RoughFilm", "colors_of_stacks", "material_index", "materials", "fit", "profile"]

_POL = {"s": "s", "p": "p", "unpolarized": "avg", "unpolarised": "avg", "avg": "avg", "average": "avg"}


def _real(x, name):
    a = np.asarray(x)
    if a.dtype.kind not in "biuf":
        raise TypeError(f"{name} must hold real numbers, got dtype {a.dtype}")
    a = a.astype(np.float64, copy=False)
    bad = ~np.isfinite(a)
    if bad.any():
        where = tuple(int(i) for i in np.argwhere(bad)[0]) if a.ndim else ()
        raise ValueError(f"{name} holds {a[where] if a.ndim else a} at index {where}: every value must be a finite "
                         "number (drop or replace NaN and inf before calling)")
    return a


def _wavelengths(x, name="wavelengths_nm"):
    """Wavelengths in nm: finite, > 0, and not metres or µm by mistake."""
    a = _real(x, name)
    if a.size == 0:
        return a
    lo, hi = float(a.min()), float(a.max())
    if lo <= 0:
        raise ValueError(f"{name} holds {lo}: wavelengths are in nm and must be > 0")
    if hi < 1e-4:
        raise ValueError(f"{name} reaches only {hi:g}: that looks like metres; iridis takes nanometres — multiply "
                         "by 1e9 (e.g. 550e-9 m → 550 nm)")
    if hi < 20:
        raise ValueError(f"{name} reaches only {hi:g}: that looks like µm; iridis takes nanometres — multiply by "
                         "1000 (e.g. 0.55 µm → 550 nm)")
    return a


def _colour_grid(grid_nm):
    """The wavelengths a colour is integrated over: ``grid_nm``, or the CIE range 380–780 nm in 5 nm steps; a grid
    holding too little of the eye's response is refused and a partial band warned, as ``thinfilm color`` does."""
    if grid_nm is None:
        return np.arange(380.0, 780.0 + 1e-9, 5.0)
    grid = _wavelengths(grid_nm, "grid_nm")
    _native._check_colour_grid(np.sort(grid.ravel()).tolist())
    return grid


def _angles(x, name="angles_rad"):
    """Angles of incidence in radians, 0 ≤ θ ≤ π/2 (what the core takes); degrees by mistake are named."""
    a = _real(x, name)
    if a.size and a.min() < 0:
        raise ValueError(f"{name} holds {float(a.min()):g} rad: angles of incidence lie in 0…π/2 rad (from the "
                         "normal; a stack has no sign of direction)")
    if a.size and a.max() > np.pi / 2 + 1e-12:
        worst = float(a.max())
        hint = ("; if these are degrees, convert them with numpy.radians(...)" if worst <= 90.0 + 1e-9 else "")
        raise ValueError(f"{name} reaches {worst:g} rad: angles of incidence lie in 0…π/2 rad{hint}")
    return a


def _offsets(x, stack, name="offsets_nm"):
    """Thickness offsets (nm): finite, and no layer thinner than 0 after the offset."""
    a = _real(x, name)
    d = stack._s.thicknesses
    if a.size and d:
        lowest, thinnest = float(a.min()), min(d)
        if thinnest + lowest < 0:
            layer = d.index(thinnest) + 1
            raise ValueError(f"{name} holds {lowest:g} nm, which makes layer {layer} ({thinnest:g} nm) thinner than 0; "
                             f"offsets must be ≥ {-thinnest:g} nm (the offset is added to every layer)")
    return a


def _broadcast(*pairs):
    arrays = [np.asarray(x) for x, n in pairs]
    try:
        out = np.broadcast_arrays(*arrays)
    except ValueError:
        shapes = ", ".join(f"{n} {a.shape}" for a, (_, n) in zip(arrays, pairs))
        raise ValueError(f"the arrays do not broadcast together: {shapes}") from None
    return [np.ascontiguousarray(a.ravel()) for a in out], out[0].shape


def material_index(name, wavelengths_nm):
    """``n + iκ`` of a material (library name such as ``"Si"``, ``"n=1.38"``, ``"file:PATH"``) at each
    wavelength (nm)."""
    wl = _wavelengths(wavelengths_nm)
    out = _native.material_index(name, np.ascontiguousarray(np.atleast_1d(wl).ravel()))
    return out.reshape(wl.shape) if wl.ndim else complex(out[0])


def colors_of_stacks(indices, thicknesses_nm, angle_rad=0.0, illuminant="D65", observer="1931",
                     polarization="unpolarized", grid_nm=None):
    """Reflected and transmitted XYZ of many stacks at once (in parallel, the GIL released).

    ``indices``: shape ``(stacks, media)`` (incident, layers…, substrate; constant, complex allowed);
    ``thicknesses_nm``: ``(stacks, media − 2)``. Returns ``{"reflected": (stacks, 3), "transmitted": …}``,
    row ``i`` equal to ``Stack.from_lists(indices[i], thicknesses_nm[i]).color(angle_rad)``.

    >>> import numpy as np, iridis.thinfilm as tf
    >>> d = np.array([[300.0], [348.0]])
    >>> xyz = tf.colors_of_stacks(np.tile([1.0, 1.33, 1.0], (2, 1)), d)["reflected"]
    >>> xyz.shape
    (2, 3)
    """
    pol = _POL.get(str(polarization).lower())
    if pol is None:
        raise ValueError(f"polarization {polarization!r}: use 's', 'p' or 'unpolarized'")
    n = np.asarray(indices)
    if n.dtype.kind not in "biufc":
        raise TypeError(f"indices must hold numbers, got dtype {n.dtype}")
    if not np.isfinite(n).all():
        raise ValueError("indices hold NaN or inf: every index must be a finite number")
    d = _real(thicknesses_nm, "thicknesses_nm")
    if d.size and d.min() < 0:
        raise ValueError(f"thicknesses_nm holds {d.min():g}: thicknesses are in nm and must be ≥ 0")
    grid = _colour_grid(grid_nm)
    angle_rad = float(_angles(angle_rad, "angle_rad"))
    if n.ndim == 3:
        # One index per medium and wavelength of the grid (dispersive media): each stack on its own.
        if d.ndim != 2 or n.shape[:2] != (d.shape[0], d.shape[1] + 2) or n.shape[2] != grid.size:
            raise ValueError(f"indices of shape {n.shape} (stacks, media, wavelengths) need thicknesses of shape "
                             f"({n.shape[0]}, {n.shape[1] - 2}) and grid_nm of {n.shape[2]} wavelengths")
        rows = [Stack.from_lists(list(n[i]), d[i], wavelengths_nm=grid).color(angle_rad, 0.0, illuminant, observer,
                                                                              polarization, grid)
                for i in range(n.shape[0])]
        return {"reflected": np.array([r["reflected"] for r in rows]),
                "transmitted": np.array([r["transmitted"] for r in rows])}
    if n.ndim != 2 or n.shape[1] < 2:
        raise ValueError(f"indices of shape {n.shape}: give one row per stack, (stacks, media) with at least two "
                         "media (the incident medium and the substrate), or (stacks, media, wavelengths)")
    if d.shape != (n.shape[0], n.shape[1] - 2):
        raise ValueError(f"indices of shape {n.shape} need thicknesses_nm of shape ({n.shape[0]}, {n.shape[1] - 2}) "
                         f"(one row per stack, one thickness per layer between the two media), got {d.shape}")
    out = _native._stack_colors(np.ascontiguousarray(n, dtype=np.complex128), np.ascontiguousarray(d),
                                float(angle_rad), np.ascontiguousarray(grid.ravel()), illuminant, observer, pol)
    return {"reflected": out[:, :3], "transmitted": out[:, 3:]}


def materials():
    """The built-in library: a list of ``(names, description)``."""
    return _native.materials()


class Stack:
    """A stack: a lossless incident medium, layers, a substrate.

    ``Stack("air | gasoline 216nm | water 220nm | asphalt")`` takes the CLI's syntax (library names,
    ``n=1.38+0.01i``, ``file:PATH``, ``inc:`` for incoherent layers); ``Stack.from_lists(indices,
    thicknesses_nm)`` takes the indices of all media (incident first) and the layers' thicknesses.
    """

    def __init__(self, spec):
        if isinstance(spec, _native._Stack):
            self._s = spec
        elif isinstance(spec, str):
            self._s = _native._Stack(spec)
        else:
            raise TypeError(f"Stack takes the CLI's stack syntax as a str, got {type(spec).__name__}; "
                            "use Stack.from_lists for lists")

    @classmethod
    def from_lists(cls, indices, thicknesses_nm, incoherent=None, wavelengths_nm=None):
        """From complex indices (incident, layers…, substrate) and one thickness (nm) per layer;
        ``incoherent``: one bool per layer.

        An index may be an array with one value per wavelength of ``wavelengths_nm`` (dispersive media, e.g.
        from ``material_index``): it is interpolated linearly in between, and wavelengths outside are refused,
        as the built-in measured data are. ``indices`` may also be one array of shape (media, wavelengths).

        >>> import numpy as np, iridis.thinfilm as tf
        >>> wl = np.array([400.0, 500.0, 600.0, 700.0])
        >>> s = tf.Stack.from_lists([1.0, tf.material_index("TiO2", wl), 1.52], [60.0], wavelengths_nm=wl)
        >>> s.reflectance([450.0, 650.0]).shape
        (2,)
        """
        inc = None if incoherent is None else [bool(x) for x in incoherent]
        d = _real(thicknesses_nm, "thicknesses_nm")
        if d.size and d.min() < 0:
            raise ValueError(f"thicknesses_nm holds {d.min():g}: layer thicknesses are in nm and must be ≥ 0")
        if d.size and 0 < d.max() < 1e-4:
            # Thinner than a thousandth of an atom: metres read as nm (348e-9 gave the bare substrate, silently).
            raise ValueError(f"thicknesses_nm reach only {d.max():g}: that looks like metres; layer thicknesses are "
                             "in nm — multiply by 1e9 (348e-9 m → 348 nm)")
        arrays = isinstance(indices, np.ndarray) and indices.ndim == 2 or any(np.ndim(x) > 0 for x in indices)
        if wavelengths_nm is None:
            if arrays:
                raise ValueError("indices hold arrays (one index per wavelength): give their wavelengths as "
                                 "wavelengths_nm=…")
            n = np.asarray(indices)
            if n.dtype.kind not in "biufc":
                raise TypeError(f"indices must hold numbers, got dtype {n.dtype}")
            if not np.isfinite(n).all():
                raise ValueError("indices hold NaN or inf: every index must be a finite number")
            return cls(_native._Stack.from_lists(indices, d, inc))
        wl = _wavelengths(wavelengths_nm)
        if wl.ndim != 1 or wl.size == 0:
            raise ValueError(f"wavelengths_nm must be a non-empty 1-D array, got shape {wl.shape}")
        rows = list(indices)
        table = np.empty((len(rows), wl.size), dtype=np.complex128)
        constant = []
        for j, x in enumerate(rows):
            a = np.asarray(x)
            if a.dtype.kind not in "biufc":
                raise TypeError(f"indices[{j}] must hold numbers, got dtype {a.dtype}")
            if a.ndim == 0:
                table[j] = a
                constant.append(True)
            elif a.shape == wl.shape:
                table[j] = a
                constant.append(False)
            else:
                raise ValueError(f"indices[{j}] has shape {a.shape}: give one number, or one index per wavelength "
                                 f"({wl.size},)")
            if not np.isfinite(table[j]).all():
                raise ValueError(f"indices[{j}] holds NaN or inf: every index must be a finite number")
        order = np.argsort(wl, kind="stable")
        if np.any(np.diff(wl[order]) == 0):
            raise ValueError("wavelengths_nm holds a wavelength twice: give each once")
        return cls(_native._Stack._from_tables(np.ascontiguousarray(table[:, order]), constant,
                                               np.ascontiguousarray(wl[order]), d, inc))

    def __str__(self):
        return str(self._s)

    def __repr__(self):
        return f"Stack({str(self._s)!r})"

    @property
    def layers(self):
        """The number of layers between the incident medium and the substrate."""
        return self._s.layers

    def indices(self, wavelengths_nm):
        """The complex index of every medium at each wavelength: shape ``(media,) + wavelengths.shape``."""
        wl = _wavelengths(wavelengths_nm)
        out = self._s.indices(np.ascontiguousarray(np.atleast_1d(wl).ravel()))
        return out.reshape((out.shape[0],) + wl.shape)

    def rta(self, wavelengths_nm, angles_rad=0.0, offsets_nm=0.0, polarization="unpolarized"):
        """R, T and A = 1 − R − T at every point of the broadcast of wavelengths × angles × thickness
        offsets (every layer's thickness plus the offset, Sussenbach eq. 4.3). ``polarization``: ``"s"``,
        ``"p"`` or ``"unpolarized"``. Returns a dict of arrays of the broadcast shape."""
        pol = _POL.get(str(polarization).lower())
        if pol is None:
            raise ValueError(f"polarization {polarization!r}: use 's', 'p' or 'unpolarized'")
        (w, a, o), shape = _broadcast((_wavelengths(wavelengths_nm), "wavelengths_nm"),
                                      (_angles(angles_rad), "angles_rad"), (_offsets(offsets_nm, self), "offsets_nm"))
        rs, rp, ts, tp = self._s._rta(w, a, o)
        r, t = {"s": (rs, ts), "p": (rp, tp), "avg": (0.5 * (rs + rp), 0.5 * (ts + tp))}[pol]
        return {"R": r.reshape(shape), "T": t.reshape(shape), "A": (1.0 - r - t).reshape(shape)}

    def reflectance(self, wavelengths_nm, angles_rad=0.0, offsets_nm=0.0, polarization="unpolarized"):
        """R alone (see :meth:`rta`)."""
        return self.rta(wavelengths_nm, angles_rad, offsets_nm, polarization)["R"]

    def transmittance(self, wavelengths_nm, angles_rad=0.0, offsets_nm=0.0, polarization="unpolarized"):
        """T alone (see :meth:`rta`)."""
        return self.rta(wavelengths_nm, angles_rad, offsets_nm, polarization)["T"]

    def rough(self, roughness_nm, correlation_nm, d_iterations=None, diffuse_transport="multiple"):
        """This stack on a rough substrate: rms roughness σ = ``roughness_nm`` of the last interface and its
        autocorrelation length τ = ``correlation_nm`` (valid for σ > 0, 2σ/τ ≤ 1 and τ²/(2√3σ) ≥ λ in the
        medium above the substrate). ``d_iterations``: terms of the HTSG series (default: as many as an error
        bound of 1e-6 of the lobe's peak needs); ``diffuse_transport``: ``"multiple"`` (default: every
        scattering inside the film, energy-conserving), ``"single"`` (one scattering, faster; alias
        ``"reciprocal"``) or ``"thesis"`` (eq. 3.18–3.19 as printed, for comparison only)."""
        return RoughFilm(self, roughness_nm, correlation_nm, d_iterations, diffuse_transport)

    def profile(self, wavelength_nm, angle_rad=0.0, polarization="unpolarized", points=400, depth_nm=None):
        """Where the light goes: :func:`profile` of this stack."""
        return profile(self, wavelength_nm, angle_rad, polarization, points, depth_nm)

    def color(self, angles_rad=0.0, offsets_nm=0.0, illuminant="D65", observer="1931",
              polarization="unpolarized", grid_nm=None):
        """Reflected and transmitted colours, as ``iridis thinfilm color`` (default grid 380–780 nm in 5 nm
        steps), at every point of the broadcast of angles × thickness offsets.

        Returns a dict: ``reflected`` and ``transmitted`` XYZ (shape ``S + (3,)``), their ``*_lab``,
        ``*_srgb`` and ``*_hex``.
        """
        pol = _POL.get(str(polarization).lower())
        if pol is None:
            raise ValueError(f"polarization {polarization!r}: use 's', 'p' or 'unpolarized'")
        grid = _colour_grid(grid_nm)
        (a, o), shape = _broadcast((_angles(angles_rad), "angles_rad"), (_offsets(offsets_nm, self), "offsets_nm"))
        xyz = self._s._colors(a, o, np.ascontiguousarray(grid.ravel()), illuminant, observer, pol)
        refl = xyz[:, :3].reshape(shape + (3,))
        trans = xyz[:, 3:].reshape(shape + (3,))
        white = white_point(illuminant, observer)
        out = {"reflected": refl, "transmitted": trans}
        for k, v in list(out.items()):
            out[k + "_lab"] = xyz_to_lab(v, white)
            out[k + "_srgb"] = xyz_to_srgb(v)
            out[k + "_hex"] = xyz_to_hex(v)
        return out


def _float(x, name, what):
    if isinstance(x, bool):
        raise TypeError(f"{name} must be {what} (a number), got {x!r}")
    try:
        return float(x)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be {what} (a number), got {x!r}") from None


def _angle(x, name):
    v = _float(x, name, "an angle in radians")
    if not np.isfinite(v):
        raise ValueError(f"{name} is {v}: an angle must be a finite number (radians)")
    return v


def _polar(x, name):
    """A polar angle from the normal in radians, 0 ≤ θ ≤ π/2 (the core's range, named here by its keyword)."""
    v = _angle(x, name)
    if not 0 <= v <= np.pi / 2 + 1e-12:
        hint = "; if it is in degrees, convert it with numpy.radians(...)" if np.pi / 2 < v <= 90.0 else ""
        raise ValueError(f"{name} is {v:g} rad: it lies in 0…π/2 rad (from the normal){hint}")
    return v


class RoughFilm:
    """A stack on a rough substrate (LSRS model with the HTSG BRDF; docs/rough-films.md): the specular part
    ``k_r`` (a fraction of the incident power) and the diffuse part ``k_d`` (sr⁻¹; ``π k_d`` is the radiance
    factor, relative to a white Lambertian surface under the same light), next to the smooth film's ``R``.
    Made by :meth:`Stack.rough`."""

    def __init__(self, stack, roughness_nm, correlation_nm, d_iterations=None, diffuse_transport="multiple"):
        if not isinstance(stack, Stack):
            raise TypeError(f"stack must be an iridis.thinfilm.Stack, got {type(stack).__name__}")
        self.stack = stack
        self.roughness_nm = _float(roughness_nm, "roughness_nm", "a length in nm")
        self.correlation_nm = _float(correlation_nm, "correlation_nm", "a length in nm")
        if d_iterations is not None and (isinstance(d_iterations, bool) or int(d_iterations) != d_iterations
                                         or d_iterations < 0):
            raise ValueError(f"d_iterations {d_iterations!r}: a whole number of terms ≥ 0, or None")
        self.d_iterations = None if d_iterations is None else int(d_iterations)
        self.diffuse_transport = str(diffuse_transport)

    def __repr__(self):
        return f"RoughFilm({str(self.stack)!r}, σ = {self.roughness_nm} nm, τ = {self.correlation_nm} nm)"

    def _args(self):
        return self.roughness_nm, self.correlation_nm, self.d_iterations, self.diffuse_transport

    def spectrum(self, wavelengths_nm, view_rad=0.0, light_rad=None, azimuth_rad=np.pi):
        """The spectrum at one view angle, as ``iridis thinfilm spectrum --roughness … --json``: a dict of arrays
        over ``wavelength_nm`` — ``R_smooth``, ``specular`` (and ``specular_s``, ``specular_p``),
        ``diffuse_per_sr`` (and ``diffuse_s_per_sr``, ``diffuse_p_per_sr``) — with ``series_terms_max`` and
        ``diffuse_error_bound_per_sr``. ``light_rad`` defaults to the view angle; ``azimuth_rad`` is the light's
        azimuth relative to the viewer (π: the mirror configuration)."""
        wl = _wavelengths(wavelengths_nm)
        if wl.ndim != 1 or wl.size == 0:
            raise ValueError(f"wavelengths_nm must be a non-empty 1-D array, got shape {wl.shape}")
        view = _polar(view_rad, "view_rad")
        light = view if light_rad is None else _polar(light_rad, "light_rad")
        return self.stack._s._rough_spectrum(*self._args(), np.ascontiguousarray(wl), view, light,
                                             _angle(azimuth_rad, "azimuth_rad"))

    def color(self, view_rad=0.0, light_rad=None, azimuth_rad=np.pi, illuminant="D65", observer="1931",
              grid_nm=None):
        """The colours, as ``iridis thinfilm color --roughness … --json``: XYZ of the smooth film's
        ``reflected`` and ``transmitted`` light, of the rough film's ``specular`` part and of its ``diffuse``
        part (``π k_d``: Y = 1 is a white Lambertian surface under the same light), each with ``*_lab``,
        ``*_srgb`` and ``*_hex``. Default grid 380–780 nm in 5 nm steps."""
        grid = _colour_grid(grid_nm)
        view = _polar(view_rad, "view_rad")
        light = view if light_rad is None else _polar(light_rad, "light_rad")
        xyz = self.stack._s._rough_color(*self._args(), view, light, _angle(azimuth_rad, "azimuth_rad"),
                                         np.ascontiguousarray(grid.ravel()), illuminant, observer)
        white = white_point(illuminant, observer)
        out = {"reflected": xyz[0], "transmitted": xyz[1], "specular": xyz[2], "diffuse": xyz[3]}
        for k, v in list(out.items()):
            out[k + "_lab"] = xyz_to_lab(v, white)
            out[k + "_srgb"] = xyz_to_srgb(v)
            out[k + "_hex"] = xyz_to_hex(v)
        return out


def profile(stack, wavelength_nm, angle_rad=0.0, polarization="unpolarized", points=400, depth_nm=None):
    """Where the light goes in ``stack`` (a :class:`Stack` or the CLI's syntax) at one wavelength and angle,
    as ``iridis thinfilm profile --json`` (the same library function): ``R``, ``T``, ``A_layers`` (absorbed in
    each layer), ``A_substrate``, ``balance`` (R + T + ΣA − 1, rounding), and over ``points`` depths ``z_nm``
    (below the first interface; default window 100 nm above the stack to 100 nm into the substrate, or into
    the first ``inc:`` layer under the films; or ``depth_nm=(from, to)``) the ``medium``, ``E2`` (|E|²,
    incident = 1), ``absorption_per_nm`` and ``flux``. ``notes`` says what the default window left out (also
    logged, as the other functions' notes are, to the ``iridis`` logger) and ``warnings`` which layers the
    samples do not resolve (also Python warnings).

    >>> import iridis.thinfilm as tf
    >>> p = tf.profile("air | Au 30nm | glass", 500.0, points=101)
    >>> round(float(p["R"] + p["T"] + sum(p["A_layers"]) + p["A_substrate"]), 9)
    1.0
    """
    s = stack if isinstance(stack, Stack) else Stack(stack)
    pol = _POL.get(str(polarization).lower())
    if pol is None:
        raise ValueError(f"polarization {polarization!r}: use 's', 'p' or 'unpolarized'")
    wl = float(_wavelengths(_float(wavelength_nm, "wavelength_nm", "a wavelength in nm"), "wavelength_nm"))
    angle = float(_angles(_angle(angle_rad, "angle_rad"), "angle_rad"))
    if isinstance(points, bool) or int(points) != points or not 2 <= points <= 1_000_000:
        raise ValueError(f"points {points!r}: a whole number of depth samples from 2 to 1000000")
    window = None
    if depth_nm is not None:
        lo, hi = (float(v) for v in _real(depth_nm, "depth_nm"))
        if not lo < hi:
            raise ValueError(f"depth_nm ({lo}, {hi}) is empty: the first depth must be above (less than) the second")
        window = (lo, hi)
    out = _native._profile(s._s, wl, angle, pol, int(points), window)
    for text in out["notes"]:
        logging.getLogger("iridis").info(f"note: {text}")
    for text in out["warnings"]:
        warn_caller(text)
    out["wavelength_nm"], out["angle_deg"], out["polarization"] = wl, float(np.degrees(angle)), pol
    return out


def fit(measured, stack, angle_rad=0.0, quantity="R", sigma=None, weights=None, grid=0, columns=None,
        percent=None, from_nm=None, to_nm=None):
    """Fits the free parameters of ``stack`` (the CLI's template syntax, e.g. ``"air | SiO2
    {d1=100nm:50nm..500nm} | Si"``) to a measured spectrum, as ``iridis thinfilm fit --json`` (the same
    library functions: reading, multi-start Levenberg–Marquardt with exact derivatives, covariance).

    ``measured``: a file path, read as the CLI reads it (separators, headers, percent, ``columns``,
    ``from_nm``/``to_nm``; what was found is in ``result["read"]["notes"]``), or arrays ``(wavelengths_nm,
    values)`` or ``(wavelengths_nm, values, sigma)`` — ψ, Δ interleaved for ``quantity="psi-delta"``.
    ``sigma``/``weights``: a number (1σ, or w = 1/σ²), for a file also column names (and for weights a file).
    ``percent``: the values are percent (for arrays it must be said; for files it is detected and stated).
    ``columns``: for a file only (arrays have none: refused). Arrays and files are read and fitted by the same
    library calls, with the same warnings (a wavelength grid too coarse for the fringes, a value on a bound).
    ``grid``: multi-start points per thickness (0: about one per 10 nm). ``angle_rad`` in radians.

    Returns the CLI's JSON keys: ``names``, ``units``, ``values``, ``sigma``, ``correlation``, ``chi2``,
    ``dof``, ``reduced_chi2``, ``sigma_given``, ``at_bound``, ``starts``, ``evaluations``, ``jacobian``,
    ``fitted``, ``wavelength_nm``, ``measured``, ``read``, ``notes`` (how the uncertainties were found).

    >>> import numpy as np, iridis.thinfilm as tf
    >>> wl = np.linspace(400, 800, 81)
    >>> r = tf.Stack("air | SiO2 150nm | si-green").reflectance(wl)
    >>> out = tf.fit((wl, r), "air | SiO2 {d=120nm:50nm..300nm} | si-green")
    >>> round(float(out["values"][0]), 3)
    150.0
    """
    q = str(quantity)
    angle = float(_angles(_angle(angle_rad, "angle_rad"), "angle_rad"))
    if isinstance(grid, bool) or int(grid) != grid or grid < 0:
        raise ValueError(f"grid {grid!r}: a whole number of starts per thickness ≥ 0 (0: automatic)")
    for name, v in (("from_nm", from_nm), ("to_nm", to_nm)):
        if v is not None:
            _wavelengths(_float(v, name, "a wavelength in nm"), name)
    if sigma is not None and weights is not None:
        raise ValueError("give sigma or weights, not both (weights are 1/σ²)")
    spread = {}
    for name, v in (("sigma", sigma), ("weights", weights)):
        if v is not None:
            spread[name] = str(v) if isinstance(v, str) else repr(_float(v, name, "a number or column names"))
    reading = dict(columns=columns, percent=None if percent is None else flag(percent, "percent"), from_nm=from_nm,
                   to_nm=to_nm, **spread)
    if isinstance(measured, (str, bytes)) or hasattr(measured, "__fspath__"):
        return _native._fit(stack, angle, q, int(grid), path=os.fsdecode(os.fspath(measured)), **reading)
    parts = [np.asarray(m) for m in measured] if isinstance(measured, (tuple, list)) else None
    if parts is None:
        a = np.asarray(measured)
        if a.ndim != 2 or a.shape[1] not in (2, 3):
            raise ValueError(f"measured of shape {a.shape}: give a file path, (wavelengths_nm, values[, sigma]) or an "
                             "array of 2 or 3 columns")
        parts = [a[:, k] for k in range(a.shape[1])]
    if len(parts) not in (2, 3):
        raise ValueError(f"measured has {len(parts)} parts: give (wavelengths_nm, values) or (wavelengths_nm, values, "
                         "sigma)")
    # Read by the library as a file is (percent, the window, σ), but without columns to choose.
    return _native._fit(stack, angle, q, int(grid), wavelengths=np.ascontiguousarray(_wavelengths(parts[0],
                        "wavelengths_nm").ravel()), values=np.ascontiguousarray(_real(parts[1], "values").ravel()),
                        sigma_values=None if len(parts) < 3 else np.ascontiguousarray(_real(parts[2], "sigma").ravel()),
                        **reading)
