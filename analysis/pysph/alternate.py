#!/usr/bin/env python3
"""PySPH against `sphstab throughput` on the same 200 x 200 block (or 3D box), alternated.

    /work/pysph-venv/bin/python alternate.py --sphstab ../../target/release/sphstab [--rounds 3]
        [--amplitude 0.1] [--dim 3] [--size N]

--dim 3 runs sphstab's periodic 3D box (`throughput --dim 3`, default --size 30: 27,000
particles) in both tools (`elastic_block.py --dim 3`); --dim and --size are passed to both.

Each round runs, one process at a time: PySPH serial (non-OpenMP build, OMP_NUM_THREADS=1),
sphstab --threads 1, PySPH --openmp with OMP_NUM_THREADS=2, sphstab --threads 2. Each tool
times its own stepping loop (wall clock, after set-up, compilation and warm-up):
`elastic_block.py --json` its `ns_per_particle_step` over --steps steps, `sphstab throughput
--json` the median over --repeats repeats of --steps steps. Alternating the four runs exposes
both tools to the same drift of the machine's load; the ratios are taken per round and their
median reported, with the 1-minute load average before every run. Each row also keeps both
tools' neighbour counts and max|v|/c (PySPH after 1 + --steps steps, sphstab after
1 + 3 x --steps). Writes --out (JSON).
"""
import argparse, json, os, statistics, subprocess, sys, time

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--sphstab", required=True)
ap.add_argument("--rounds", type=int, default=3)
ap.add_argument("--steps", type=int, default=50)
ap.add_argument("--dim", type=int, default=2, choices=(2, 3))
ap.add_argument("--size", type=int, help="particles per side (default 200 in 2D, 30 in 3D)")
# the initial velocity amplitude in c, the same field in both tools (1e-3: the near-static
# block of the first comparison; 0.1: particles moving as in a real run, pairs changing)
ap.add_argument("--amplitude", type=float, default=1e-3)
ap.add_argument("--out")
a = ap.parse_args()
if a.size is None:
    a.size = 200 if a.dim == 2 else 30
if a.out is None:
    if a.dim == 2:
        name = "results-alternated.json" if a.amplitude == 1e-3 else \
            f"results-alternated-A{a.amplitude:g}.json"
    else:
        name = f"results-alternated-3d-A{a.amplitude:g}.json"
    a.out = os.path.join(here, name)


def load():
    return float(open("/proc/loadavg").read().split()[0])


def run(cmd, env):
    t0 = time.time()
    out = subprocess.run(cmd, env={**os.environ, **env}, capture_output=True, text=True,
                         check=True).stdout
    return json.loads(out), time.time() - t0


def pysph(threads):
    cmd = [sys.executable, os.path.join(here, "elastic_block.py"), "--dim", str(a.dim),
           "--steps", str(a.steps), "--size", str(a.size), "--amp", str(a.amplitude),
           "--json"] + (["--openmp"] if threads > 1 else [])
    j, _ = run(cmd, {"OMP_NUM_THREADS": str(threads)})
    return j["ns_per_particle_step"], {
        "neighbours": j["neighbours_mean"], "neighbours_end": j.get("neighbours_mean_end"),
        "max_speed_end": j["max_speed_over_c"]}


def sphstab(threads):
    cmd = [a.sphstab, "throughput", "--dim", str(a.dim), "--threads", str(threads), "--size",
           str(a.size), "--steps", str(a.steps), "--repeats", "3", "--amplitude",
           str(a.amplitude), "--json"]
    j, _ = run(cmd, {})
    b = j["blocks"][0]
    return b["ns_per_particle_step"], {
        "bytes": b.get("state_bytes_per_particle"), "neighbours_end": b["neighbours_per_particle"],
        "max_speed_end": b["max_speed_end"]}


rows = []
for r in range(a.rounds):
    row = {}
    for name, f in [("pysph_1", lambda: pysph(1)), ("sphstab_1", lambda: sphstab(1)),
                    ("pysph_2", lambda: pysph(2)), ("sphstab_2", lambda: sphstab(2))]:
        l0 = load()
        v, extra = f()
        tool = name.split("_")[0]
        for k, x in extra.items():
            row[f"{tool}_{k}"] = x      # the same in both thread counts; the last one kept
        row[name] = v
        row[name + "_load"] = l0
        print(f"round {r + 1} {name}: {v:.1f} ns/particle-step (load {l0:.2f})", flush=True)
    row["ratio_1"] = row["pysph_1"] / row["sphstab_1"]
    row["ratio_2"] = row["pysph_2"] / row["sphstab_2"]
    rows.append(row)
med = {k: statistics.median(r[k] for r in rows)
       for k in ["pysph_1", "sphstab_1", "pysph_2", "sphstab_2", "ratio_1", "ratio_2"]}
res = {"dim": a.dim, "size": a.size, "particles": a.size ** a.dim, "amplitude": a.amplitude,
       "steps": a.steps, "rounds": rows, "medians": med, "command": " ".join(sys.argv),
       "date_utc": time.strftime("%Y-%m-%d %H:%M:%S", time.gmtime())}
json.dump(res, open(a.out, "w"), indent=1)
print(json.dumps(med, indent=1))
