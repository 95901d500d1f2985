#!/usr/bin/env python
"""Swegle-test growth rate in PySPH 1.0b2 with Monaghan-Gray artificial stress, against sphstab.

Manual comparison (see README.md in this directory, section "Swegle test with artificial
stress"). Not part of the Rust build or test suite.

Set-up ([V21 sec. 7.2], the scene of `sphstab swegle --boundary-density frozen`):

* 21 x 21 particles at spacing dx = 0.1, x = (i - 10) dx, on [-1, 1]^2; the outer 3 layers
  are a separate particle array "boundary" that takes part in every sum but has no
  integrator step (fixed, density frozen at its initial value); the 15 x 15 inner particles
  are the array "solid".
* rho0 = 2.8, K = 0.686275, G = 0, c = sqrt(K/rho0); mass m = f rho0 dx^2, initial density
  f rho0 everywhere (f < 1: tension), at rest except the centre particle, u = 1e-10.
* EOS p = c^2 (rho - rho0) (PySPH IsothermalEOS with c0_ref = c, rho_ref = rho0), i.e.
  sphstab's hydro stress sigma = -K (rho/rho0 - 1) I; deviatoric stress S = 0 (G = 0).
* PySPH CubicSpline(dim=2) (M4, sigma = 10/(7 pi h^2), support 2h), h = hdx dx.
* Continuity equation (PySPH ContinuityEquation), classical momentum equation with
  artificial stress (MomentumEquationWithStress: sum m_b (sigma_a/rho_a^2 + sigma_b/rho_b^2 +
  (R_a + R_b) f_ab^n) grad_a W_ab, f_ab = W_ab / W(dx)), R from MonaghanArtificialStress
  (R = -eps sigma+/rho^2 on positive principal stresses). No artificial viscosity, no XSPH.
* Time integration: sphstab's kick-drift-kick leapfrog written as a PySPH Integrator
  subclass (KDKIntegrator) with a PySPH IntegratorStep (KDKStep):
  v' = v^n + dt/2 a(y^n); x' = x^n + dt/2 v'; rho^{n+1} = rho^n + dt rho_dot(x', v', rho^n);
  x^{n+1} = x' + dt/2 v'; v^{n+1} = v' + dt/2 a(x^{n+1}, v', rho^{n+1}); dt = cfl dx/c.
* Growth rate: least-squares fit of ln max|v| (free particles, |v| = hypot(u, v)) against t
  over the first contiguous stretch with 1e-8 < max|v| < 1e-4, sampled every step (the
  definition of sphstab's growth_fit, src/solver/diagnostics.rs), in units of c/dx.

For each point the script also runs
`sphstab swegle --form classical --kernel m4 --h H --density-ratio F --boundary-density frozen
[--art-eps E] --until-window --json` and stores its measured and predicted rates.

Usage:
    cd analysis/pysph
    /work/pysph-venv/bin/python swegle_art_stress.py --sphstab PATH [--only h,f,eps ...]

The JSON (results-art-stress.json) is rewritten; with --only, the other points already in it
are kept.
"""

import argparse
import datetime
import json
import math
import os
import platform
import subprocess
import sys
import time

GRID_H = (1.2, 1.3)
GRID_F = (0.99, 0.95)
GRID_EPS = (0.0, 0.1, 0.2, 0.3, 0.4, 0.6)

SIZE, LAYERS, DX = 21, 3, 0.1
RHO0, BULK = 2.8, 0.686275
KICK = 1e-10
WINDOW = (1e-8, 1e-4)
ART_N = 4


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--sphstab", required=True, help="path of the sphstab binary")
    p.add_argument("--only", action="append", default=[],
                   help="run only this point, 'h,f,eps' (repeatable); the other points of "
                        "an existing JSON are kept")
    p.add_argument("--out", default="results-art-stress.json", help="output JSON")
    p.add_argument("--dt", "--cfl", dest="cfl", type=float, default=0.2,
                   help="the time step in dx/c for both codes (sphstab's --dt, default 0.2; "
                        "--cfl, its old name, is read too)")
    p.add_argument("--t-max", type=float, default=3000.0,
                   help="time limit of a PySPH run in dx/c (default 3000 = 15000 steps at "
                        "cfl 0.2); a run stops earlier when max|v| reaches the window top")
    p.add_argument("--boundary-density", choices=("frozen", "evolve"), default="frozen",
                   help="frozen (the comparison; default) or evolve: the boundary density "
                        "follows the continuity equation (a check against sphstab's "
                        "default; needs --out other than the default)")
    p.add_argument("--no-sphstab", action="store_true",
                   help="skip the sphstab runs (keep what the JSON has)")
    p.add_argument("--history", type=int, default=120,
                   help="samples of (t, max|v|) kept per PySPH run in the JSON")
    return p.parse_args(argv)


