#!/usr/bin/env python
"""Throughput benchmark of PySPH's ElasticSolidsScheme on sphstab's 2D block or 3D periodic box.

Manual benchmark for comparison with sphstab's Rust solver (see README.md in this
directory). Not part of the Rust build or test suite.

2D set-up (--dim 2, the default; all in units of the lattice spacing, dx = 1 by default):

* size x size particles on a square lattice, x_i = (i + 1/2) dx, block side L = size*dx,
  mass m = rho0 dx^2, rho = rho0 (so p = 0 and S = 0 at t = 0), h = hdx*dx (1.3).
* PySPH CubicSpline(dim=2) (support 2h = 2.6 dx).
* pysph.sph.solid_mech.basic.ElasticSolidsScheme with one elastic solid and no
  boundary ("solids=[]"): a free block, no periodicity.
* Velocity v_x = amp*c*sin(pi y/L), v_y = amp*c*sin(pi x/L), amp = 1e-3, with c the
  scheme's sound speed cs = sqrt(E/(3(1-2nu)rho0)) = sqrt(K/rho0) (bulk).
* Time step dt = dt_factor*dx/c (0.2 by default), EPECIntegrator + SolidMechStep
  (the scheme's defaults).

3D set-up (--dim 3): the scene of `sphstab throughput --dim 3` (a periodic box):

* size^3 particles (default 30) on a cubic lattice at x_i = i dx, i = 0 .. size-1 (sphstab's
  coordinates), periodic in x, y and z with period L = size*dx (PySPH DomainManager on
  [-dx/2, L - dx/2]^3, ghost layer one support radius wide, --n-layers 1), m = rho0 dx^3,
  rho = rho0, h = 1.3 dx, CubicSpline(dim=3).
* Material of sphstab's box: P-wave modulus lambda + 2G = 1, nu = 0.3, rho0 = 1, i.e.
  E = (1+nu)(1-2nu)/(1-nu) = 0.742857; c below is sphstab's c = c_P = 1 (PySPH's own
  cs = sqrt(K/rho0) = 0.786796 enters only its EOS and its viscosity).
* Velocity v_a = amp*c_P*sin(2 pi x_{a+1}/L) (a+1 mod 3): v_x(y), v_y(z), v_z(x), as sphstab;
  dt = dt_factor*dx/c_P.
* Viscosity: PySPH's alpha is set to alpha_sphstab*c_P/cs (1.27098 for sphstab's alpha = 1),
  so that alpha*cs, the only place its sound speed enters Pi_ab, equals sphstab's alpha*c_P;
  beta = 1.
* No artificial stress (sphstab has none in 3D): wdeltap = -1 switches the R f^n term off and
  the scheme's MonaghanArtificialStress equation (whose R nothing reads then) is left out
  (--keep-art-stress-eq keeps it, as dead work).
* The scheme's equations with two changes that 3D periodicity needs (ElasticSolidsScheme
  1.0b2 is written for 2D): VelocityGradient2D is replaced by PySPH's VelocityGradient3D, and
  the IsothermalEOS runs in its own Group(real=False) first, so that the periodic ghost
  particles (copies made before each evaluation) carry the current pressure.

Timing: the scheme's own Solver is built with ElasticSolidsScheme.configure_solver and
set up with Solver.setup (which generates and compiles the Cython code, exactly as
pysph.solver.application.Application does), with a LinkedListNNPS configured as
Application's defaults (--nnps ll, no cache, fixed_h False). We then drive the
compiled integrator directly: integrator.initial_acceleration + one integrator.step
(untimed warm-up), then N calls of integrator.step(t, dt) timed with
time.perf_counter. Solver.solve is not used, so no output files, progress bar or
time-step computation are timed. Each step includes everything PySPH does in a step:
two NNPS updates, two acceleration evaluations, two stepper stages and two
update_domain calls (in 3D these rebuild the periodic ghosts). ns per particle-step
counts the real particles only (size^dim).
"""

