"""A drop-in for S. J. Byrnes' ``tmm`` package (0.2.0), computed by iridis.

``import iridis.tmm as tmm`` runs a tmm script unchanged: every public function of ``tmm.tmm_core`` is here with
the same arguments and the same results (the committed fixtures of tools/gen_tmm_api_fixtures.py cover each;
tmm's own ``examples.py`` runs on this module and plots the same numbers). ``coh_tmm``, ``unpolarized_RT`` and
``ellips`` are the Rust core's (``iridis_thinfilm::tmm``); the helpers (``snell``, ``interface_r``, …), the
position-resolved fields and the incoherent bookkeeping of ``inc_tmm`` are written here in NumPy from the same
definitions (Byrnes, arXiv:1603.02720), with the coherent stacks computed by the core. ``coh_tmm_batch`` is new:
one call for arrays of wavelengths and angles, in parallel.

``coh_tmm`` returns a read-only mapping (computed on demand from the core's result) that copies and pickles as
the plain dict tmm returns, so results cross ``multiprocessing``; ``from iridis.tmm.tmm_core import …`` works as
``from tmm.tmm_core import …`` does.

Angles may be complex as in tmm: an absorbing first medium takes the complex ``th_0`` that makes
``n_list[0]·sin(th_0)`` real. Bad input raises :class:`TmmInputError`, a ``ValueError`` that is also an
``AssertionError`` (what tmm's asserts raise), with a message saying what is wrong. Not reproduced: tmm's clamp
of almost opaque layers in ``coh_tmm`` (changes nothing above 1e-30) and its one-time print about it.

Example:
    >>> import numpy as np
    >>> import iridis.tmm as tmm
    >>> d = tmm.coh_tmm('p', [1, 1.38, 1.5], [np.inf, 100, np.inf], 0.3, 550)
    >>> sorted(d)[:5]
    ['R', 'T', 'd_list', 'kz_list', 'lam_vac']
    >>> layer, z = tmm.find_in_structure_with_inf([np.inf, 100, np.inf], 30.0)
    >>> round(float(tmm.position_resolved(layer, z, d)['poyn']), 6) == round(1 - d['R'], 6)   # lossless film
    True
    >>> b = tmm.coh_tmm_batch('s', [1, 1.38, 1.5], [np.inf, 100, np.inf], 0.0, np.linspace(400, 700, 4))
    >>> b['R'].shape
    (4,)
"""
from __future__ import annotations

import cmath
import functools
import sys
from collections.abc import Mapping

import numpy as np

from . import _native
from ._native import CohTmmResult, _check_stack

Mapping.register(CohTmmResult)

EPSILON = sys.float_info.epsilon

# `from tmm.tmm_core import coh_tmm`, tmm's own module path, as `from iridis.tmm.tmm_core import coh_tmm`.
tmm_core = sys.modules[__name__]
sys.modules[__name__ + ".tmm_core"] = tmm_core
inf = np.inf

__all__ = [
    "make_2x2_array", "is_forward_angle", "snell", "list_snell", "interface_r", "interface_t", "R_from_r",
    "T_from_t", "power_entering_from_r", "interface_R", "interface_T", "coh_tmm", "coh_tmm_reverse", "ellips",
    "unpolarized_RT", "position_resolved", "find_in_structure", "find_in_structure_with_inf", "layer_starts",
    "absorp_analytic_fn", "absorp_in_each_layer", "inc_group_layers", "inc_tmm", "inc_absorp_in_each_layer",
    "inc_find_absorp_analytic_fn", "coh_tmm_batch", "CohTmmResult", "TmmInputError",
]


class TmmInputError(ValueError, AssertionError):
    """Input tmm refuses: a ``ValueError`` (iridis' convention for bad values) that is also the
    ``AssertionError`` tmm's own checks raise, so that code written for either catches it."""


def _tmm_errors(native):
    """``native`` with its refusals raised as :class:`TmmInputError`, tmm's ``AssertionError`` too (tmm's own
    ``"Error in n0 or th0!"`` is an assert, and a script written for tmm catches that)."""
    @functools.wraps(native)
    def call(*args, **kwargs):
        try:
            return native(*args, **kwargs)
        except TmmInputError:
            raise
        except ValueError as e:
            raise TmmInputError(str(e)) from None
    return call


