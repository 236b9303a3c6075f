"""Thin films as the command line computes them: ``iridis thinfilm spectrum``, ``table``, ``color``, ``chart``,
``materials``, ``bench``, ``profile`` and ``fit`` as functions of the same names calling the same library
functions (``iridis_api::film``, ``film_chart``, ``film_fit``, ``film_bench``, ``rough``), so the numbers and
the text are the CLI's.

Each returns an :class:`Answer`: the dict the command prints with ``--json`` (for ``table`` and ``chart``, which
print CSV, the CSV's columns as arrays), with ``.text`` (what the command prints without ``--json``), ``.csv``
and, with ``plot=True``, ``.image`` (the plot as an RGB array). Stacks are written as on the command line
(``"air | water 348nm | air"``); angles are in radians, wavelengths in nm; ranges (``angles``, ``thickness``)
are the CLI's ``FROM:TO:STEP`` with units. ``roughness_nm`` and ``correlation_nm`` switch spectrum, table,
color, chart and bench to the rough-substrate (LSRS) model, as ``--roughness``/``--correlation`` do.

Example:
    >>> import iridis.film as film
    >>> s = film.spectrum("air | water 348nm | air", from_nm=550, to_nm=560, step_nm=10)
    >>> round(s["R"][0], 4)
    0.0556
    >>> print(film.color("air | water 348nm | air").text.splitlines()[2])
    reflected
"""
from __future__ import annotations

from . import _native
from ._answer import Answer, answer, count, file_path, flag, keywords
from .thinfilm import _polar

__all__ = ["Answer", "spectrum", "table", "color", "chart", "materials", "bench", "profile", "fit"]


def _rough(roughness_nm, correlation_nm, d_iterations, diffuse_transport):
    # None (not given) passes through: the light's and the series' keywords without a roughness raise.
    return dict(roughness_nm=_opt_float(roughness_nm), correlation_nm=_opt_float(correlation_nm),
                d_iterations=None if d_iterations is None else count(d_iterations, "d_iterations"),
                diffuse_transport=None if diffuse_transport is None else str(diffuse_transport))


def _opt_float(x):
    return None if x is None else float(x)


def _view(angle_rad):
    """The angle of incidence (or view), radians in 0…π/2; degrees by mistake are named."""
    return _polar(angle_rad, "angle_rad")


def _light(light_angle_rad):
    return None if light_angle_rad is None else _polar(light_angle_rad, "light_angle_rad")


@keywords
def spectrum(stack, angle_rad=0.0, from_nm=380.0, to_nm=780.0, step_nm=5.0, polarization="avg", *, plot=False,
             roughness_nm=None, correlation_nm=None, light_angle_rad=None, azimuth_rad=None, d_iterations=None,
             diffuse_transport=None):
    """``iridis thinfilm spectrum``: R, T, A (of ``polarization``: avg, s or p), Rs, Rp, Ts, Tp, ψ and Δ
    (degrees) against wavelength; with a rough substrate the smooth R, specular ``k_r`` and diffuse ``k_d``
    (sr⁻¹) at the view ``angle_rad`` and light ``light_angle_rad``. ``.spectra_csv``: R and T in pavo's layout."""
    return answer(_native._film_spectrum(str(stack), _view(angle_rad), float(from_nm), float(to_nm), float(step_nm),
                                         str(polarization), flag(plot, "plot"),
                                         **_rough(roughness_nm, correlation_nm, d_iterations, diffuse_transport),
                                         light_rad=_light(light_angle_rad),
                                         azimuth_rad=_opt_float(azimuth_rad)))


@keywords
def table(stack, angles="1deg:90deg:1deg", from_nm=380.0, to_nm=780.0, step_nm=5.0, *, plot=False, scale=None,
          roughness_nm=None, correlation_nm=None, light_angles=None, azimuth_rad=None, d_iterations=None,
          diffuse_transport=None):
    """``iridis thinfilm table``: the angle × wavelength table (Sussenbach Figure 3.8) as columns angle_deg,
    wavelength_nm, R, T, A, Rs, Rp, Ts, Tp, psi_deg, delta_deg; with a rough substrate Algorithm 2's view ×
    light × wavelength table (``light_angles`` default: ``angles``). ``plot``: the map of R (``scale``: auto,
    linear or log; without ``plot`` it raises) or of π·k_d. The rough substrate's keywords (``light_angles``,
    ``azimuth_rad``, ``d_iterations``, ``diffuse_transport``) without ``roughness_nm`` raise ValueError, here
    and in spectrum, color, chart and bench: they would be ignored."""
    return answer(_native._film_table(str(stack), str(angles), float(from_nm), float(to_nm), float(step_nm),
                                      flag(plot, "plot"), None if scale is None else str(scale),
                                      **_rough(roughness_nm, correlation_nm, d_iterations, diffuse_transport),
                                      light_angles=light_angles, azimuth_rad=_opt_float(azimuth_rad)), table=True)


