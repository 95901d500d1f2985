"""sphstab from Python: von Neumann stability of SPH forms and kernels, and the solver that
checks it.

Every function mirrors the CLI command of the same name (``stability_map`` is ``map``), with
its flags as keyword arguments (``--alpha-s`` is ``alpha_s``) and the same defaults. It returns
what ``sphstab <command> --json`` prints, as a dict whose ``"units"`` names the unit of every
field; arrays (curves, maps, histories, particles) are numpy ``float64`` arrays.

Units: normalised, Δx = c = 1 (wave numbers κΔx, ω² in c²/Δx², rates in c/Δx, Δt in Δx/c,
stress σ̄ = σ/C); ``swegle`` in the test's own units and ``simulate`` in SI, both with the
scales that convert them.

Bad input raises ``ValueError`` with the CLI's one-line message, naming the keyword argument.
Long computations (``stability_map``, ``timestep(verify=True)``, ``swegle``, ``simulate``) run
without the GIL and stop on Ctrl-C (``KeyboardInterrupt``). Runs that would exceed the
resource budget are refused before they start: ``max_memory`` (bytes, or "512M", "2G"; default
2 GiB or a quarter of the RAM) and ``max_steps`` (particle-steps of one time integration,
default 5e7) on every function.
"""

import inspect as _inspect
import json as _json

import numpy as _np

from . import _sphstab

__all__ = [
    "query",
    "dispersion",
    "timestep",
    "stability_map",
    "swegle",
    "simulate",
    "kernels",
]

# (keyword, what it is: unit, range, default), shared by the questions of the analysis
_QUESTION = (
    ("form", "SPH form: classical (default), nonlocal, local, lnl, cll, total-lagrangian, "
     "eulerian-stress-points, lagrangian-stress-points, least-squares, eulerian-nodal; "
     "2D/3D solids also enog (SPH-ENOG) and tl-enog."),
    ("kernel", "kernel: m4 (default), m5, m6, wendland-c2, wendland-c4, wendland-c6, gaussian, "
     "lucy, efg-cubic, efg-quartic, mollifier (see kernels())."),
    ("h", "smoothing length h/Δx in the kernel's own convention, in [0.05, 50] with support "
     "ζh > Δx (default 1.2 unless support is given)."),
    ("support", "support radius R/Δx = ζ h/Δx, > 1; alternative to h."),
    ("shape", "shape family: sph, shepard, mls, corrected (default: the form's)."),
    ("stress", "pre-stress σ̄ = σ/C, dimensionless, positive in tension, in [-10, 10] "
     "(default 0.01)."),
    ("prestress", "2D/3D shape of the pre-stress: isotropic (default), uniaxial or shear "
     "(the last two need the elastic material)."),
    ("hourglass", "hourglass-control coefficient, in [0, 1000]: ζ of enog (default "
     "0.7D + 2.1), κ of tl-enog (default 1.07), Ganzenmüller's α of total-lagrangian "
     "(default none)."),
    ("c", "partition coefficient c of lnl/cll, in [0, 1] (default 0.5)."),
    ("alpha_s", "least-squares stabilisation α_s (β = α_s Δx²), in [0, 100] (default 0)."),
    ("dt", "time step Δt in Δx/c, in (0, 1e6]: the fully discrete check with the integrator "
     "(query, timestep)."),
    ("av_alpha", "Monaghan artificial viscosity α, dimensionless, in [0, 100]."),
    ("av_beta", "Monaghan artificial viscosity β, in [0, 100]: only timestep(verify=True) "
     "uses it (it vanishes in the linearisation)."),
    ("dim", "dimension 1 (default; map: 2), 2 or 3."),
    ("lattice", "2D square (default) or hex; 3D sc (default), bcc or fcc."),
    ("gamma", "2D square-lattice aspect ratio Δy/Δx, in [0.1, 10] (default 1)."),
    ("material", "2D/3D material: hydro (G = 0, σ̄ = 1 − ρ/ρ0), elastic (default) or "
     "neo-hookean (total-lagrangian)."),
    ("poisson", "2D/3D Poisson ratio ν, in [-0.99, 0.5) (default 0.3; plane strain in 2D)."),
    ("rate", "2D/3D objective stress rate: jaumann (default) or truesdell."),
    ("art_eps", "2D classical/cll: Monaghan–Gray artificial stress ε, in [0, 10]."),
    ("art_n", "artificial-stress exponent n, in [1, 12] (default 4; needs art_eps)."),
    ("delta", "δ-SPH density diffusion δ, in [0, 10] (typical 0.1)."),
    ("delta_form", "δ-SPH term: antuono (default) or molteni-colagrossi (needs delta)."),
)
_GRID = ("grid", "wave-vector sampling: 1D κ points in (0, π] (default 512); 2D/3D wave "
         "vectors per reciprocal direction, 2D in [2, 1024] (default 64), 3D in [2, 128] "
         "(default 16).")
