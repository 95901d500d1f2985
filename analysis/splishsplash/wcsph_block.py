#!/usr/bin/env python3
"""SPlisHSPlasH's WCSPH on a 3D block of size³ fluid particles, headless, timing the stepping loop.

    OMP_NUM_THREADS=1 /work/splish-venv/bin/python wcsph_block.py --size 30 --steps 20 [--threads 1]
        [--boundary none|particles] [--amplitude 0.1] [--json]

The counterpart of `sphstab throughput --dim 3 --material hydro --h 1.0 --amplitude 0.1`
(analysis/splishsplash/README.md): the same units (Δx = 1, ρ0 = 1, c = 1), the same simple-cubic
lattice, time step (0.2 Δx/c, fixed: no CFL adaptivity) and initial velocity field
v_a = A c sin(2π x_{a+1}/L), L = size·Δx. SPlisHSPlasH's default support radius is 4 particle
radii = 2Δx, i.e. the cubic spline of sphstab's h = 1.0Δx: 26 neighbours (self excluded) in the
lattice interior. SPlisHSPlasH has no periodic boundaries, so the block is either free
(`--boundary none`, default: no boundary particles; the particles near the six faces have fewer
neighbours) or closed by walls one spacing outside the outer particles (where the next lattice
layer would be; --wall-gap), sampled with Akinci et al. 2012 boundary particles
(`--boundary particles`).

Timed: `SimulatorBase.timeStepNoGUI()` (SPlisHSPlasH's own headless step: neighbour search,
densities, non-pressure forces, pressure, symplectic Euler update) called --steps times, wall
clock, after set-up and one warm-up step (which also does SPlisHSPlasH's z-order sort, repeated
only every 500 steps). Reports ns per fluid particle-step, the mean neighbour counts (after the
warm-up step and at the end), peak RSS, and a sanity check (finite positions, max |v|/c, largest
displacement in Δx).
"""
import argparse, json, os, sys, sysconfig, tempfile, time, resource

ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
ap.add_argument("--size", type=int, default=30, help="particles per side (default 30: 27,000)")
ap.add_argument("--steps", type=int, default=20, help="timed steps (default 20)")
ap.add_argument("--threads", type=int, default=None,
                help="OpenMP threads (sets OMP_NUM_THREADS before the library loads; default: "
                     "OMP_NUM_THREADS if set, else 1)")
ap.add_argument("--boundary", choices=["none", "particles"], default="none",
                help="none: free block (default); particles: closed box of Akinci 2012 boundary "
                     "particles at --wall-gap outside the outer fluid particles")
ap.add_argument("--wall-gap", type=float, default=1.0,
                help="--boundary particles: distance from the outer fluid particles to the walls, "
                     "in Δx (default 1: where the next lattice layer would be)")
ap.add_argument("--amplitude", type=float, default=0.1,
                help="initial velocity amplitude A in c (default 0.1, as sphstab --amplitude 0.1)")
ap.add_argument("--dt", type=float, default=0.2, help="fixed time step in Δx/c (default 0.2)")
ap.add_argument("--gamma", type=float, default=1.0,
                help="EOS exponent γ of p = B((ρ/ρ0)^γ − 1) (default 1: linear, as sphstab hydro; "
                     "B = c²ρ0/γ keeps c = 1)")
ap.add_argument("--viscosity", type=float, default=0.1,
                help="kinematic viscosity ν of SPlisHSPlasH's 'Standard' viscosity in Δx·c "
                     "(default 0.1 = α h c / (2(d+2)) for α = 1, h = Δx; 0: no viscosity method)")
ap.add_argument("--kernel", choices=["cubic", "precomputed"], default="cubic",
                help="cubic: the cubic spline evaluated (the scene loader's default); precomputed: "
                     "SPlisHSPlasH's tabulated cubic spline")
ap.add_argument("--json", action="store_true", help="one JSON object on stdout")
a = ap.parse_args()
if a.size < 4 or a.steps < 1:
    sys.exit("error: --size must be >= 4 and --steps >= 1")

threads = a.threads if a.threads is not None else int(os.environ.get("OMP_NUM_THREADS", "1"))
os.environ["OMP_NUM_THREADS"] = str(threads)  # before libgomp is loaded

