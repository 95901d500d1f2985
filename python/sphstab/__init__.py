"""sphstab from Python: von Neumann stability of SPH forms and kernels.

Every function mirrors the CLI command of the same name, with its flags as keyword arguments
(``--alpha-s`` is ``alpha_s``) and the same defaults; it returns what ``sphstab <command> --json``
prints, as a dict. Bad input raises ``ValueError`` with the CLI's one-line message.
"""

import json as _json

import numpy as _np

from . import _sphstab

__all__ = ["query", "dispersion", "kernels"]

# the array-valued fields of a dispersion document, as numpy float64 arrays
_DISPERSION_ARRAYS = ("path", "kappa", "omega2", "growth_rate", "omega2_continuum")


def query(*, integrator="kdk", **kwargs):
    """Stability of one configuration: ``sphstab query --json``.

    Keyword arguments (all optional): form, kernel, h (h/Δx) or support (R/Δx), shape,
    stress (σ̄ = σ/C, + tension), c, alpha_s, dt (Δx/c), av_alpha, av_beta, dim (1, 2, 3),
    lattice, gamma, material, poisson, rate, art_eps, art_n, delta, delta_form, grid,
    integrator. Returns the JSON document as a dict (its "units" name every field's unit).
    """
    return _json.loads(_sphstab.query_json(_json.dumps(kwargs), integrator))


def dispersion(*, points=256, **kwargs):
    """Dispersion curves ω²(κ): ``sphstab dispersion --json --points POINTS``.

    The keyword arguments of :func:`query` (not ``grid``: the path is sampled with ``points``,
    1D: κ points in (0, π]; 2D/3D: points per segment of the symmetry path). Returns the JSON
    document as a dict whose ``path`` (arc length, dimensionless), ``kappa`` (κΔx per
    component), ``omega2`` (ω²Δx²/c², one row per point, one column per branch),
    ``growth_rate`` (c/Δx) and ``omega2_continuum`` are numpy float64 arrays.
    """
    doc = _json.loads(_sphstab.dispersion_json(_json.dumps(kwargs), int(points)))
    for key in _DISPERSION_ARRAYS:
        if key in doc:
            doc[key] = _np.asarray(doc[key], dtype=_np.float64)
    return doc


def kernels():
    """The kernel table: ``sphstab kernels --json``, a list of dicts (name, zeta = support in
    units of h, sigma_1/2/3 = normalisations, inflection_1d/2d = q*, customary_h = the h/Δx
    range, reference)."""
    return _json.loads(_sphstab.kernels_json())