coh_tmm = _tmm_errors(_native.coh_tmm)
unpolarized_RT = _tmm_errors(_native.unpolarized_RT)
ellips = _tmm_errors(_native.ellips)
_coh_tmm_batch = _tmm_errors(_native._coh_tmm_batch)


def _pol(pol):
    if pol not in ("s", "p"):
        raise ValueError("Polarization must be 's' or 'p'")
    return pol


# --- small helpers ------------------------------------------------------------------------------------------

def make_2x2_array(a, b, c, d, dtype=float):
    """The 2×2 array ``[[a, b], [c, d]]`` of ``dtype``."""
    return np.array([[a, b], [c, d]], dtype=dtype)


def is_forward_angle(n, theta):
    """Whether a wave at (complex) angle ``theta`` in a medium of index ``n`` is the one travelling forwards,
    from the front of the stack to the back: the one that decays forwards where ``n cos θ`` is complex, the one
    whose flux ``Re(n cos θ)`` points forwards otherwise (Byrnes, arXiv:1603.02720, appendix D). The other is
    at ``π − θ``. Gain (``Re n · Im n < 0``) and waves whose s and p fluxes disagree are refused."""
    n, theta = complex(n), complex(theta)
    if n.real * n.imag < 0:
        raise TmmInputError(
            "For materials with gain, it's ambiguous which beam is incoming vs outgoing. See "
            f"https://arxiv.org/abs/1603.02720 Appendix C.\nn: {n}   angle: {theta}")
    q = n * cmath.cos(theta)
    forward = q.imag > 0 if abs(q.imag) > 100 * EPSILON else q.real > 0
    sign = 1.0 if forward else -1.0
    # Both fluxes (s: Re(n cos θ); p: Re(n cos θ*)) and the decay must point the same way.
    if min(sign * q.imag, sign * q.real, sign * (n * cmath.cos(theta.conjugate())).real) < -100 * EPSILON:
        raise TmmInputError("It's not clear which beam is incoming vs outgoing. Weird index maybe?\n"
                            f"n: {n}   angle: {theta}")
    return bool(forward)


def snell(n_1, n_2, th_1):
    """The (complex) angle in a medium of index ``n_2`` of a wave at ``th_1`` in ``n_1``, by Snell's law on the
    principal branch of arcsin (``numpy.emath.arcsin``: real arguments beyond 1 give complex angles), the
    forward-travelling one (:func:`is_forward_angle`)."""
    th_2 = np.emath.arcsin(n_1 * np.sin(th_1) / n_2)
    return th_2 if is_forward_angle(n_2, th_2) else np.pi - th_2


def list_snell(n_list, th_0):
    """The angle in every medium of ``n_list`` for ``th_0`` in the first; the two semi-infinite media get the
    forward-travelling angle, the layers the principal arcsin (their choice does not change any result)."""
    n = np.asarray(n_list)
    th = np.emath.arcsin(n[0] * np.sin(th_0) / n)
    for end in (0, -1):
        if not is_forward_angle(n[end], th[end]):
            th[end] = np.pi - th[end]
    return th


def interface_r(polarization, n_i, n_f, th_i, th_f):
    """Fresnel reflection amplitude from ``n_i`` at ``th_i`` into ``n_f`` at ``th_f`` (Byrnes eq. 11–12)."""
    ci, cf = np.cos(th_i), np.cos(th_f)
    if _pol(polarization) == "s":
        return (n_i * ci - n_f * cf) / (n_i * ci + n_f * cf)
    return (n_f * ci - n_i * cf) / (n_f * ci + n_i * cf)


def interface_t(polarization, n_i, n_f, th_i, th_f):
    """Fresnel transmission amplitude from ``n_i`` at ``th_i`` into ``n_f`` at ``th_f`` (Byrnes eq. 11–12)."""
    ci, cf = np.cos(th_i), np.cos(th_f)
    if _pol(polarization) == "s":
        return 2 * n_i * ci / (n_i * ci + n_f * cf)
    return 2 * n_i * ci / (n_f * ci + n_i * cf)


def R_from_r(r):
    """Reflected power ``|r|²``."""
    return abs(r) ** 2


def _flux(pol, n, th):
    """The normal flux of a unit wave: ``Re(n cos θ)`` for s, ``Re(n cos θ*)`` for p (Byrnes eq. 21–22)."""
    return (n * np.cos(th)).real if pol == "s" else (n * np.conj(np.cos(th))).real