import argparse
import json
import math
import os
import platform
import sys
import time


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--steps", type=int, default=50, help="timed steps (default 50)")
    p.add_argument("--dim", type=int, default=2, choices=(2, 3),
                   help="2: the free 2D block (default); 3: sphstab's periodic 3D box")
    p.add_argument("--size", type=int, default=None,
                   help="particles per side (default 200 in 2D, 30 in 3D)")
    p.add_argument("--openmp", action="store_true",
                   help="compile PySPH's generated code with OpenMP (threads from "
                        "OMP_NUM_THREADS); without it the run is forced to 1 thread")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--profile", action="store_true",
                   help="also print compyle's per-group/per-loop timings of the timed steps")
    p.add_argument("--dx", type=float, default=1.0, help="lattice spacing (default 1)")
    p.add_argument("--hdx", type=float, default=1.3, help="h/dx (default 1.3)")
    p.add_argument("--E", type=float, default=None,
                   help="Young's modulus (default 1.2 in 2D, so that c = sqrt(K/rho0) = 1; "
                        "in 3D (1+nu)(1-2nu)/(1-nu), so that lambda + 2G = 1, sphstab's)")
    p.add_argument("--nu", type=float, default=0.3, help="Poisson ratio (default 0.3)")
    p.add_argument("--rho0", type=float, default=1.0, help="reference density (default 1)")
    p.add_argument("--dt-factor", type=float, default=0.2,
                   help="dt = factor*dx/c with c = sqrt(K/rho0) in 2D, c = c_P in 3D "
                        "(default 0.2)")
    p.add_argument("--amp", type=float, default=1e-3,
                   help="velocity amplitude / c (c as for --dt-factor)")
    p.add_argument("--alpha", type=float, default=None,
                   help="PySPH's Monaghan AV alpha (default: the scheme's 1 in 2D; in 3D "
                        "c_P/cs = 1.27098, so that alpha*cs = 1*c_P as in sphstab)")
    p.add_argument("--beta", type=float, default=1.0, help="Monaghan AV beta (scheme default 1)")
    p.add_argument("--art-eps", type=float, default=None,
                   help="artificial stress epsilon (scheme default 0.3; 2D only)")
    p.add_argument("--art-n", type=int, default=4,
                   help="artificial stress exponent n (particle-array default 4)")
    p.add_argument("--no-art-stress", action="store_true",
                   help="wdeltap = -1: PySPH's switch that drops the R f^n term from the "
                        "momentum equation (R is still computed)")
    p.add_argument("--xsph-eps", type=float, default=0.5,
                   help="XSPH epsilon (scheme default 0.5; 0 keeps the equation but "
                        "makes it a no-op)")
    p.add_argument("--n-layers", type=float, default=1.0,
                   help="3D: width of the periodic ghost layer in support radii (default 1, "
                        "the least that gives every particle its full neighbourhood; "
                        "PySPH's DomainManager default is 2)")
    p.add_argument("--keep-art-stress-eq", action="store_true",
                   help="3D: keep the scheme's MonaghanArtificialStress equation (R computed "
                        "every evaluation but unused, wdeltap = -1)")
    a = p.parse_args(argv)
    if a.dim == 2:
        if a.keep_art_stress_eq or a.n_layers != 1.0:
            p.error("--keep-art-stress-eq and --n-layers are for --dim 3")
        a.size = 200 if a.size is None else a.size
        a.E = 1.2 if a.E is None else a.E
        a.alpha = 1.0 if a.alpha is None else a.alpha
        a.art_eps = 0.3 if a.art_eps is None else a.art_eps
    else:
        if a.art_eps is not None or a.no_art_stress:
            p.error("--dim 3 has no artificial stress (as sphstab's 3D box); drop "
                    "--art-eps/--no-art-stress")
        a.size = 30 if a.size is None else a.size
        # P-wave modulus lambda + 2G = 1 (times rho0, so that c_P = 1 for any rho0)
        if a.E is None:
            a.E = a.rho0 * (1 + a.nu) * (1 - 2 * a.nu) / (1 - a.nu)
        a.art_eps = 0.0
        a.no_art_stress = True
        if a.size <= 4 * a.hdx:
            p.error("--size must exceed two support radii (4 h/dx = %g) in the periodic box"
                    % (4 * a.hdx))
    return a


def equations_3d(groups, keep_art_stress_eq):
    """The scheme's two groups made right for a 3D periodic box (see the module docstring)."""
    from pysph.sph.equation import Group
    from pysph.sph.basic_equations import VelocityGradient2D, VelocityGradient3D
    from pysph.sph.solid_mech.basic import IsothermalEOS, MonaghanArtificialStress
    g0, g1 = groups
    eos, rest = [], []
    for eq in g0.equations:
        if isinstance(eq, IsothermalEOS):
            eos.append(eq)
        elif isinstance(eq, VelocityGradient2D):
            rest.append(VelocityGradient3D(dest=eq.dest, sources=eq.sources))
        elif isinstance(eq, MonaghanArtificialStress):
            if keep_art_stress_eq:
                rest.append(eq)
        else:
            raise RuntimeError("unexpected equation in the scheme's group 0: %r" % eq)
    # p of the ghosts too: they are copies of the real particles made by update_domain
    # *before* the evaluation, when p was still the previous evaluation's
    return [Group(equations=eos, real=False), Group(equations=rest), g1]