# --------------------------------------------------------------------------------------
# growth fit: the same definition as sphstab's growth_fit (src/solver/diagnostics.rs)
# --------------------------------------------------------------------------------------
def growth_fit(t, y, lo, hi):
    start = None
    for i, v in enumerate(y):
        if v > lo:
            start = i
            break
    if start is None:
        return None
    idx = []
    for i in range(start, len(y)):
        yi = y[i]
        if yi >= hi or yi != yi or yi <= 0.0:
            break
        if yi > lo:
            idx.append(i)
    if len(idx) < 3:
        return None
    n = float(len(idx))
    st = sy = stt = sty = 0.0
    for i in idx:
        ly = math.log(y[i])
        st += t[i]
        sy += ly
        stt += t[i] * t[i]
        sty += t[i] * ly
    den = n * stt - st * st
    if den <= 0.0:
        return None
    rate = (n * sty - st * sy) / den
    a = (sy - rate * st) / n
    mean = sy / n
    ss_res = sum((math.log(y[i]) - a - rate * t[i]) ** 2 for i in idx)
    ss_tot = sum((math.log(y[i]) - mean) ** 2 for i in idx)
    r2 = 1.0 - ss_res / ss_tot if ss_tot > 0 else 1.0
    return {"rate": rate, "window": (t[idx[0]], t[idx[-1]]), "samples": len(idx), "r2": r2}


# --------------------------------------------------------------------------------------
# PySPH
# --------------------------------------------------------------------------------------
from pysph.sph.integrator import Integrator
from pysph.sph.integrator_step import IntegratorStep


class KDKStep(IntegratorStep):
    """sphstab's kdk: density advanced by the mid-step (x', v'), velocity kicked twice."""

    def stage1(self, d_idx, d_x, d_y, d_u, d_v, d_au, d_av, dt):
        # half kick with a(y^n), half drift
        d_u[d_idx] += 0.5 * dt * d_au[d_idx]
        d_v[d_idx] += 0.5 * dt * d_av[d_idx]
        d_x[d_idx] += 0.5 * dt * d_u[d_idx]
        d_y[d_idx] += 0.5 * dt * d_v[d_idx]

    def stage2(self, d_idx, d_x, d_y, d_u, d_v, d_rho, d_arho, dt):
        # density with the rate at (x', v', rho^n), second half drift
        d_rho[d_idx] += dt * d_arho[d_idx]
        d_x[d_idx] += 0.5 * dt * d_u[d_idx]
        d_y[d_idx] += 0.5 * dt * d_v[d_idx]

    def stage3(self, d_idx, d_u, d_v, d_au, d_av, dt):
        # half kick with a(x^{n+1}, v', rho^{n+1})
        d_u[d_idx] += 0.5 * dt * d_au[d_idx]
        d_v[d_idx] += 0.5 * dt * d_av[d_idx]


class BoundaryRhoStep(IntegratorStep):
    """Fixed particles whose density evolves (--boundary-density evolve): the density stage
    of KDKStep only."""

    def stage1(self, d_idx, dt):
        pass

    def stage2(self, d_idx, d_rho, d_arho, dt):
        d_rho[d_idx] += dt * d_arho[d_idx]

    def stage3(self, d_idx, dt):
        pass