def T_from_t(pol, t, n_i, n_f, th_i, th_f):
    """Transmitted power from the amplitude ``t``: ``|t|²`` times the ratio of the normal fluxes in the final
    and the incident medium."""
    return abs(t ** 2) * (_flux(_pol(pol), n_f, th_f) / _flux(pol, n_i, th_i))


def power_entering_from_r(pol, r, n_i, th_i):
    """The flux entering the first layer per unit incident flux, from ``r``: ``1 − R`` unless the incident
    medium absorbs (Byrnes sec. 4)."""
    if _pol(pol) == "s":
        q = n_i * np.cos(th_i)
        return (q * (1 + np.conj(r)) * (1 - r)).real / q.real
    q = n_i * np.conj(np.cos(th_i))
    return (q * (1 + r) * (1 - np.conj(r))).real / q.real


def interface_R(polarization, n_i, n_f, th_i, th_f):
    """Reflected power at one interface."""
    return R_from_r(interface_r(polarization, n_i, n_f, th_i, th_f))


def interface_T(polarization, n_i, n_f, th_i, th_f):
    """Transmitted power at one interface."""
    return T_from_t(polarization, interface_t(polarization, n_i, n_f, th_i, th_f), n_i, n_f, th_i, th_f)


# --- coherent stacks ----------------------------------------------------------------------------------------

def coh_tmm_reverse(pol, n_list, d_list, th_0, lam_vac):
    """``coh_tmm`` of the stack turned around: light from the last medium, at the angle Snell's law gives there
    for ``th_0`` in the first."""
    n = np.asarray(n_list)
    d = np.asarray(d_list, dtype=float)
    return coh_tmm(pol, n[::-1], d[::-1], snell(n[0], n[-1], th_0), lam_vac)


def position_resolved(layer, distance, coh_tmm_data):
    """The normal Poynting flux ``poyn``, the absorbed power density ``absor`` and the field ``Ex``, ``Ey``,
    ``Ez`` (incident |E| = 1; z normal, light in the x–z plane) at ``distance`` into medium ``layer`` (as
    :func:`find_in_structure_with_inf` gives them) of a :func:`coh_tmm` result."""
    data = coh_tmm_data
    if layer > 0:
        v, w = data["vw_list"][layer]
    else:
        v, w = 1, data["r"]
    d_here = data["d_list"][layer]
    if not ((layer >= 1 and 0 <= distance <= d_here) or (layer == 0 and distance <= 0)):
        raise TmmInputError(f"position ({layer}, {distance}) is outside the stack: medium 0 takes distance ≤ 0, "
                            f"medium {layer} takes 0 ≤ distance ≤ {d_here} (find_in_structure_with_inf gives both)")
    kz, th, n = data["kz_list"][layer], data["th_list"][layer], data["n_list"][layer]
    n_0, th_0, pol = data["n_list"][0], data["th_0"], data["pol"]
    forward = v * np.exp(1j * kz * distance)
    backward = w * np.exp(-1j * kz * distance)
    plus, minus = forward + backward, forward - backward
    if pol == "s":
        q, q0 = n * np.cos(th), (n_0 * np.cos(th_0)).real
        poyn = (q * np.conj(plus) * minus).real / q0
        absor = (q * kz * abs(plus) ** 2).imag / q0
        return {"poyn": poyn, "absor": absor, "Ex": 0, "Ey": plus, "Ez": 0}
    q, q0 = n * np.conj(np.cos(th)), (n_0 * np.conj(np.cos(th_0))).real
    poyn = (q * plus * np.conj(minus)).real / q0
    absor = (q * (kz * abs(minus) ** 2 - np.conj(kz) * abs(plus) ** 2)).imag / q0
    return {"poyn": poyn, "absor": absor, "Ex": minus * np.cos(th), "Ey": 0, "Ez": -plus * np.sin(th)}


def find_in_structure(d_list, distance):
    """``[layer, z]`` for a depth ``distance`` from the front of a stack of finite layers ``d_list``: the layer it
    falls in (``len(d_list)`` beyond the last, ``-1`` in front) and the depth into that layer."""
    if sum(d_list) == np.inf:
        raise ValueError("This function expects finite arguments")
    if distance < 0:
        return [-1, distance]
    layer = 0
    for d in d_list:
        if distance < d:
            break
        distance -= d
        layer += 1
    return [layer, distance]


