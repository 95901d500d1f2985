#!/usr/bin/env python
"""Throughput benchmark of PySPH's ElasticSolidsScheme on a free 2D elastic block.

Manual benchmark for comparison with sphstab's Rust solver (see README.md in this
directory). Not part of the Rust build or test suite.

Set-up (all in units of the lattice spacing, dx = 1 by default):

* size x size particles on a square lattice, x_i = (i + 1/2) dx, block side L = size*dx,
  mass m = rho0 dx^2, rho = rho0 (so p = 0 and S = 0 at t = 0), h = hdx*dx (1.3).
* PySPH CubicSpline(dim=2) (support 2h = 2.6 dx).
* pysph.sph.solid_mech.basic.ElasticSolidsScheme with one elastic solid and no
  boundary ("solids=[]"): a free block, no periodicity.
* Velocity v_x = amp*c*sin(pi y/L), v_y = amp*c*sin(pi x/L), amp = 1e-3, with c the
  scheme's sound speed cs = sqrt(E/(3(1-2nu)rho0)) = sqrt(K/rho0) (bulk).
* Time step dt = dt_factor*dx/c (0.2 by default), EPECIntegrator + SolidMechStep
  (the scheme's defaults).

Timing: the scheme's own Solver is built with ElasticSolidsScheme.configure_solver and
set up with Solver.setup (which generates and compiles the Cython code, exactly as
pysph.solver.application.Application does), with a LinkedListNNPS configured as
Application's defaults (--nnps ll, no cache, fixed_h False). We then drive the
compiled integrator directly: integrator.initial_acceleration + one integrator.step
(untimed warm-up), then N calls of integrator.step(t, dt) timed with
time.perf_counter. Solver.solve is not used, so no output files, progress bar or
time-step computation are timed. Each step includes everything PySPH does in a step:
two NNPS updates, two acceleration evaluations, two stepper stages and two
update_domain calls.
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
    p.add_argument("--size", type=int, default=200, help="particles per side (default 200)")
    p.add_argument("--openmp", action="store_true",
                   help="compile PySPH's generated code with OpenMP (threads from "
                        "OMP_NUM_THREADS); without it the run is forced to 1 thread")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--profile", action="store_true",
                   help="also print compyle's per-group/per-loop timings of the timed steps")
    p.add_argument("--dx", type=float, default=1.0, help="lattice spacing (default 1)")
    p.add_argument("--hdx", type=float, default=1.3, help="h/dx (default 1.3)")
    p.add_argument("--E", type=float, default=1.2,
                   help="Young's modulus (default 1.2, so that c = sqrt(K/rho0) = 1)")
    p.add_argument("--nu", type=float, default=0.3, help="Poisson ratio (default 0.3)")
    p.add_argument("--rho0", type=float, default=1.0, help="reference density (default 1)")
    p.add_argument("--dt-factor", type=float, default=0.2,
                   help="dt = factor*dx/c with c = sqrt(K/rho0) (default 0.2)")
    p.add_argument("--amp", type=float, default=1e-3, help="velocity amplitude / c")
    p.add_argument("--alpha", type=float, default=1.0, help="Monaghan AV alpha (scheme default 1)")
    p.add_argument("--beta", type=float, default=1.0, help="Monaghan AV beta (scheme default 1)")
    p.add_argument("--art-eps", type=float, default=0.3,
                   help="artificial stress epsilon (scheme default 0.3)")
    p.add_argument("--art-n", type=int, default=4,
                   help="artificial stress exponent n (particle-array default 4)")
    p.add_argument("--no-art-stress", action="store_true",
                   help="wdeltap = -1: PySPH's switch that drops the R f^n term from the "
                        "momentum equation (R is still computed)")
    p.add_argument("--xsph-eps", type=float, default=0.5,
                   help="XSPH epsilon (scheme default 0.5; 0 keeps the equation but "
                        "makes it a no-op)")
    return p.parse_args(argv)


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

    n, dx, hdx = args.size, args.dx, args.hdx
    h = hdx * dx
    L = n * dx
    E, nu, rho0 = args.E, args.nu, args.rho0
    c = get_speed_of_sound(E, nu, rho0)            # sqrt(E/(3(1-2nu)rho0)) = sqrt(K/rho0)
    G = get_shear_modulus(E, nu)
    K = get_bulk_mod(G, nu)
    lam = K - 2.0 * G / 3.0
    c_p = math.sqrt((lam + 2.0 * G) / rho0)       # plane-strain P-wave speed (sphstab's c)
    dt = args.dt_factor * dx / c

    # --- particles -------------------------------------------------------------
    kernel = CubicSpline(dim=2)
    wdeltap = -1.0 if args.no_art_stress else kernel.kernel(rij=dx, h=h)
    xs = (np.arange(n) + 0.5) * dx
    x, y = np.meshgrid(xs, xs, indexing="ij")
    x = x.ravel()
    y = y.ravel()
    pa = get_particle_array_elastic_dynamics(
        name="solid", x=x, y=y, m=rho0 * dx * dx, rho=rho0, h=h,
        constants=dict(wdeltap=wdeltap, n=args.art_n, rho_ref=rho0, E=E, nu=nu))
    pa.u[:] = args.amp * c * np.sin(np.pi * y / L)
    pa.v[:] = args.amp * c * np.sin(np.pi * x / L)
    npart = pa.get_number_of_particles()

    def kinetic_energy():
        return 0.5 * float(np.sum(pa.m * (pa.u ** 2 + pa.v ** 2 + pa.w ** 2)))

    ke0 = kinetic_energy()

    # --- scheme, solver, compilation ---------------------------------------------
    scheme = ElasticSolidsScheme(
        elastic_solids=["solid"], solids=[], dim=2,
        artificial_stress_eps=args.art_eps, xsph_eps=args.xsph_eps,
        alpha=args.alpha, beta=args.beta)
    scheme.configure_solver(kernel=kernel, dt=dt, tf=dt * (args.steps + 1))
    solver = scheme.solver
    equations = scheme.get_equations()
    nnps = LinkedListNNPS(dim=2, particles=[pa], radius_scale=kernel.radius_scale,
                          domain=None, fixed_h=False, cache=False, sort_gids=False)

    solver.set_parallel_manager(None)   # as Application does in a serial (non-MPI) run
    t0 = time.perf_counter()
    solver.setup(particles=[pa], equations=equations, nnps=nnps, kernel=kernel,
                 fixed_h=False)
    t_setup = time.perf_counter() - t0
    integrator = solver.integrator

    # neighbour count (from the initial NNPS state)
    from cyarray.carray import UIntArray
    nbrs = UIntArray()
    nnps.update()
    counts = np.empty(npart, dtype=np.int64)
    for i in range(npart):
        nnps.get_nearest_particles(0, 0, i, nbrs)
        counts[i] = nbrs.length
    mid = (n // 2) * n + n // 2
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

    t_nnps, c_nnps = prof_time("nnps.update")
    t_acc, c_acc = prof_time("acceleration_eval_0")

    finite = bool(np.all(np.isfinite(pa.u)) and np.all(np.isfinite(pa.rho)))
    vmax = float(np.max(np.hypot(pa.u, pa.v)))
    ke1 = kinetic_energy()
    pstep = npart * args.steps
    rate = pstep / elapsed
    ns = elapsed / pstep * 1e9

    res = {
        "code": "pysph",
        "pysph_version": pysph.__version__,
        "scheme": "ElasticSolidsScheme",
        "integrator": type(integrator).__name__ + "+SolidMechStep",
        "rate_evaluations_per_step": c_acc // max(args.steps, 1),
        "nnps_updates_per_step": c_nnps // max(args.steps, 1),
        "nnps": "LinkedListNNPS(cache=False, fixed_h=False)",
        "openmp": bool(args.openmp),
        "threads": int(nthreads),
        "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS"),
        "size": n,
        "particles": int(npart),
        "steps": args.steps,
        "dx": dx,
        "h_over_dx": hdx,
        "kernel": "CubicSpline(dim=2)",
        "neighbours_interior": nbr_interior,
        "neighbours_mean": nbr_mean,
        "E": E, "nu": nu, "rho0": rho0, "G": G, "K": K, "lambda": lam,
        "c_bulk": c, "c_p": c_p,
        "dt": dt, "dt_dx_over_c_bulk": args.dt_factor, "dt_dx_over_c_p": dt * c_p / dx,
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
        "other_s": elapsed - t_nnps - t_acc,
        "finite": finite,
        "max_speed_over_c": vmax / c,
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
        print("PySPH %s ElasticSolidsScheme, %d x %d = %d particles, %d steps"
              % (pysph.__version__, n, n, npart, args.steps))
        print("  openmp=%s threads=%d (OMP_NUM_THREADS=%s)"
              % (args.openmp, nthreads, res["OMP_NUM_THREADS"]))
        print("  E=%g nu=%g rho0=%g  c_bulk=%.6g c_p=%.6g  dt=%.6g (%.3g dx/c_bulk, %.3g dx/c_p)"
              % (E, nu, rho0, c, c_p, dt, args.dt_factor, dt * c_p / dx))
        print("  alpha=%g beta=%g art_eps=%g n=%g (art stress %s) xsph_eps=%g"
              % (args.alpha, args.beta, args.art_eps, args.art_n,
                 "on" if not args.no_art_stress else "off", args.xsph_eps))
        print("  neighbours (incl. self): interior %d, mean %.2f" % (nbr_interior, nbr_mean))
        print("  setup+compile %.2f s, warm-up %.3f s" % (t_setup, t_warm))
        print("  timed: %.4f s  (nnps.update %.4f s in %d calls, acceleration_eval %.4f s in %d calls, other %.4f s)"
              % (elapsed, t_nnps, c_nnps, t_acc, c_acc, elapsed - t_nnps - t_acc))
        print("  sanity: finite=%s max|v|/c=%.3e KE(end)/KE(0)=%.6f"
              % (finite, vmax / c, res["kinetic_energy_ratio"]))
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