_INTEGRATOR = (
    ("integrator", "time integrator: kdk (default), dkd, verlet-lagged, symplectic-euler-vx, "
     "symplectic-euler-xv, pec, epec, verlet-euler, rk2-midpoint, rk2-heun, rk4, euler."),
    ("euler_every", "N_s of verlet-euler, in [1, 1000] (default 40)."),
)
_BUDGET = (
    ("max_memory", "memory budget: bytes, or a string with a K/M/G/T suffix (default 2G, or "
     "a quarter of the RAM if less)."),
    ("max_steps", "cap on particle-steps of one time integration, ≥ 1 (default 5e7)."),
)


def _api(params, doc):
    """Gives a keyword-only function the signature and the documented arguments `params`
    (None means the library's default), so that help() and IDEs show them."""

    def wrap(f):
        f.__signature__ = _inspect.Signature(
            [_inspect.Parameter(name, _inspect.Parameter.KEYWORD_ONLY, default=None)
             for name, _ in params])
        lines = "\n".join(f"    {name}: {what}" for name, what in params)
        f.__doc__ = f"{doc}\n\nKeyword arguments (all optional):\n{lines}\n"
        return f

    return wrap


def _json_default(x):
    # numpy scalars (np.int64, np.bool_) are plain numbers to the library
    if isinstance(x, _np.generic):
        return x.item()
    raise TypeError(f"{type(x).__name__} is not a number, string or bool")


def _kwargs(kwargs):
    """The keyword arguments given (None: the library's default) as JSON."""
    return _json.dumps({k: v for k, v in kwargs.items() if v is not None},
                       default=_json_default)


def _arrays(doc, keys):
    for key in keys:
        if doc.get(key) is not None:
            doc[key] = _np.asarray(doc[key], dtype=_np.float64)
    return doc


@_api(_QUESTION + (_GRID,) + _INTEGRATOR + _BUDGET,
      """Stability of one configuration: ``sphstab query --json``.

Returns a dict: ``stable``, ``max_growth_rate`` (c/Δx), ``kappa_at_max`` (κΔx),
``instabilities`` (each named: tensile, compressive, rank-deficiency, material, time-step,
integrator; with its κ range and growth rate), ``critical_dt`` (Δx/c), ``units``, …""")
def query(**kwargs):
    return _json.loads(_sphstab.query_json(_kwargs(kwargs)))


@_api((("points", "1D: κ points in (0, π], in [2, 10000000]; 2D/3D: points per segment of "
        "the high-symmetry path, in [2, 100000] (default 256)."),
       ("eigenvectors", "also return the unit polarisation of every branch (default False)."),)
      + _QUESTION + _BUDGET,
      """Dispersion curves ω²(κ): ``sphstab dispersion --json``.

Returns the JSON document as a dict whose curves are numpy float64 arrays, P points along the
path (1D: κ in (0, π]; 2D/3D: the high-symmetry path, its corners in ``labels``):
``path`` (P,) arc length (1/Δx; 1D κΔx), ``kappa`` (P, D) wave vectors κΔx, ``omega2``
(P, D) ω²Δx²/c² of the D branches ascending, ``growth_rate`` (P,) c/Δx, ``omega2_continuum``
(P, D) (1D: (1 + σ̄)(κΔx)² [B00 eq 32]); for a dissipative system also ``damping_rate`` (c/Δx)
and ``damping_ratio``, lists of P rows of D values (None where the matching of eigenvalue to
branch is ambiguous). With ``eigenvectors=True``,
``polarisation`` (P, D, D) complex128: ``polarisation[p, b]`` is the unit polarisation of
branch ``b`` (the column order of ``omega2``) at point ``p``.""")
def dispersion(**kwargs):
    doc, modes = _sphstab.dispersion_json(_kwargs(kwargs))
    doc = _arrays(_json.loads(doc), ("path", "kappa", "omega2", "growth_rate",
                                     "omega2_continuum"))
    if modes is not None:
        doc["polarisation"] = modes
    return doc


@_api(_QUESTION + (_GRID,) + _INTEGRATOR + (
        ("verify", "also measure the largest stable Δt in the time domain: the solver on a "
         "periodic body of the lattice, Δt bisected to 1% (seconds in 1D, up to minutes in 3D; "
         "default False)."),
        ("viscosity", "pairs the viscosity of the verify runs acts on: one-sided (default, as "
         "SPH codes apply it) or two-sided (as the analysis linearises it)."),) + _BUDGET,
      """Critical time step of the integrator: ``sphstab timestep --json``.

Returns a dict: ``critical_dt`` (Δx/c) and ``critical_cfl`` (c Δt/h), ``omega_max`` (c/Δx),
``critical_dt_from_omega_max`` (2/ω_max), ``critical_dt_eq120`` ([B00] eq 120, dissipative
systems), ``critical_dt_inviscid``, and with ``verify=True`` the measurement as ``verify``.""")
def timestep(**kwargs):
    return _json.loads(_sphstab.timestep_json(_kwargs(kwargs)))