class KDKIntegrator(Integrator):
    """Kick-drift-kick leapfrog (sphstab `kdk`); the accelerations at the end of a step are
    those of the next step's first kick (no velocity-dependent forces here), so two rate
    evaluations per step. `initial_acceleration` must be called before the first step."""

    def one_timestep(self, t, dt):
        self.stage1()
        self.update_domain()
        self.do_post_stage(0.5 * dt, 1)

        self.compute_accelerations()
        self.stage2()
        self.update_domain()
        self.do_post_stage(dt, 2)

        self.compute_accelerations()
        self.stage3()
        self.do_post_stage(dt, 3)


_PYSPH = {}


def pysph_classes():
    """Imports the PySPH classes used (once)."""
    if _PYSPH:
        return _PYSPH
    from compyle.config import get_config
    get_config().use_openmp = False
    import pysph
    from pysph.base.kernels import CubicSpline
    from pysph.base.nnps import LinkedListNNPS
    from pysph.base.nnps_base import set_number_of_threads
    from pysph.sph.equation import Group
    from pysph.sph.basic_equations import ContinuityEquation
    from pysph.sph.solid_mech.basic import (
        IsothermalEOS, MonaghanArtificialStress, MomentumEquationWithStress,
        get_particle_array_elastic_dynamics)
    from pysph.solver.solver import Solver

    set_number_of_threads(1)   # the prebuilt NNPS is OpenMP-linked; one thread
    _PYSPH.update(dict(
        version=pysph.__version__, CubicSpline=CubicSpline, LinkedListNNPS=LinkedListNNPS,
        Group=Group, ContinuityEquation=ContinuityEquation, IsothermalEOS=IsothermalEOS,
        MonaghanArtificialStress=MonaghanArtificialStress,
        MomentumEquationWithStress=MomentumEquationWithStress,
        get_pa=get_particle_array_elastic_dynamics, Solver=Solver,
        KDKStep=KDKStep, KDKIntegrator=KDKIntegrator, BoundaryRhoStep=BoundaryRhoStep))
    return _PYSPH


def dominant_mode(fields, n):
    """The dominant standing mode of the free particles' velocity, as sphstab's
    dominant_mode_nd (src/solver/diagnostics.rs): power of the sine coefficients
    sum_ij F_ij sin(m pi (i+1)/(n+1)) sin(l pi (j+1)/(n+1)) summed over the components;
    returns ([kappa_x dx, kappa_y dx], share of the total power)."""
    import numpy as np
    k = np.arange(1, n + 1)
    s = np.sin(np.pi * np.outer(k, k) / (n + 1))       # s[m-1, i] = sin(m pi (i+1)/(n+1))
    power = sum((s @ f @ s.T) ** 2 for f in fields)
    total = float(power.sum())
    if total <= 0.0:
        return None
    m, l = np.unravel_index(int(np.argmax(power)), power.shape)
    d = math.pi / (n + 1)
    return [[float((m + 1) * d), float((l + 1) * d)], float(power[m, l]) / total]