def find_in_structure_with_inf(d_list, distance):
    """:func:`find_in_structure` for tmm's ``d_list`` (``inf`` at both ends; depth from the start of medium 1):
    ``[0, distance]`` in front of the stack."""
    if distance < 0:
        return [0, distance]
    layer, z = find_in_structure(d_list[1:-1], distance)
    return [layer + 1, z]


def layer_starts(d_list):
    """The depth at which each medium of tmm's ``d_list`` starts (``-inf`` for the first, 0 for medium 1)."""
    d = np.asarray(d_list, dtype=float)
    starts = np.empty(len(d))
    starts[0] = -np.inf
    starts[1:] = np.concatenate(([0.0], np.cumsum(d[1:-1])))
    return starts


class absorp_analytic_fn:  # noqa: N801 (tmm's name)
    """The absorbed power density in one layer as a function of depth ``z`` (0 at the layer's top), as the
    fraction of the incident power per unit length: ``A1 e^{a1 z} + A2 e^{−a1 z} + A3 e^{i a3 z} + c.c.``
    with real ``A1``, ``A2``, ``a1 = 2 Im k_z``, ``a3 = 2 Re k_z``, complex ``A3``, and the thickness ``d``."""

    def fill_in(self, coh_tmm_data, layer):
        """The function of medium ``layer`` (negative counts from the end) of a :func:`coh_tmm` result."""
        data = coh_tmm_data
        v, w = data["vw_list"][layer]
        kz, n, th = data["kz_list"][layer], data["n_list"][layer], data["th_list"][layer]
        n_0, th_0 = data["n_list"][0], data["th_0"]
        self.d = data["d_list"][layer]
        self.a1, self.a3 = 2 * kz.imag, 2 * kz.real
        if data["pol"] == "s":
            scale = (n * np.cos(th) * kz).imag / (n_0 * np.cos(th_0)).real
            self.A1, self.A2, self.A3 = scale * abs(w) ** 2, scale * abs(v) ** 2, scale * v * np.conj(w)
        else:
            q0 = (n_0 * np.conj(np.cos(th_0))).real
            q = n * np.cos(np.conj(th))
            scale = 2 * kz.imag * q.real / q0
            self.A1, self.A2 = scale * abs(w) ** 2, scale * abs(v) ** 2
            self.A3 = v * np.conj(w) * (-2 * kz.real * q.imag / q0)
        return self

    def copy(self):
        """An independent copy."""
        other = absorp_analytic_fn()
        other.A1, other.A2, other.A3, other.a1, other.a3, other.d = (
            self.A1, self.A2, self.A3, self.a1, self.a3, self.d)
        return other

    def run(self, z):
        """The absorbed power density at depth ``z`` (array or number)."""
        wave = self.A3 * np.exp(1j * self.a3 * z)
        return self.A1 * np.exp(self.a1 * z) + self.A2 * np.exp(-self.a1 * z) + wave + np.conj(wave)

    def flip(self):
        """Turns the function around in the layer: afterwards ``run(z)`` gives the old ``run(d − z)``."""
        self.A1, self.A2 = self.A2 * np.exp(-self.a1 * self.d), self.A1 * np.exp(self.a1 * self.d)
        self.A3 = np.conj(self.A3 * np.exp(1j * self.a3 * self.d))
        return self

    def scale(self, factor):
        """Multiplies the density by ``factor``."""
        self.A1, self.A2, self.A3 = self.A1 * factor, self.A2 * factor, self.A3 * factor
        return self

    def add(self, b):
        """Adds another function of the same ``a1`` and ``a3`` (the same layer)."""
        if b.a1 != self.a1 or b.a3 != self.a3:
            raise ValueError("Incompatible absorption analytical functions!")
        self.A1, self.A2, self.A3 = self.A1 + b.A1, self.A2 + b.A2, self.A3 + b.A3
        return self


def absorp_in_each_layer(coh_tmm_data):
    """The fraction of the incident power ending in each medium of a :func:`coh_tmm` result: reflected (the
    first entry), absorbed in each layer (the flux entering it minus the flux leaving it), transmitted (the
    last). The entries add up to 1."""
    data = coh_tmm_data
    count = len(data["d_list"])
    entering = np.empty(count)
    entering[0], entering[1], entering[-1] = 1.0, data["power_entering"], data["T"]
    for i in range(2, count - 1):
        entering[i] = position_resolved(i, 0, data)["poyn"]
    out = np.empty(count)
    out[:-1] = entering[:-1] - entering[1:]
    out[-1] = entering[-1]
    return out


