"""Type stubs of sphstab: the arguments of every function with their types (units, ranges
and defaults are in each function's docstring, ``help(sphstab.query)``). ``None`` means the
library's default, the CLI's."""

from typing import Any, Literal, Optional, Union

import numpy as np
import numpy.typing as npt

Form = Literal[
    "classical", "nonlocal", "local", "lnl", "cll", "total-lagrangian",
    "eulerian-stress-points", "lagrangian-stress-points", "least-squares", "eulerian-nodal",
    "enog", "tl-enog",
]
Kernel = Literal[
    "m4", "m5", "m6", "wendland-c2", "wendland-c4", "wendland-c6", "gaussian", "lucy",
    "efg-cubic", "efg-quartic", "mollifier",
]
Shape = Literal["sph", "shepard", "mls", "corrected"]
Lattice = Literal["square", "hex", "sc", "bcc", "fcc"]
Material = Literal["hydro", "elastic", "neo-hookean"]
Integrator = Literal[
    "kdk", "dkd", "verlet-lagged", "symplectic-euler-vx", "symplectic-euler-xv", "pec", "epec",
    "verlet-euler", "rk2-midpoint", "rk2-heun", "rk4", "euler",
]
Bytes = Union[int, float, str]
Array = npt.NDArray[np.float64]

def query(
    *,
    form: Optional[Form] = None,  # default classical
    kernel: Optional[Kernel] = None,  # default m4
    h: Optional[float] = None,  # h/Δx in [0.05, 50], default 1.2
    support: Optional[float] = None,  # R/Δx > 1, instead of h
    shape: Optional[Shape] = None,
    stress: Optional[float] = None,  # σ̄ = σ/C in [-10, 10], + tension, default 0.01
    prestress: Optional[Literal["isotropic", "uniaxial", "shear"]] = None,  # 2D/3D
    hourglass: Optional[float] = None,  # enog ζ, tl-enog κ, total-lagrangian α; [0, 1000]
    c: Optional[float] = None,  # lnl/cll, [0, 1], default 0.5
    alpha_s: Optional[float] = None,  # least-squares, [0, 100]
    dt: Optional[float] = None,  # Δt in Δx/c, (0, 1e6]
    av_alpha: Optional[float] = None,  # [0, 100]
    av_beta: Optional[float] = None,  # refused: only timestep(verify=True) uses it
    dim: Optional[Literal[1, 2, 3]] = None,  # default 1
    lattice: Optional[Lattice] = None,
    gamma: Optional[float] = None,  # Δy/Δx in [0.1, 10]
    material: Optional[Material] = None,  # 2D/3D, default elastic
    poisson: Optional[float] = None,  # [-0.99, 0.5), default 0.3
    rate: Optional[Literal["jaumann", "truesdell"]] = None,
    art_eps: Optional[float] = None,  # 2D, [0, 10]
    art_n: Optional[int] = None,  # [1, 12], default 4
    delta: Optional[float] = None,  # [0, 10]
    delta_form: Optional[Literal["antuono", "molteni-colagrossi"]] = None,
    grid: Optional[int] = None,  # 1D [2, 1e7]; 2D [2, 1024]; 3D [2, 128]
    integrator: Optional[Integrator] = None,  # default kdk
    euler_every: Optional[int] = None,  # verlet-euler, [1, 1000], default 40
    max_memory: Optional[Bytes] = None,
    max_steps: Optional[float] = None,
) -> dict[str, Any]: ...

def dispersion(
    *,
    points: Optional[int] = None,  # default 256
    eigenvectors: Optional[bool] = None,  # adds "polarisation" (P, D, D) complex128
    form: Optional[Form] = None,
    kernel: Optional[Kernel] = None,
    h: Optional[float] = None,
    support: Optional[float] = None,
    shape: Optional[Shape] = None,
    stress: Optional[float] = None,
    prestress: Optional[Literal["isotropic", "uniaxial", "shear"]] = None,
    hourglass: Optional[float] = None,
    c: Optional[float] = None,
    alpha_s: Optional[float] = None,
    dt: Optional[float] = None,  # refused: ω² is semi-discrete
    av_alpha: Optional[float] = None,
    av_beta: Optional[float] = None,
    dim: Optional[Literal[1, 2, 3]] = None,
    lattice: Optional[Lattice] = None,
    gamma: Optional[float] = None,
    material: Optional[Material] = None,
    poisson: Optional[float] = None,
    rate: Optional[Literal["jaumann", "truesdell"]] = None,
    art_eps: Optional[float] = None,
    art_n: Optional[int] = None,
    delta: Optional[float] = None,
    delta_form: Optional[Literal["antuono", "molteni-colagrossi"]] = None,
    max_memory: Optional[Bytes] = None,
    max_steps: Optional[float] = None,
) -> dict[str, Any]:
    """path (P,), kappa (P, D), omega2 (P, D), growth_rate (P,), omega2_continuum (P, D):
    float64 arrays."""