# In --json mode the library's console log (std::cout) goes to stderr; the JSON to the real stdout.
json_fd = None
if a.json:
    sys.stdout.flush()
    json_fd = os.dup(1)
    os.dup2(2, 1)

import ctypes, glob
import numpy as np


def import_pysplishsplash():
    """Imports pysplishsplash with its bundled libGLdispatch preloaded (RTLD_GLOBAL).

    The wheel's extension links the GL libraries it bundles in pysplishsplash.libs/ (libOpenGL,
    libGLX, libGLdispatch, libGLU); the system's libGL.so.1, pulled in through libX11/libGLX,
    brings the system's libGLdispatch.so.0 as well, and importing with both loaded segfaults.
    Loading the bundled libGLdispatch first, globally, makes every GL library bind to that one."""
    libs = os.path.join(sysconfig.get_paths()["platlib"], "pysplishsplash.libs")
    found = sorted(glob.glob(os.path.join(libs, "libGLdispatch-*.so*")))
    if not found:
        sys.exit(f"error: no libGLdispatch-*.so* in {libs} (is pysplishsplash installed in "
                 f"{sys.prefix}?)")
    ctypes.CDLL(found[0], mode=ctypes.RTLD_GLOBAL)
    import pysplishsplash
    gomp = sorted(glob.glob(os.path.join(libs, "libgomp-*.so*")))
    return pysplishsplash, found[0], (gomp[0] if gomp else None)


def rss_kib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss  # KiB on Linux


def current_rss_kib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


sph, gldispatch, gomp_path = import_pysplishsplash()
try:
    from importlib.metadata import version as _version
    version = _version("pysplishsplash")
except Exception:  # noqa: BLE001 (metadata missing: report unknown)
    version = None
omp_threads = None
if gomp_path:
    try:
        omp_threads = ctypes.CDLL(gomp_path).omp_get_max_threads()
    except (OSError, AttributeError):
        pass
rss_after_import = current_rss_kib()

n = a.size
dx, r = 1.0, 0.5           # SPlisHSPlasH's particle radius is Δx/2; its support radius 4r = 2Δx
L = n * dx
rho0, c = 1.0, 1.0
stiffness = c * c * rho0 / a.gamma
models = os.path.join(sysconfig.get_paths()["scripts"], "data", "models")
tmp = tempfile.TemporaryDirectory(prefix="wcsph_block_")
material = {"id": "Fluid", "density0": rho0, "maxEmitterParticles": 0,
            "viscosityMethod": 1 if a.viscosity > 0 else 0, "vorticityMethod": 0,
            "surfaceTensionMethod": 0, "dragMethod": 0, "elasticityMethod": 0}
if a.viscosity > 0:
    material["Standard viscosity"] = {"viscosity": a.viscosity, "viscosityBoundary": 0.0}
kernel = 0 if a.kernel == "cubic" else 4
scene = {
    "Configuration": {
        "particleRadius": r, "sim2D": False, "simulationMethod": 0,        # 0: WCSPH
        "timeStepSize": a.dt, "cflMethod": 0,                               # 0: no CFL adaptivity
        "gravitation": [0.0, 0.0, 0.0], "boundaryHandlingMethod": 0,        # 0: Akinci 2012
        "enableZSort": True,
        "WCSPH": {"stiffness": stiffness, "exponent": a.gamma},
        # no exporter is active by default: the output directory gets only log/ (checked)
    },
    "Materials": [material],
    # regular sampling of a block fills (start, end) with particles at start + Δx, ...: this box
    # puts n particles per axis at x = 0, 1, ..., n−1 (the lattice of sphstab's block)
    "FluidBlocks": [{"id": "Fluid", "denseMode": 0, "start": [-dx] * 3, "end": [L] * 3}],
}
if a.boundary == "particles":
    scene["RigidBodies"] = [{
        "geometryFile": os.path.join(models, "UnitBox.obj"),
        # walls at −g and (n − 1)Δx + g, g = --wall-gap·Δx
        "translation": [(L - dx) / 2] * 3, "scale": [L - dx + 2 * a.wall_gap * dx] * 3,
        "isDynamic": False, "isWall": True, "mapInvert": True, "mapThickness": 0.0,
        "mapResolution": [20, 20, 20]}]
scene_file = os.path.join(tmp.name, "block.json")
with open(scene_file, "w") as f:
    json.dump(scene, f, indent=1)