def run_pysph(hdx, f, eps, cfl, t_max, nhist, boundary_density="frozen"):
    P = pysph_classes()
    import numpy as np

    c = math.sqrt(BULK / RHO0)
    unit = c / DX                      # rates in c/dx
    dt = cfl * DX / c
    h = hdx * DX
    kernel = P["CubicSpline"](dim=2)
    wdeltap = kernel.kernel(rij=DX, h=h)   # W(dx): PySPH's switch (-1 would turn R f^n off)
    half = (SIZE - 1) / 2.0
    idx = np.arange(SIZE)
    I, J = np.meshgrid(idx, idx, indexing="ij")
    I, J = I.ravel(), J.ravel()
    x = (I - half) * DX
    y = (J - half) * DX
    fixed = (I < LAYERS) | (I >= SIZE - LAYERS) | (J < LAYERS) | (J >= SIZE - LAYERS)
    rho = f * RHO0
    m = rho * DX * DX
    consts = dict(wdeltap=wdeltap, n=ART_N, rho_ref=RHO0)
    arrays = []
    for name, sel in (("solid", ~fixed), ("boundary", fixed)):
        pa = P["get_pa"](name=name, x=x[sel], y=y[sel], m=m, rho=rho, h=h,
                         constants=dict(consts))
        # the EOS constant: c0_ref = c = sqrt(K/rho0) (the helper derives it from E, nu)
        pa.c0_ref[0] = c
        pa.cs[:] = c
        arrays.append(pa)
    solid = arrays[0]
    centre = int(np.argmin(solid.x ** 2 + solid.y ** 2))
    assert abs(solid.x[centre]) < 1e-12 and abs(solid.y[centre]) < 1e-12
    solid.u[centre] = KICK

    both = ["solid", "boundary"]
    equations = [
        P["Group"](equations=[
            P["IsothermalEOS"](dest=d, sources=None) for d in both
        ] + [
            P["MonaghanArtificialStress"](dest=d, sources=None, eps=eps) for d in both
        ]),
        P["Group"](equations=[
            P["ContinuityEquation"](dest="solid", sources=both),
            P["MomentumEquationWithStress"](dest="solid", sources=both),
        ] + ([P["ContinuityEquation"](dest="boundary", sources=both)]
             if boundary_density == "evolve" else [])),
    ]
    steppers = dict(solid=P["KDKStep"]())
    if boundary_density == "evolve":
        steppers["boundary"] = P["BoundaryRhoStep"]()
    integrator = P["KDKIntegrator"](**steppers)
    solver = P["Solver"](dim=2, integrator=integrator, kernel=kernel, dt=dt, tf=t_max)
    nnps = P["LinkedListNNPS"](dim=2, particles=arrays, radius_scale=kernel.radius_scale,
                               domain=None, fixed_h=False, cache=False, sort_gids=False)
    solver.set_parallel_manager(None)
    t0 = time.perf_counter()
    solver.setup(particles=arrays, equations=equations, nnps=nnps, kernel=kernel,
                 fixed_h=False)
    setup_s = time.perf_counter() - t0
    integ = solver.integrator

    def vmax():
        return float(np.max(np.hypot(solid.u, solid.v)))

    t = 0.0
    ts, ys = [0.0], [max(vmax(), KICK)]
    nnps.update()
    integ.initial_acceleration(t, dt)
    # initial equilibrium check: largest |a| of the free particles at rest
    a0 = float(np.max(np.hypot(solid.au, solid.av)))
    steps_max = int(math.ceil(t_max * DX / c / dt))
    vmax_ever = 0.0
    t0 = time.perf_counter()
    steps = 0
    for s in range(steps_max):
        integ.step(t, dt)
        steps += 1
        t = (s + 1) * dt
        v = vmax()
        if not math.isfinite(v):
            break
        vmax_ever = max(vmax_ever, v)
        ts.append(t)
        ys.append(v)
        if v >= WINDOW[1]:
            break
    runtime = time.perf_counter() - t0
    nfree = SIZE - 2 * LAYERS
    # the velocity field at the end: the first step at or above the window top, where
    # sphstab takes its snapshot (or the end of the run)
    dominant = dominant_mode(
        [solid.u.reshape(nfree, nfree), solid.v.reshape(nfree, nfree)], nfree)
    fit = growth_fit(ts, ys, *WINDOW)
    stride = max(1, len(ts) // nhist)
    hist = [[ts[i] * unit, ys[i]] for i in range(0, len(ts), stride)]
    if hist[-1][0] != ts[-1] * unit:
        hist.append([ts[-1] * unit, ys[-1]])
    drho = float(np.max(np.abs(solid.rho - rho)))
    return {
        "growth_rate": fit["rate"] / unit if fit else None,
        "grew": vmax_ever > 2.0 * KICK,
        "fit_window": [fit["window"][0] * unit, fit["window"][1] * unit] if fit else None,
        "fit_window_physical": list(fit["window"]) if fit else None,
        "fit_samples": fit["samples"] if fit else 0,
        "fit_r2": fit["r2"] if fit else None,
        "steps": steps,
        "dt": dt,
        "dt_dx_over_c": dt * c / DX,
        "t_end": t,
        "t_end_dx_over_c": t * unit,
        "max_velocity_end": ys[-1],
        "max_velocity_ever": vmax_ever,
        "max_abs_drho_end": drho,
        "dominant_kappa": dominant,
        "initial_max_accel": a0,
        "wdeltap": wdeltap,
        "setup_compile_s": setup_s,
        "runtime_s": runtime,
        "history_dx_over_c_maxv": hist,
    }


# --------------------------------------------------------------------------------------
# sphstab
# --------------------------------------------------------------------------------------
def run_sphstab(path, hdx, f, eps, cfl, boundary="frozen"):
    cmd = [path, "swegle", "--form", "classical", "--kernel", "m4", "--h", repr(hdx),
           "--density-ratio", repr(f), "--boundary-density", boundary]
    if eps > 0:
        cmd += ["--art-eps", repr(eps)]
    if cfl != 0.2:
        cmd += ["--dt", repr(cfl)]
    cmd += ["--until-window", "--json"]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if p.returncode not in (0, 3):
        raise RuntimeError("sphstab failed (%d): %s" % (p.returncode, p.stderr))
    d = json.loads(p.stdout)
    c = math.sqrt(BULK / RHO0)
    unit = c / DX
    fit = d.get("fit")
    return {
        "command": " ".join(["sphstab"] + cmd[1:]),
        "measured_growth_rate": d["measured_growth_rate"],
        "predicted_growth_rate_box": d["predicted_growth_rate_box"],
        "predicted_growth_rate_infinite": d["predicted_growth_rate_infinite"],
        "box_method": d.get("box_method"),
        "grew": d["grew"],
        "fit_window": [fit["window"][0] * unit, fit["window"][1] * unit] if fit else None,
        "fit_r2": fit["r2"] if fit else None,
        "dominant_kappa": d.get("dominant_kappa"),
        "predicted_kappa_box": d.get("predicted_kappa_box"),
        "steps": d["steps"],
        # sphstab's `dt` is in dx/c; the stored `dt` is in the test's units, as PySPH's
        "dt": d["dt_physical"],
        "t_end_dx_over_c": d["steps"] * d["dt_physical"] * unit,
        "diverged": d.get("diverged"),
        "runtime_s": d["runtime_s"],
        "wall_s": wall,
    }


def sphstab_version(path):
    try:
        p = subprocess.run([path, "--version"], capture_output=True, text=True)
        return p.stdout.strip() or None
    except OSError:
        return None


def key(h, f, e):
    return (round(h, 6), round(f, 6), round(e, 6))


def summarise(runs):
    rows = []
    for r in runs:
        p, s = r["pysph"], r.get("sphstab") or {}
        g = p.get("growth_rate")
        row = {"h": r["h"], "density_ratio": r["density_ratio"], "art_eps": r["art_eps"],
               "pysph": g, "sphstab_measured": s.get("measured_growth_rate"),
               "sphstab_box": s.get("predicted_growth_rate_box")}
        row["pysph_over_sphstab_measured"] = (
            g / row["sphstab_measured"] if g and row["sphstab_measured"] else None)
        row["pysph_over_sphstab_box"] = (
            g / row["sphstab_box"] if g and row["sphstab_box"] and row["sphstab_box"] > 1e-6
            else None)
        rows.append(row)
    ratios = [x["pysph_over_sphstab_measured"] for x in rows
              if x["pysph_over_sphstab_measured"] is not None]
    out = {"rows": rows}
    if ratios:
        out["pysph_over_sphstab_measured"] = {
            "min": min(ratios), "max": max(ratios), "count": len(ratios),
            "mean": sum(ratios) / len(ratios)}
    # the epsilon of the smallest rate, per (h, f), in each code
    minima = []
    for h in sorted({x["h"] for x in rows}):
        for f in sorted({x["density_ratio"] for x in rows}):
            pts = [x for x in rows if x["h"] == h and x["density_ratio"] == f]
            if not pts:
                continue
            entry = {"h": h, "density_ratio": f}
            for k in ("pysph", "sphstab_measured", "sphstab_box"):
                vals = [(x[k], x["art_eps"]) for x in pts if x[k] is not None]
                entry["argmin_eps_" + k] = min(vals)[1] if vals else None
            minima.append(entry)
    out["minimum_over_eps"] = minima
    return out


def main(argv=None):
    args = parse_args(argv)
    if args.boundary_density != "frozen" and args.out == "results-art-stress.json":
        sys.exit("--boundary-density evolve is a check: give it its own --out")
    points = [(h, f, e) for h in GRID_H for f in GRID_F for e in GRID_EPS]
    if args.only:
        sel = []
        for o in args.only:
            h, f, e = (float(v) for v in o.split(","))
            sel.append((h, f, e))
        points = sel
    old = {}
    if os.path.exists(args.out):
        with open(args.out) as fh:
            prev = json.load(fh)
        for r in prev.get("runs", []):
            old[key(r["h"], r["density_ratio"], r["art_eps"])] = r
    P = pysph_classes()
    c = math.sqrt(BULK / RHO0)
    for (h, f, e) in points:
        print("h=%g f=%g eps=%g ..." % (h, f, e), flush=True)
        p = run_pysph(h, f, e, args.cfl, args.t_max, args.history, args.boundary_density)
        prev_run = old.get(key(h, f, e), {})
        s = prev_run.get("sphstab") if args.no_sphstab else run_sphstab(
            args.sphstab, h, f, e, args.cfl, args.boundary_density)
        old[key(h, f, e)] = {"h": h, "density_ratio": f, "art_eps": e, "art_n": ART_N,
                             "pysph": p, "sphstab": s}
        print("  PySPH %s (grew %s, fit %s dx/c, %d steps, %.1f s)  sphstab measured %s box %s"
              % ("%.5f" % p["growth_rate"] if p["growth_rate"] is not None else "none",
                 p["grew"],
                 "[%.1f, %.1f]" % tuple(p["fit_window"]) if p["fit_window"] else "-",
                 p["steps"], p["runtime_s"],
                 "%.5f" % s["measured_growth_rate"] if s and s["measured_growth_rate"]
                 is not None else "none",
                 "%.5f" % s["predicted_growth_rate_box"] if s else "-"), flush=True)
    runs = [old[k] for k in sorted(old)]
    res = {
        "pysph_version": P["version"],
        "sphstab": {"path": args.sphstab, "version": sphstab_version(args.sphstab)},
        "date_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M"),
        "python": platform.python_version(),
        "command": "cd analysis/pysph && /work/pysph-venv/bin/python swegle_art_stress.py "
                   + " ".join(sys.argv[1:] if argv is None else argv),
        "setup": {
            "reference": "V21 sec. 7.2 (sphstab swegle --boundary-density frozen)",
            "size": SIZE, "fixed_layers": LAYERS, "dx": DX, "domain": [-1.0, 1.0],
            "rho0": RHO0, "bulk_modulus": BULK, "shear_modulus": 0.0,
            "sound_speed": c, "mass": "f*rho0*dx^2", "initial_density": "f*rho0",
            "kick_vx_centre": KICK, "artificial_viscosity": None, "xsph": None,
            "kernel": "CubicSpline(dim=2) (M4, support 2h)", "h": "hdx*dx",
            "eos": "IsothermalEOS: p = c^2 (rho - rho0), c0_ref = c, rho_ref = rho0",
            "density": "ContinuityEquation (drho_a/dt = sum_b m_b v_ab . grad_a W_ab)",
            "momentum": "MomentumEquationWithStress (sum form + (R_a + R_b) f^n)",
            "artificial_stress": "MonaghanArtificialStress, R = -eps sigma+/rho^2, "
                                 "f = W(r)/W(dx), n = %d, wdeltap = W(dx, h)" % ART_N,
            "boundary": "separate array, source of every equation, destination of EOS "
                        "and artificial stress only, no integrator step (fixed, "
                        "density frozen)" if args.boundary_density == "frozen" else
                        "separate array, source of every equation, destination of EOS, "
                        "artificial stress and continuity, fixed, density stepped "
                        "(BoundaryRhoStep)",
            "boundary_density": args.boundary_density,
            "integrator": "KDKIntegrator/KDKStep (this script): sphstab's kdk leapfrog",
            "cfl": args.cfl, "dt": args.cfl * DX / c,
            "t_max_dx_over_c": args.t_max,
            "stop": "max|v| >= window top, or t_max",
            "fit_window_max_v": list(WINDOW),
            "rates_unit": "c/dx",
        },
        "runs": runs,
        "ratio_summary": summarise(runs),
    }
    with open(args.out, "w") as fh:
        json.dump(res, fh, indent=1)
        fh.write("\n")
    print("wrote %s (%d runs)" % (args.out, len(runs)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