def timestep(
    *,
    form: Optional[Form] = None,
    kernel: Optional[Kernel] = None,
    h: Optional[float] = None,
    support: Optional[float] = None,
    shape: Optional[Shape] = None,
    stress: Optional[float] = None,
    prestress: Optional[Literal["isotropic", "uniaxial", "shear"]] = None,
    hourglass: Optional[float] = None,
    c: Optional[float] = None,
    alpha_s: Optional[float] = None,
    dt: Optional[float] = None,
    av_alpha: Optional[float] = None,
    av_beta: Optional[float] = None,  # only with verify=True
    dim: Optional[Literal[1, 2, 3]] = None,
    lattice: Optional[Lattice] = None,
    gamma: Optional[float] = None,
    material: Optional[Material] = None,
    poisson: Optional[float] = None,
    rate: Optional[Literal["jaumann", "truesdell"]] = None,
    art_eps: Optional[float] = None,
    art_n: Optional[int] = None,
    delta: Optional[float] = None,
    delta_form: Optional[Literal["antuono", "molteni-colagrossi"]] = None,
    grid: Optional[int] = None,
    integrator: Optional[Integrator] = None,
    euler_every: Optional[int] = None,
    verify: Optional[bool] = None,  # measure the stable Δt in the time domain
    viscosity: Optional[Literal["one-sided", "two-sided"]] = None,  # verify runs only
    max_memory: Optional[Bytes] = None,
    max_steps: Optional[float] = None,
) -> dict[str, Any]: ...

def stability_map(
    *,
    n: Optional[int] = None,  # [2, 1024], default 128
    plane: Optional[Literal["xy", "xz", "yz", "diagonal"]] = None,  # 3D only
    form: Optional[Form] = None,
    kernel: Optional[Kernel] = None,
    h: Optional[float] = None,
    support: Optional[float] = None,
    shape: Optional[Shape] = None,
    stress: Optional[float] = None,
    prestress: Optional[Literal["isotropic", "uniaxial", "shear"]] = None,
    hourglass: Optional[float] = None,
    c: Optional[float] = None,
    alpha_s: Optional[float] = None,
    av_alpha: Optional[float] = None,
    av_beta: Optional[float] = None,
    dim: Optional[Literal[2, 3]] = None,  # default 2
    lattice: Optional[Lattice] = None,
    gamma: Optional[float] = None,
    material: Optional[Material] = None,
    poisson: Optional[float] = None,
    rate: Optional[Literal["jaumann", "truesdell"]] = None,
    art_eps: Optional[float] = None,
    art_n: Optional[int] = None,
    delta: Optional[float] = None,
    delta_form: Optional[Literal["antuono", "molteni-colagrossi"]] = None,
    max_memory: Optional[Bytes] = None,
    max_steps: Optional[float] = None,
) -> dict[str, Any]:
    """kx (n,), ky (n,), growth (n, n) float64 (c/Δx), growth[i, j] at (kx[i], ky[j])."""

def swegle(
    *,
    dim: Optional[Literal[2, 3]] = None,  # default 2
    form: Optional[Literal["classical", "nonlocal", "local", "lnl", "cll", "total-lagrangian"]] = None,
    kernel: Optional[Kernel] = None,
    h: Optional[float] = None,  # default 1.2
    shape: Optional[Shape] = None,
    density_ratio: Optional[float] = None,  # f = ρ/ρ0 in [0.5, 1.5], default 0.99
    size: Optional[int] = None,  # particles per side, default 21 (2D), 12 (3D)
    t_end: Optional[float] = None,  # test's units, (0, 1e6], default 40
    until_window: Optional[bool] = None,
    kick: Optional[float] = None,  # [1e-15, 1e-9], default 1e-10
    boundary_density: Optional[Literal["evolve", "frozen"]] = None,
    dt: Optional[float] = None,  # Δx/c, (0, 2], default 0.2
    c: Optional[float] = None,
    art_eps: Optional[float] = None,
    art_n: Optional[int] = None,
    delta: Optional[float] = None,
    delta_form: Optional[Literal["antuono", "molteni-colagrossi"]] = None,
    integrator: Optional[Integrator] = None,
    euler_every: Optional[int] = None,
    max_memory: Optional[Bytes] = None,
    max_steps: Optional[float] = None,
) -> dict[str, Any]:
    """The report, with history (t, centre_abs_v, max_abs_v_free, rms_v_free, kinetic_energy:
    (T,) float64 each) and final (positions, velocities (N, D); density (N,))."""

def simulate(
    scene: Union[dict[str, Any], Literal["uniform-bar", "compressive-wave", "tensile-wave", "rod"]],
    *,
    max_memory: Optional[Bytes] = None,
    max_steps: Optional[float] = None,
) -> dict[str, Any]:
    """The report (SI), with history (t, max_abs_v, kinetic_energy: (T,) float64 each) and
    final (positions, velocities (N, 1); density (N,), stress, local_stress (N, 1, 1) if
    carried)."""

def kernels() -> list[dict[str, Any]]: ...