t_setup = time.perf_counter()
base = sph.Exec.SimulatorBase()
base.init(sceneFile=scene_file, useGui=False, outputDir=tmp.name, initialPause=False,
          useCache=False, stopAt=-1.0)
base.initSimulation()
sim = sph.Simulation.getCurrent()
fm = sim.getFluidModel(0)
N = fm.numActiveParticles()
if N != n ** 3:
    sys.exit(f"error: SPlisHSPlasH sampled {N} fluid particles, expected {n ** 3}")
tm = sph.TimeManager.getCurrent()

# the initial velocity field of sphstab's periodic block: v_a = A c sin(2π x_{a+1} / L)
x = np.asarray(fm.getFieldBuffer("position"))[:N]
v = np.asarray(fm.getFieldBuffer("velocity"))
if v.dtype != np.float32 and v.dtype != np.float64:
    sys.exit(f"error: unexpected velocity buffer type {v.dtype}")
real_bytes = v.dtype.itemsize
for ax in range(3):
    v[:N, ax] = a.amplitude * c * np.sin(2 * np.pi * x[:, (ax + 1) % 3] / L)
x0 = x.copy()                            # the script's own copies (16 B per particle, in the RSS)
x0_ids = np.asarray(fm.getFieldBuffer("id"))[:N].copy()

# the scene loader does not apply "kernel"/"gradKernel" from the scene file: set them here
sim.setValueInt(sim.KERNEL_METHOD, kernel)
sim.setValueInt(sim.GRAD_KERNEL_METHOD, kernel)
settings = {k: sim.getValueInt(getattr(sim, k)) for k in
            ["SIMULATION_METHOD", "KERNEL_METHOD", "GRAD_KERNEL_METHOD", "CFL_METHOD",
             "BOUNDARY_HANDLING_METHOD"]}
ts = sim.getTimeStep()
settings["stiffness"] = ts.getValueFloat(ts.STIFFNESS)
settings["exponent"] = ts.getValueFloat(ts.EXPONENT)
settings["enable_z_sort"] = sim.getValueBool(sim.ENABLE_Z_SORT)
settings["steps_per_z_sort"] = sim.getValueUInt(2) if sim.getName(2) == "stepsPerZSort" else None
if (settings["KERNEL_METHOD"], settings["GRAD_KERNEL_METHOD"]) != (kernel, kernel):
    sys.exit(f"error: kernel method {settings['KERNEL_METHOD']}, expected {kernel}")
settings["support_radius"] = sim.getSupportRadius()
settings["time_step"] = tm.getTimeStepSize()
settings["VISCOSITY_METHOD"] = fm.getValueInt(fm.VISCOSITY_METHOD)
visc = fm.getViscosityBase()
if visc is not None and hasattr(visc, "VISCOSITY_COEFFICIENT"):
    settings["viscosity"] = visc.getValueFloat(visc.VISCOSITY_COEFFICIENT)
    settings["viscosity_boundary"] = visc.getValueFloat(visc.VISCOSITY_COEFFICIENT_BOUNDARY)
if settings["SIMULATION_METHOD"] != 0 or settings["CFL_METHOD"] != 0:
    sys.exit(f"error: not WCSPH with a fixed step: {settings}")


def mean_neighbours():
    """Mean neighbours per fluid particle (self excluded) from the last neighbour search: fluid
    neighbours, and boundary-particle neighbours."""
    sets = sim.numberOfPointSets()
    counts = [0] * sets
    for k in range(sets):
        counts[k] = sum(sim.numberOfNeighbors(0, k, i) for i in range(N)) / N
    return counts[0], sum(counts[1:])


# warm-up: runSimulation() makes SPlisHSPlasH's deferred initialisation (needed before a step)
# and steps until t > stopAt; stopAt = dt/2 gives exactly one step.
base.setValueFloat(base.STOP_AT, 0.5 * settings["time_step"])
base.runSimulation()
base.setValueFloat(base.STOP_AT, -1.0)
warm_steps = round(tm.getTime() / settings["time_step"])
setup_s = time.perf_counter() - t_setup
# point set 0 is the fluid, the others the boundary models' particles (created in the deferred
# initialisation, so counted only now)
nsearch = sim.getNeighborhoodSearch()
nb_boundary = sum(nsearch.numberOfPointsInSet(k) for k in range(1, sim.numberOfPointSets()))
nf0, nbd0 = mean_neighbours()

