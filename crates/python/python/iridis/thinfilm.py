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

import numpy as np

from . import _native
from .color import xyz_to_hex, xyz_to_lab, xyz_to_srgb, white_point

__all__ = ["Stack", "RoughFilm", "colors_of_stacks", "material_index", "materials"]

_POL = {"s": "s", "p": "p", "unpolarized": "avg", "unpolarised": "avg", "avg": "avg", "average": "avg"}


def _real(x, name):
    a = np.asarray(x)
    if a.dtype.kind not in "biuf":
        raise TypeError(f"{name} must hold real numbers, got dtype {a.dtype}")
    return a.astype(np.float64, copy=False)


def _broadcast(*pairs):
    arrays = [_real(x, n) for x, n in pairs]
    try:
        out = np.broadcast_arrays(*arrays)
    except ValueError:
        shapes = ", ".join(f"{n} {a.shape}" for a, (_, n) in zip(arrays, pairs))
        raise ValueError(f"the arrays do not broadcast together: {shapes}") from None
    return [np.ascontiguousarray(a.ravel()) for a in out], out[0].shape


def material_index(name, wavelengths_nm):
    """``n + iκ`` of a material (library name such as ``"Si"``, ``"n=1.38"``, ``"file:PATH"``) at each
    wavelength (nm)."""
    wl = _real(wavelengths_nm, "wavelengths_nm")
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
    d = _real(thicknesses_nm, "thicknesses_nm")
    if n.ndim != 2 or d.ndim != 2:
        raise ValueError(f"indices and thicknesses_nm must be 2-D (one row per stack), got {n.shape} and {d.shape}")
    grid = np.arange(380.0, 780.0 + 1e-9, 5.0) if grid_nm is None else _real(grid_nm, "grid_nm")
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
    def from_lists(cls, indices, thicknesses_nm, incoherent=None):
        """From complex indices (incident, layers…, substrate) and one thickness (nm) per layer;
        ``incoherent``: one bool per layer."""
        return cls(_native._Stack.from_lists(indices, thicknesses_nm,
                                             None if incoherent is None else [bool(x) for x in incoherent]))

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
        wl = _real(wavelengths_nm, "wavelengths_nm")
        out = self._s.indices(np.ascontiguousarray(np.atleast_1d(wl).ravel()))
        return out.reshape((out.shape[0],) + wl.shape)

    def rta(self, wavelengths_nm, angles_rad=0.0, offsets_nm=0.0, polarization="unpolarized"):
        """R, T and A = 1 − R − T at every point of the broadcast of wavelengths × angles × thickness
        offsets (every layer's thickness plus the offset, Sussenbach eq. 4.3). ``polarization``: ``"s"``,
        ``"p"`` or ``"unpolarized"``. Returns a dict of arrays of the broadcast shape."""
        pol = _POL.get(str(polarization).lower())
        if pol is None:
            raise ValueError(f"polarization {polarization!r}: use 's', 'p' or 'unpolarized'")
        (w, a, o), shape = _broadcast((wavelengths_nm, "wavelengths_nm"), (angles_rad, "angles_rad"),
                                      (offsets_nm, "offsets_nm"))
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
        bound of 1e-6 of the lobe's peak needs); ``diffuse_transport``: ``"reciprocal"`` (default) or
        ``"thesis"`` (eq. 3.18–3.19 as printed, for comparison only)."""
        return RoughFilm(self, roughness_nm, correlation_nm, d_iterations, diffuse_transport)

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
        grid = np.arange(380.0, 780.0 + 1e-9, 5.0) if grid_nm is None else _real(grid_nm, "grid_nm")
        (a, o), shape = _broadcast((angles_rad, "angles_rad"), (offsets_nm, "offsets_nm"))
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
    return _float(x, name, "an angle in radians")


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
        wl = _real(wavelengths_nm, "wavelengths_nm")
        if wl.ndim != 1 or wl.size == 0:
            raise ValueError(f"wavelengths_nm must be a non-empty 1-D array, got shape {wl.shape}")
        view = _angle(view_rad, "view_rad")
        light = view if light_rad is None else _angle(light_rad, "light_rad")
        return self.stack._s._rough_spectrum(*self._args(), np.ascontiguousarray(wl), view, light,
                                             _angle(azimuth_rad, "azimuth_rad"))

    def color(self, view_rad=0.0, light_rad=None, azimuth_rad=np.pi, illuminant="D65", observer="1931",
              grid_nm=None):
        """The colours, as ``iridis thinfilm color --roughness … --json``: XYZ of the smooth film's
        ``reflected`` and ``transmitted`` light, of the rough film's ``specular`` part and of its ``diffuse``
        part (``π k_d``: Y = 1 is a white Lambertian surface under the same light), each with ``*_lab``,
        ``*_srgb`` and ``*_hex``. Default grid 380–780 nm in 5 nm steps."""
        grid = np.arange(380.0, 780.0 + 1e-9, 5.0) if grid_nm is None else _real(grid_nm, "grid_nm")
        view = _angle(view_rad, "view_rad")
        light = view if light_rad is None else _angle(light_rad, "light_rad")
        xyz = self.stack._s._rough_color(*self._args(), view, light, _angle(azimuth_rad, "azimuth_rad"),
                                         np.ascontiguousarray(grid.ravel()), illuminant, observer)
        white = white_point(illuminant, observer)
        out = {"reflected": xyz[0], "transmitted": xyz[1], "specular": xyz[2], "diffuse": xyz[3]}
        for k, v in list(out.items()):
            out[k + "_lab"] = xyz_to_lab(v, white)
            out[k + "_srgb"] = xyz_to_srgb(v)
            out[k + "_hex"] = xyz_to_hex(v)
        return out