# --- incoherent and partly coherent stacks ------------------------------------------------------------------

def inc_group_layers(n_list, d_list, c_list):
    """How the media of a partly coherent stack group (``c_list``: ``'i'`` incoherent, ``'c'`` coherent, with
    ``'i'`` at both ends): runs of coherent layers form *stacks*, each between two incoherent media. Returns the
    index maps of tmm: ``stack_d_list``, ``stack_n_list`` (each stack with its two incoherent neighbours),
    ``all_from_inc``, ``inc_from_all`` (``nan`` for coherent media), ``all_from_stack``, ``stack_from_all``
    (``[stack, index within it]``, ``nan`` for incoherent media), ``inc_from_stack``, ``stack_from_inc``
    (``nan`` where an incoherent medium does not follow a stack), ``num_stacks``, ``num_inc_layers``,
    ``num_layers``."""
    n = np.asarray(n_list)
    d = np.asarray(d_list, dtype=float)
    if n.ndim != 1 or d.ndim != 1:
        raise ValueError("Problem with n_list or d_list!")
    if d[0] != np.inf or d[-1] != np.inf:
        raise ValueError("d_list must start and end with inf!")
    if c_list[0] != "i" or c_list[-1] != "i":
        raise ValueError('c_list should start and end with "i"')
    if not n.size == d.size == len(c_list):
        raise ValueError("List sizes do not match!")
    out = {k: [] for k in ("stack_d_list", "stack_n_list", "all_from_inc", "inc_from_all", "all_from_stack",
                           "stack_from_all", "inc_from_stack", "stack_from_inc")}
    current = None  # the stack being gathered: (thicknesses, indices)
    for j, kind in enumerate(c_list):
        if kind == "c":
            out["inc_from_all"].append(np.nan)
            if current is None:
                stack = len(out["all_from_stack"])
                current = ([np.inf, d[j]], [n[j - 1], n[j]])
                out["all_from_stack"].append([j - 1, j])
                out["inc_from_stack"].append(len(out["all_from_inc"]) - 1)
            else:
                current[0].append(d[j])
                current[1].append(n[j])
                out["all_from_stack"][-1].append(j)
            out["stack_from_all"].append([len(out["all_from_stack"]) - 1, len(current[0]) - 1])
        elif kind == "i":
            out["stack_from_all"].append(np.nan)
            out["inc_from_all"].append(len(out["all_from_inc"]))
            out["all_from_inc"].append(j)
            if current is None:
                out["stack_from_inc"].append(np.nan)
            else:
                out["stack_from_inc"].append(len(out["all_from_stack"]) - 1)
                out["stack_d_list"].append(current[0] + [np.inf])
                out["stack_n_list"].append(current[1] + [n[j]])
                out["all_from_stack"][-1].append(j)
                current = None
        else:
            raise ValueError("Error: c_list entries must be 'i' or 'c'!")
    out["num_stacks"] = len(out["all_from_stack"])
    out["num_inc_layers"] = len(out["all_from_inc"])
    out["num_layers"] = len(n)
    return out