t0 = time.perf_counter()
for _ in range(a.steps):
    base.timeStepNoGUI()
elapsed = time.perf_counter() - t0
nf1, nbd1 = mean_neighbours()
peak = rss_kib()

x = np.asarray(fm.getFieldBuffer("position"))[:N].astype(np.float64)
v = np.asarray(fm.getFieldBuffer("velocity"))[:N].astype(np.float64)
ids = np.asarray(fm.getFieldBuffer("id"))[:N]
start = np.empty(x0.shape)
start[x0_ids] = x0                       # z-sort reorders the particles; ids do not change
disp = np.linalg.norm(x - start[ids], axis=1)
finite = bool(np.isfinite(x).all() and np.isfinite(v).all())
speed = np.linalg.norm(v, axis=1)
ns = elapsed / (N * a.steps) * 1e9
res = {
    "tool": "SPlisHSPlasH", "version": version,
    "method": "WCSPH", "real_bytes": real_bytes, "precision": "single" if real_bytes == 4 else "double",
    "boundary": a.boundary, "size": n, "particles": N, "boundary_particles": nb_boundary,
    "steps": a.steps, "warmup_steps": warm_steps, "threads": threads,
    "omp_max_threads": omp_threads, "gl_preloaded": gldispatch, "kernel": a.kernel, "amplitude": a.amplitude,
    "viscosity": a.viscosity, "settings": settings,
    "seconds": elapsed, "seconds_per_step": elapsed / a.steps,
    "ns_per_particle_step": ns, "particle_steps_per_second": N * a.steps / elapsed,
    "setup_seconds": setup_s,
    "neighbours_fluid_start": nf0, "neighbours_boundary_start": nbd0,
    "neighbours_fluid_end": nf1, "neighbours_boundary_end": nbd1,
    "neighbours_per_particle": nf1 + nbd1,
    "peak_rss_bytes": peak * 1024, "rss_after_import_bytes": rss_after_import * 1024,
    "rss_bytes_per_particle": peak * 1024 / N,
    "rss_net_bytes_per_particle": (peak - rss_after_import) * 1024 / N,
    "finite": finite, "max_speed_end": float(speed.max()) / c,
    "max_displacement": float(disp.max()) / dx, "mean_displacement": float(disp.mean()) / dx,
    "units": {"ns_per_particle_step": "ns (wall clock) per fluid particle-step",
              "neighbours_*": "per fluid particle, self excluded", "max_speed_end": "c",
              "*_displacement": "dx", "time_step": "dx/c", "support_radius": "dx"},
}
if a.json:
    os.write(json_fd, (json.dumps(res, indent=1) + "\n").encode())
else:
    print(f"SPlisHSPlasH WCSPH ({res['precision']} precision), {N:,} fluid particles "
          f"({n}³), boundary {a.boundary} ({nb_boundary:,} boundary particles), "
          f"{threads} thread(s) (omp_get_max_threads {omp_threads})")
    print(f"  {a.steps} steps in {elapsed:.3f} s: {ns:,.1f} ns per particle-step, "
          f"{N * a.steps / elapsed:,.0f} particle-steps/s (set-up {setup_s:.1f} s)")
    print(f"  neighbours per fluid particle (self excluded): fluid {nf0:.2f} → {nf1:.2f}, "
          f"boundary {nbd0:.2f} → {nbd1:.2f}")
    print(f"  peak RSS {peak / 1024:.1f} MiB ({peak * 1024 / N:,.0f} B per particle; "
          f"{(peak - rss_after_import) * 1024 / N:,.0f} B above the RSS after import)")
    print(f"  sanity: finite {finite}, max|v| {res['max_speed_end']:.3f} c, displacement max "
          f"{res['max_displacement']:.3f} Δx, mean {res['mean_displacement']:.3f} Δx")
sys.stdout.flush()
sys.stderr.flush()
if os.environ.get("WCSPH_BLOCK_KEEP"):
    print("output directory kept:", tmp.name, os.listdir(tmp.name), file=sys.stderr)
else:
    tmp.cleanup()
# skip SPlisHSPlasH's teardown (it prints timing tables to stdout and frees the scene)
os._exit(0 if finite else 1)