@keywords
def color(stack, angle_rad=0.0, illuminant="d65", observer="1931", polarization="avg", from_nm=380.0, to_nm=780.0,
          step_nm=5.0, *, visual=None, roughness_nm=None, correlation_nm=None, light_angle_rad=None,
          azimuth_rad=None, d_iterations=None, diffuse_transport=None):
    """``iridis thinfilm color``: the reflected and transmitted colour (XYZ, xyY, Lab, sRGB, hex), the specular
    and diffuse parts (rough substrate), and with ``visual`` (a system of ``iridis.vision``) how an animal sees
    the reflected and transmitted light."""
    return answer(_native._film_color(str(stack), _view(angle_rad), str(polarization), float(from_nm), float(to_nm),
                                      float(step_nm), str(illuminant), str(observer), visual=visual,
                                      **_rough(roughness_nm, correlation_nm, d_iterations, diffuse_transport),
                                      light_rad=_light(light_angle_rad),
                                      azimuth_rad=_opt_float(azimuth_rad)))


@keywords
def chart(stack, thickness="0nm:2000nm:2nm", angle_rad=0.0, illuminant="d65", exposure=None, from_nm=380.0,
          to_nm=780.0, step_nm=5.0, *, roughness_nm=None, correlation_nm=None, light_angle_rad=None,
          azimuth_rad=None, d_iterations=None, diffuse_transport=None):
    """``iridis thinfilm chart``: the soap-film colour chart (Sussenbach Figure 5.11) of the layer written
    ``{d}``: the CSV's columns (thickness_nm, R_X … R_hex, R_hex_exposure_RU (the exposure the hex is shown at), T_X …
    T_hex_exposure_RU; S_… and D_… with a rough substrate), ``.image`` the
    chart, ``.exposure`` the top band's exposure (RU) and ``.summary`` what was drawn."""
    return answer(_native._film_chart(str(stack), str(thickness), _view(angle_rad), str(illuminant),
                                      None if exposure is None else float(exposure), float(from_nm), float(to_nm),
                                      float(step_nm),
                                      **_rough(roughness_nm, correlation_nm, d_iterations, diffuse_transport),
                                      light_rad=_light(light_angle_rad),
                                      azimuth_rad=_opt_float(azimuth_rad)), table=True)


@keywords
def materials(at_nm=None):
    """``iridis thinfilm materials``: the built-in materials, their sources, ranges and (``at_nm``) index."""
    return answer(_native._film_materials(None if at_nm is None else float(at_nm)))


@keywords
def bench(seconds=1.0, no_python=False, *, roughness_nm=None, correlation_nm=None, azimuth_rad=None,
          d_iterations=None, diffuse_transport=None):
    """``iridis thinfilm bench``: (λ, θ) evaluations per second against Python's tmm (spawned as ``python3``
    unless ``no_python``), the fit of tools/fit_scipy_compare.py and a batch of 10⁶ points timed (below
    ``seconds=1`` that share of them, at least 10⁴); with a rough substrate the LSRS table of Listing 3.6
    (shared generation against direct evaluation)."""
    return answer(_native._film_bench(float(seconds), flag(no_python, "no_python"),
                                      **_rough(roughness_nm, correlation_nm, d_iterations, diffuse_transport),
                                      azimuth_rad=_opt_float(azimuth_rad)))


@keywords
def profile(stack, wavelength_nm, angle_rad=0.0, polarization="avg", points=400, depth=None, *, plot=False):
    """``iridis thinfilm profile``: where the light goes — R, T, absorption per layer and in the substrate, the
    energy balance, and the depth profile (|E|², absorbed power per nm, flux) over ``depth`` (``"FROM:TO"``
    with units, below the first interface; default 100 nm above the stack to 100 nm into the substrate)."""
    return answer(_native._film_profile(str(stack), float(wavelength_nm), _view(angle_rad), str(polarization),
                                        count(points, "points"), None if depth is None else str(depth),
                                        flag(plot, "plot")))


@keywords
def fit(measured, stack, angle_rad=0.0, quantity="R", *, sigma=None, weights=None, grid=0, columns=None,
        percent=None, from_nm=None, to_nm=None, plot=False):
    """``iridis thinfilm fit``: fits the free parameters ``{NAME=START:LOW..HIGH}`` of ``stack`` to the
    spectrum in the file ``measured`` (read as the CLI reads it); ``.csv`` the fitted curve. Arrays
    ``(wavelengths_nm, values[, sigma])`` are ``iridis.thinfilm.fit``'s (the same library calls)."""
    measured = file_path(measured, "iridis.film.fit", "iridis.thinfilm.fit((wavelengths_nm, values[, sigma]), stack)")
    return answer(_native._film_fit(measured, str(stack), _view(angle_rad), str(quantity), count(grid, "grid"),
                                    flag(plot, "plot"), sigma=None if sigma is None else str(sigma),
                                    weights=None if weights is None else str(weights), columns=columns,
                                    percent=None if percent is None else flag(percent, "percent"),
                                    from_nm=None if from_nm is None else float(from_nm),
                                    to_nm=None if to_nm is None else float(to_nm)))