def inc_tmm(pol, n_list, d_list, c_list, th_0, lam_vac):
    """Incoherent or partly coherent stacks (``c_list``: ``'i'``/``'c'`` per medium), as ``tmm.inc_tmm``: the
    coherent stacks by :func:`coh_tmm` both ways, the incoherent media by the transfer matrices of intensities
    (Byrnes, arXiv:1603.02720, sec. 6). Returns tmm's dictionary: ``R``, ``T``, ``VW_list`` (forward and
    backward intensities at the start of each incoherent medium), ``coh_tmm_data_list``,
    ``coh_tmm_bdata_list``, ``stackFB_list`` (light arriving at each stack from the front and from the back),
    ``power_entering_list``, and everything :func:`inc_group_layers` returns."""
    try:  # coh_tmm's checks on the whole stack: its incoherent media reach no coherent calculation
        _check_stack(n_list, d_list, th_0, lam_vac)
    except ValueError as e:
        raise TmmInputError(str(e)) from None
    n = np.asarray(n_list)
    d = np.asarray(d_list, dtype=float)
    if np.real_if_close(n[0] * np.sin(th_0)).imag != 0:
        raise TmmInputError("Error in n0 or th0! n_list[0]·sin(th_0) must be real")
    groups = inc_group_layers(n, d, c_list)
    inc_all, stacks = groups["all_from_inc"], groups["all_from_stack"]
    stack_from_inc, inc_from_stack = groups["stack_from_inc"], groups["inc_from_stack"]
    n_inc = groups["num_inc_layers"]
    th = list_snell(n, th_0)
    fwd, bwd = [], []
    for s, members in enumerate(stacks):
        args = (pol, groups["stack_n_list"][s], groups["stack_d_list"][s], th[members[0]], lam_vac)
        fwd.append(coh_tmm(*args))
        bwd.append(coh_tmm_reverse(*args))
    # One pass through each finite incoherent medium keeps exp(−4π d Im(n cos θ)/λ) of the intensity (at least
    # 1e-30, as tmm, so that the matrices stay invertible).
    passes = np.zeros(n_inc)
    for k in range(1, n_inc - 1):
        j = inc_all[k]
        passes[k] = max(np.exp(-4 * np.pi * d[j] * (n[j] * np.cos(th[j])).imag / lam_vac), 1e-30)
    # Power reflection and transmission between neighbouring incoherent media, both ways: one interface, or the
    # coherent stack between them.
    big_r, big_t = np.zeros((n_inc, n_inc)), np.zeros((n_inc, n_inc))
    for k in range(n_inc - 1):
        s = stack_from_inc[k + 1]
        if np.isnan(s):
            j = inc_all[k]
            big_r[k, k + 1] = interface_R(pol, n[j], n[j + 1], th[j], th[j + 1])
            big_t[k, k + 1] = interface_T(pol, n[j], n[j + 1], th[j], th[j + 1])
            big_r[k + 1, k] = interface_R(pol, n[j + 1], n[j], th[j + 1], th[j])
            big_t[k + 1, k] = interface_T(pol, n[j + 1], n[j], th[j + 1], th[j])
        else:
            big_r[k, k + 1], big_t[k, k + 1] = fwd[s]["R"], fwd[s]["T"]
            big_r[k + 1, k], big_t[k + 1, k] = bwd[s]["R"], bwd[s]["T"]
        # Where nothing crosses (total internal reflection: exactly 0 here, rounding noise of ~1e-17 in tmm), the
        # matrices below would divide by 0: 1e-30 stands in, as for the passes.
        big_t[k, k + 1], big_t[k + 1, k] = max(big_t[k, k + 1], 1e-30), max(big_t[k + 1, k], 1e-30)

    def crossing(k):
        """The intensity transfer matrix across the boundary from incoherent medium k to k + 1."""
        return np.array([[1.0, -big_r[k + 1, k]],
                         [big_r[k, k + 1], big_t[k + 1, k] * big_t[k, k + 1] - big_r[k + 1, k] * big_r[k, k + 1]]]
                        ) / big_t[k, k + 1]

    matrices = [np.nan]
    total = crossing(0)
    for k in range(1, n_inc - 1):
        m = np.diag([1 / passes[k], passes[k]]) @ crossing(k)
        matrices.append(m)
        total = total @ m
    T = 1 / total[0, 0]
    R = total[1, 0] / total[0, 0]
    vw = np.zeros((n_inc, 2))
    vw[0] = np.nan
    vw[-1] = [T, 0.0]
    here = np.array([T, 0.0])
    for k in range(n_inc - 2, 0, -1):
        here = matrices[k] @ here
        vw[k] = here
    fb = []
    for s, k in enumerate(inc_from_stack):
        forward = 1 if k == 0 else vw[k][0] * passes[k]
        fb.append([forward, vw[k + 1][1]])
    entering = [1]
    for k in range(1, n_inc):
        s = stack_from_inc[k]
        if not np.isnan(s):
            entering.append(fb[s][0] * fwd[s]["T"] - fb[s][1] * bwd[s]["power_entering"])
        elif k == 1:
            entering.append(big_t[0, 1] - vw[1][1] * big_t[1, 0])
        else:
            entering.append(vw[k - 1][0] * passes[k - 1] * big_t[k - 1, k] - vw[k][1] * big_t[k, k - 1])
    out = {"T": T, "R": R, "VW_list": vw, "coh_tmm_data_list": fwd, "coh_tmm_bdata_list": bwd,
           "stackFB_list": fb, "power_entering_list": entering}
    out.update(groups)
    return out