def main(argv=None):
    args = parse_args(argv)
    load0 = os.getloadavg()[0]

    # Configure compyle *before* any PySPH code is generated/compiled.
    from compyle.config import get_config
    cfg = get_config()
    cfg.use_openmp = bool(args.openmp)

    import numpy as np
    import pysph
    from pysph.base.kernels import CubicSpline
    from pysph.base.nnps import LinkedListNNPS
    from pysph.base.nnps_base import DomainManager
    from pysph.base.nnps_base import get_number_of_threads, set_number_of_threads
    from pysph.sph.solid_mech.basic import (
        ElasticSolidsScheme, get_particle_array_elastic_dynamics,
        get_speed_of_sound, get_shear_modulus, get_bulk_mod)
    from compyle.profile import get_profile_info

    if not args.openmp:
        # PySPH's prebuilt NNPS extensions are linked with OpenMP and would use
        # all cores; a serial measurement must pin them to one thread.
        set_number_of_threads(1)
    nthreads = get_number_of_threads()

    dim = args.dim
    n, dx, hdx = args.size, args.dx, args.hdx
    h = hdx * dx
    L = n * dx
    E, nu, rho0 = args.E, args.nu, args.rho0
    c = get_speed_of_sound(E, nu, rho0)            # sqrt(E/(3(1-2nu)rho0)) = sqrt(K/rho0)
    G = get_shear_modulus(E, nu)
    K = get_bulk_mod(G, nu)
    lam = K - 2.0 * G / 3.0
    c_p = math.sqrt((lam + 2.0 * G) / rho0)       # P-wave speed (plane strain in 2D): sphstab's c
    # the c of --dt-factor and --amp: PySPH's cs in 2D (as before), sphstab's c_P in 3D
    c_ref = c if dim == 2 else c_p
    dt = args.dt_factor * dx / c_ref
    if args.alpha is None:                          # 3D default: alpha*cs = 1*c_P
        args.alpha = c_p / c

    # --- particles -------------------------------------------------------------
    kernel = CubicSpline(dim=dim)
    wdeltap = -1.0 if args.no_art_stress else kernel.kernel(rij=dx, h=h)
    domain = None
    if dim == 2:
        xs = (np.arange(n) + 0.5) * dx
        x, y = np.meshgrid(xs, xs, indexing="ij")
        x = x.ravel()
        y = y.ravel()
        pa = get_particle_array_elastic_dynamics(
            name="solid", x=x, y=y, m=rho0 * dx * dx, rho=rho0, h=h,
            constants=dict(wdeltap=wdeltap, n=args.art_n, rho_ref=rho0, E=E, nu=nu))
        pa.u[:] = args.amp * c * np.sin(np.pi * y / L)
        pa.v[:] = args.amp * c * np.sin(np.pi * x / L)
    else:
        # sphstab's lattice (src/studies/throughput/block.rs): x = i dx, first axis slowest,
        # period L = n dx per axis, v_a = A c sin(2 pi x_{a+1} / L)
        xs = np.arange(n) * dx
        x, y, z = np.meshgrid(xs, xs, xs, indexing="ij")
        x = x.ravel()
        y = y.ravel()
        z = z.ravel()
        pa = get_particle_array_elastic_dynamics(
            name="solid", x=x, y=y, z=z, m=rho0 * dx ** 3, rho=rho0, h=h,
            constants=dict(wdeltap=wdeltap, n=args.art_n, rho_ref=rho0, E=E, nu=nu))
        amp = args.amp * c_p
        pa.u[:] = amp * np.sin(2 * np.pi * y / L)
        pa.v[:] = amp * np.sin(2 * np.pi * z / L)
        pa.w[:] = amp * np.sin(2 * np.pi * x / L)
        lo, hi = -0.5 * dx, L - 0.5 * dx
        domain = DomainManager(xmin=lo, xmax=hi, ymin=lo, ymax=hi, zmin=lo, zmax=hi,
                               periodic_in_x=True, periodic_in_y=True, periodic_in_z=True,
                               n_layers=args.n_layers)
    npart = pa.get_number_of_particles()            # real particles (no ghosts yet)

    def real(prop):
        return getattr(pa, prop)[:npart]

    def kinetic_energy():
        return 0.5 * float(np.sum(real("m") * (real("u") ** 2 + real("v") ** 2
                                               + real("w") ** 2)))

    ke0 = kinetic_energy()

    # --- scheme, solver, compilation ---------------------------------------------
    scheme = ElasticSolidsScheme(
        elastic_solids=["solid"], solids=[], dim=dim,
        artificial_stress_eps=args.art_eps, xsph_eps=args.xsph_eps,
        alpha=args.alpha, beta=args.beta)
    scheme.configure_solver(kernel=kernel, dt=dt, tf=dt * (args.steps + 1))
    solver = scheme.solver
    equations = scheme.get_equations()
    if dim == 3:
        equations = equations_3d(equations, args.keep_art_stress_eq)
    # in 3D the constructor also makes the first periodic ghosts (copies of the state above)
    nnps = LinkedListNNPS(dim=dim, particles=[pa], radius_scale=kernel.radius_scale,
                          domain=domain, fixed_h=False, cache=False, sort_gids=False)

    solver.set_parallel_manager(None)   # as Application does in a serial (non-MPI) run
    t0 = time.perf_counter()
    solver.setup(particles=[pa], equations=equations, nnps=nnps, kernel=kernel,
                 fixed_h=False)
    t_setup = time.perf_counter() - t0
    integrator = solver.integrator

    # neighbour count (from the initial NNPS state; periodic ghosts are appended after the
    # real particles, which keep their order)
    from cyarray.carray import UIntArray
    nbrs = UIntArray()
    nnps.update()
    assert pa.get_number_of_particles(real=True) == npart
    assert not np.any(pa.tag[:npart]), "real particles are not first"
    ghosts = pa.get_number_of_particles() - npart

    def neighbour_counts():
        counts = np.empty(npart, dtype=np.int64)
        for i in range(npart):
            nnps.get_nearest_particles(0, 0, i, nbrs)
            counts[i] = nbrs.length
        return counts

    counts = neighbour_counts()
    mid = (n // 2) * n + n // 2 if dim == 2 else ((n // 2) * n + n // 2) * n + n // 2
    nbr_interior = int(counts[mid])
    nbr_mean = float(counts.mean())

    # --- warm-up: initial acceleration + 1 step (untimed) -----------------------
    t = 0.0
    t0 = time.perf_counter()
    integrator.initial_acceleration(t, dt)
    integrator.step(t, dt)
    t += dt
    t_warm = time.perf_counter() - t0

    # reset compyle's always-on profile counters so they cover the timed steps only
    prof = get_profile_info()
    prof.clear()

    # --- timed stepping --------------------------------------------------------
    t0 = time.perf_counter()
    for _ in range(args.steps):
        integrator.step(t, dt)
        t += dt
    elapsed = time.perf_counter() - t0

    def prof_time(name):
        for level in prof.values():
            if name in level:
                return level[name]["time"], level[name]["calls"]
        return 0.0, 0

    # neighbours at the end (sphstab's throughput reports them at the end); untimed
    nnps.update()
    nbr_mean_end = float(neighbour_counts().mean())

    t_nnps, c_nnps = prof_time("nnps.update")
    t_acc, c_acc = prof_time("acceleration_eval_0")
    t_dom, c_dom = prof_time("Integrator.update_domain")

    finite = all(bool(np.all(np.isfinite(real(q)))) for q in ("u", "v", "w", "rho", "s00"))
    vmax = float(np.max(np.sqrt(real("u") ** 2 + real("v") ** 2 + real("w") ** 2)))
    ke1 = kinetic_energy()
    pstep = npart * args.steps
    rate = pstep / elapsed
    ns = elapsed / pstep * 1e9

    res = {
        "code": "pysph",
        "pysph_version": pysph.__version__,
        "scheme": "ElasticSolidsScheme" + (
            "" if dim == 2 else " (VelocityGradient3D, EOS on ghosts, " +
            ("MonaghanArtificialStress kept)" if args.keep_art_stress_eq
             else "no MonaghanArtificialStress)")),
        "dim": dim,
        "domain": "open" if dim == 2 else "periodic",
        "integrator": type(integrator).__name__ + "+SolidMechStep",
        "rate_evaluations_per_step": c_acc // max(args.steps, 1),
        "nnps_updates_per_step": c_nnps // max(args.steps, 1),
        "nnps": "LinkedListNNPS(cache=False, fixed_h=False)",
        "openmp": bool(args.openmp),
        "threads": int(nthreads),
        "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS"),
        "size": n,
        "particles": int(npart),
        "ghost_particles": int(ghosts),
        "ghost_layers_support_radii": None if dim == 2 else args.n_layers,
        "steps": args.steps,
        "dx": dx,
        "h_over_dx": hdx,
        "kernel": "CubicSpline(dim=%d)" % dim,
        "neighbours_interior": nbr_interior,
        "neighbours_mean": nbr_mean,
        "neighbours_mean_end": nbr_mean_end,
        "E": E, "nu": nu, "rho0": rho0, "G": G, "K": K, "lambda": lam,
        "c_bulk": c, "c_p": c_p, "c_ref": "c_bulk" if dim == 2 else "c_p",
        "amp_over_c_ref": args.amp,
        "dt": dt, "dt_dx_over_c_bulk": args.dt_factor if dim == 2 else dt * c / dx, "dt_dx_over_c_p": dt * c_p / dx,
        "alpha": args.alpha, "beta": args.beta, "av_eps": "0.01*h^2",
        "art_eps": args.art_eps, "art_n": args.art_n,
        "art_stress_on": not args.no_art_stress, "wdeltap": wdeltap,
        "xsph_eps": args.xsph_eps,
        "setup_compile_s": t_setup,
        "warmup_s": t_warm,
        "elapsed_s": elapsed,
        "particle_steps_per_s": rate,
        "ns_per_particle_step": ns,
        "nnps_update_s": t_nnps,
        "acceleration_eval_s": t_acc,
        "update_domain_s": t_dom,
        "other_s": elapsed - t_nnps - t_acc,
        "finite": finite,
        "max_speed_over_c": vmax / c_ref,
        "kinetic_energy_ratio": ke1 / ke0 if ke0 > 0 else None,
        "python": platform.python_version(),
        "machine": platform.machine(),
        "cpus": os.cpu_count(),
        "loadavg_1min_at_start": load0,
    }

    if args.profile:
        res["profile"] = {"%d:%s" % (lev, name): [d["time"], d["calls"]]
                          for lev, entries in sorted(prof.items())
                          for name, d in entries.items()}
    if args.json:
        print(json.dumps(res))
    else:
        print("PySPH %s %s, %s = %d particles (%s), %d steps"
              % (pysph.__version__, res["scheme"], " x ".join([str(n)] * dim), npart,
                 res["domain"] + ("" if dim == 2 else ", %d ghosts" % ghosts), args.steps))
        print("  openmp=%s threads=%d (OMP_NUM_THREADS=%s)"
              % (args.openmp, nthreads, res["OMP_NUM_THREADS"]))
        print("  E=%g nu=%g rho0=%g  c_bulk=%.6g c_p=%.6g  dt=%.6g (%.3g dx/c_bulk, %.3g dx/c_p)"
              % (E, nu, rho0, c, c_p, dt, dt * c / dx, dt * c_p / dx))
        print("  alpha=%g beta=%g art_eps=%g n=%g (art stress %s) xsph_eps=%g"
              % (args.alpha, args.beta, args.art_eps, args.art_n,
                 "on" if not args.no_art_stress else "off", args.xsph_eps))
        print("  neighbours (incl. self): interior %d, mean %.2f (%.2f at the end)"
              % (nbr_interior, nbr_mean, nbr_mean_end))
        print("  setup+compile %.2f s, warm-up %.3f s" % (t_setup, t_warm))
        print("  timed: %.4f s  (nnps.update %.4f s in %d calls, acceleration_eval %.4f s in %d calls, other %.4f s, of which update_domain %.4f s)"
              % (elapsed, t_nnps, c_nnps, t_acc, c_acc, elapsed - t_nnps - t_acc, t_dom))
        print("  sanity: finite=%s max|v|/%s=%.3e KE(end)/KE(0)=%.6f"
              % (finite, res["c_ref"], vmax / c_ref, res["kinetic_energy_ratio"]))
        print("  1-min load average at start: %.2f" % load0)
        if args.profile:
            print("  profile of the timed steps (level:name  seconds  calls):")
            for k, (tt, cc) in sorted(res["profile"].items(), key=lambda kv: -kv[1][0]):
                print("    %-60s %8.4f %6d" % (k, tt, cc))
        print("particle-steps/s: %.4e" % rate)
        print("ns/particle-step: %.1f" % ns)
    return 0


if __name__ == "__main__":
    sys.exit(main())