@_api((("n", "wave vectors per direction over [−π, π]², in [2, 1024] (default 128)."),
       ("plane", "3D: the plane through Γ, xy (default), xz, yz or diagonal."),)
      + tuple(p for p in _QUESTION if p[0] != "dt") + _BUDGET,
      """Stability map, the growth rate over the 2D zone or a plane of the 3D zone:
``sphstab map --json`` (default dim 2).

Returns a dict: ``kx`` (n,) and ``ky`` (n,) float64, the cell centres of [−π, π] as κΔx (3D:
the in-plane coordinates u, v, with k = u e_u + v e_v and ``plane`` = [e_u, e_v]); ``growth``
(n, n) float64, ``growth[i, j]`` the growth rate (c/Δx, 0 = stable) at (kx[i], ky[j]);
``omega2_max`` (c²/Δx²).""")
def stability_map(**kwargs):
    doc, arrays = _sphstab.map_json(_kwargs(kwargs))
    doc = _json.loads(doc)
    doc.update(arrays)
    return doc


_SWEGLE = (
    ("dim", "2 (default; size² particles) or 3 (size³)."),
    ("form", "classical (default), nonlocal, local, lnl, cll, total-lagrangian."),
    ("kernel", "kernel (default m4)."),
    ("h", "h/Δx in the kernel's convention, in [0.05, 50] (default 1.2)."),
    ("shape", "shape family (default: the form's)."),
    ("density_ratio", "f = ρ/ρ0, in [0.5, 1.5] (default 0.99): < 1 tension, σ̄ = 1 − f."),
    ("size", "particles per side, ≥ 9, ≤ 2001 (2D) or 201 (3D); default 21 in 2D (the "
     "published box), 12 in 3D."),
    ("t_end", "end time in the test's units (Δx/c ≈ 0.2020), in (0, 1e6] (default 40)."),
    ("until_window", "run past t_end until a mode growing at the box prediction reaches the "
     "fit window (default False)."),
    ("kick", "initial v_x of the centre particle (test's units), in [1e-15, 1e-9] "
     "(default 1e-10)."),
    ("boundary_density", "the fixed layers' density: evolve (default) or frozen."),
    ("dt", "time step Δt in Δx/c, in (0, 2] (default 0.2)."),
    ("c", "partition coefficient of lnl/cll, in [0, 1] (default 0.5)."),
    ("art_eps", "2D classical/cll: Monaghan–Gray artificial stress ε, in [0, 10] (off)."),
    ("art_n", "artificial-stress exponent n, in [1, 12] (default 4)."),
    ("delta", "δ-SPH density diffusion δ, in [0, 10] (off)."),
    ("delta_form", "antuono (default) or molteni-colagrossi."),
) + _INTEGRATOR + _BUDGET

_PARTICLES = """``final``: the particles at the end, ``positions`` and ``velocities`` (N, D), ``density``
(N,) if the form carries it, ``stress`` (N, D, D) σ if carried, ``local_stress`` (N, D, D) τ of
lnl/cll."""


def _run(doc, history, final):
    doc = _json.loads(doc)
    doc["history"] = history
    doc["final"] = final
    return doc


@_api(_SWEGLE,
      """The Swegle perturbed-particle test [V21 §7.2] against its predicted growth:
``sphstab swegle --json``.

Returns the JSON document as a dict (``measured_growth_rate``, ``predicted_growth_rate_box``
and ``predicted_growth_rate_infinite`` in c/Δx, ``fit``, ``dt`` in Δx/c; what the run measures
in the test's units, converted by ``dx_physical`` and ``sound_speed_physical``), with
``history``: 1D float64 arrays ``t``, ``centre_abs_v``, ``max_abs_v_free``, ``rms_v_free``,
``kinetic_energy`` (the columns of history.csv, test's units), and """ + _PARTICLES)
def swegle(**kwargs):
    return _run(*_sphstab.swegle_json(_kwargs(kwargs)))


def simulate(scene, *, max_memory=None, max_steps=None):
    """Runs a 1D scene: ``sphstab simulate SCENE --json``.

    ``scene`` is a dict with the schema of the JSON scene files (``analysis/scenes``; its keys
    are named in errors as written), or a built-in scene's name: uniform-bar,
    compressive-wave, tensile-wave, rod. ``max_memory`` and ``max_steps`` are the budget (as in
    every function).

    Returns the JSON document as a dict (SI units, with ``dx_physical``,
    ``sound_speed_physical`` and ``modulus_physical``; ``dt`` in Δx/c), with ``history``: 1D
    float64 arrays ``t`` (s), ``max_abs_v`` (m/s), ``kinetic_energy`` (J per unit area), and
    ``final``: the particles at the end, ``positions`` and ``velocities`` (N, 1), ``density``
    (N,) if the form carries it, ``stress`` (N, 1, 1) σ (Pa) if carried, ``local_stress``
    (N, 1, 1) τ of lnl/cll.
    """
    return _run(*_sphstab.simulate_json(
        _json.dumps(scene, default=_json_default),
        _kwargs({"max_memory": max_memory, "max_steps": max_steps})))


def kernels():
    """The kernel table: ``sphstab kernels --json``, a list of dicts (name, zeta = support in
    units of h, sigma_1/2/3 = normalisations, inflection_1d/2d = q*, customary_h = the h/Δx
    range, reference)."""
    return _json.loads(_sphstab.kernels_json())
