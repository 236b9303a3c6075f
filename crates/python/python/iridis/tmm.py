"""A drop-in for S. J. Byrnes' ``tmm`` package, computed by iridis.

``import iridis.tmm as tmm`` runs an existing tmm script unchanged: ``coh_tmm``, ``unpolarized_RT``,
``ellips``, ``inc_tmm``, ``inc_absorp_in_each_layer`` and ``absorp_in_each_layer`` take the same arguments and
return the same keys and numbers (to 1e-9 on the 1184-case fixture of tools/gen_thinfilm_fixtures.py).
``coh_tmm_batch`` is new: one call for arrays of wavelengths and angles, in parallel.

Differences, all raised as ValueError with a message rather than answered: an absorbing incident medium
(tmm accepts it with a complex angle), gain (Im n < 0). tmm's clamp of almost opaque layers
(transmission below 1e-30) is not reproduced.

Example:
    >>> import numpy as np
    >>> import iridis.tmm as tmm
    >>> d = tmm.coh_tmm('p', [1, 1.38, 1.5], [np.inf, 100, np.inf], 0.3, 550)
    >>> sorted(d)[:5]
    ['R', 'T', 'd_list', 'kz_list', 'lam_vac']
    >>> b = tmm.coh_tmm_batch('s', [1, 1.38, 1.5], [np.inf, 100, np.inf], 0.0, np.linspace(400, 700, 4))
    >>> b['R'].shape
    (4,)
"""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ._native import CohTmmResult, _coh_tmm_batch, coh_tmm, ellips, inc_tmm, unpolarized_RT

Mapping.register(CohTmmResult)

__all__ = [
    "coh_tmm",
    "coh_tmm_batch",
    "unpolarized_RT",
    "ellips",
    "inc_tmm",
    "inc_absorp_in_each_layer",
    "absorp_in_each_layer",
    "CohTmmResult",
]


def coh_tmm_batch(pol, n_list, d_list, th_0, lam_vac):
    """``coh_tmm`` over arrays: ``th_0`` and ``lam_vac`` broadcast together to a shape S (numpy rules).

    ``n_list`` is 1-D (one index per medium, the same everywhere) or has shape ``(len(d_list),) + S``
    (dispersive media: one index per medium and point). Returns a dict of arrays of shape S: ``r``, ``t``
    (complex), ``R``, ``T``, ``power_entering``, with coh_tmm's meanings. Computed in parallel with the GIL
    released; points that share an angle share the per-interface work.

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


def inc_absorp_in_each_layer(inc_data):
    """The fraction of the incident power absorbed in each medium, as ``tmm.inc_absorp_in_each_layer``:
    ``[R, A_1, …, A_N, T]`` for the result of :func:`inc_tmm`."""
    try:
        return list(inc_data["absorp_in_each_layer"])
    except KeyError:
        raise ValueError("inc_absorp_in_each_layer needs the result of iridis.tmm.inc_tmm") from None


def absorp_in_each_layer(coh_tmm_data):
    """The fraction of the incident power absorbed in each medium, as ``tmm.absorp_in_each_layer``:
    ``[R, A_1, …, A_N, T]`` (T: the flux into the last medium) for the result of :func:`coh_tmm`."""
    d = coh_tmm_data
    c_list = ["i"] + ["c"] * (len(d["d_list"]) - 2) + ["i"]
    return np.asarray(inc_tmm(d["pol"], d["n_list"], d["d_list"], c_list, d["th_0"], d["lam_vac"])["absorp_in_each_layer"])