def inc_absorp_in_each_layer(inc_data):
    """The fraction of the incident power ending in each medium of an :func:`inc_tmm` result (reflected first,
    transmitted last; they add up to 1): per incoherent medium what enters minus what leaves, per coherent
    layer its absorption lit from the front and from the back."""
    stack_from_inc = inc_data["stack_from_inc"]
    entering = inc_data["power_entering_list"]
    fb = inc_data["stackFB_list"]
    out = []
    for k in range(len(entering) - 1):
        s = stack_from_inc[k + 1]
        if np.isnan(s):
            out.append(entering[k] - entering[k + 1])
            continue
        f, b = fb[s]
        data, bdata = inc_data["coh_tmm_data_list"][s], inc_data["coh_tmm_bdata_list"][s]
        out.append(entering[k] - (f * data["power_entering"] - b * bdata["T"]))
        out.extend(f * absorp_in_each_layer(data)[1:-1] + b * absorp_in_each_layer(bdata)[-2:0:-1])
    out.append(inc_data["T"])
    return out


def inc_find_absorp_analytic_fn(layer, inc_data):
    """The :class:`absorp_analytic_fn` of a coherent ``layer`` inside a partly coherent stack: the light
    arriving at its stack from the front and from the back, each through the stack's coherent solution."""
    where = inc_data["stack_from_all"][layer]
    if np.any(np.isnan(where)):
        raise ValueError("layer must be coherent for this function!")
    s, within = where
    f, b = inc_data["stackFB_list"][s]
    front = absorp_analytic_fn().fill_in(inc_data["coh_tmm_data_list"][s], within).scale(f)
    back = absorp_analytic_fn().fill_in(inc_data["coh_tmm_bdata_list"][s], -1 - within).scale(b).flip()
    return front.add(back)


# --- arrays ---------------------------------------------------------------------------------------------------

def coh_tmm_batch(pol, n_list, d_list, th_0, lam_vac):
    """``coh_tmm`` over arrays: ``th_0`` and ``lam_vac`` broadcast together to a shape S (numpy rules).

    ``n_list`` is 1-D (one index per medium, the same everywhere) or has shape ``(len(d_list),) + S``
    (dispersive media: one index per medium and point). Returns a dict of arrays of shape S: ``r``, ``t``
    (complex), ``R``, ``T``, ``power_entering``, with coh_tmm's meanings. Computed in parallel with the GIL
    released; with constant indices four points at a time go through one vectorised recurrence.

    >>> import numpy as np, iridis.tmm as tmm
    >>> lam = np.linspace(400, 700, 301)[:, None]
    >>> th = np.radians(np.arange(0, 90, 10))[None, :]
    >>> out = tmm.coh_tmm_batch('p', [1, 2.2, 1.5], [np.inf, 80, np.inf], th, lam)
    >>> out['R'].shape
    (301, 9)
    """
    th = np.asarray(th_0, dtype=np.float64)
    lam = np.asarray(lam_vac, dtype=np.float64)
    try:
        th, lam = np.broadcast_arrays(th, lam)
    except ValueError:
        raise ValueError(f"th_0 of shape {np.shape(th_0)} and lam_vac of shape {np.shape(lam_vac)} do not broadcast") from None
    shape = th.shape
    n = np.asarray(n_list)
    if n.dtype.kind not in "biufc":
        raise TypeError(f"n_list must hold numbers, got dtype {n.dtype}")
    n = n.astype(np.complex128, copy=False)
    d = np.asarray(d_list, dtype=np.float64)
    if d.ndim != 1:
        raise ValueError(f"d_list must be 1-D, got shape {d.shape}")
    if n.ndim == 1:
        native_n = np.ascontiguousarray(n)
    else:
        if n.shape != (d.size,) + shape:
            raise ValueError(
                f"n_list of shape {n.shape}: give one index per medium ({d.size},) or per medium and point "
                f"{(d.size,) + shape}"
            )
        native_n = np.ascontiguousarray(n.reshape(d.size, -1))
    out = _coh_tmm_batch(pol, native_n, np.ascontiguousarray(d), np.ascontiguousarray(th.ravel()),
                         np.ascontiguousarray(lam.ravel()))
    return {k: v.reshape(shape) for k, v in out.items()}
