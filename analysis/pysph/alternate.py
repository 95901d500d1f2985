#!/usr/bin/env python3
"""PySPH against `sphstab throughput` on the same 200 x 200 block, alternated.

    /work/pysph-venv/bin/python alternate.py --sphstab ../../target/release/sphstab [--rounds 3]
        [--amplitude 0.1]

Each round runs, one process at a time: PySPH serial (non-OpenMP build, OMP_NUM_THREADS=1),
sphstab --threads 1, PySPH --openmp with OMP_NUM_THREADS=2, sphstab --threads 2. Each tool
times its own stepping loop (wall clock, after set-up, compilation and warm-up):
`elastic_block.py --json` its `ns_per_particle_step` over --steps steps, `sphstab throughput
--json` the median over --repeats repeats of --steps steps. Alternating the four runs exposes
both tools to the same drift of the machine's load; the ratios are taken per round and their
median reported, with the 1-minute load average before every run. Writes --out (JSON).
"""
import argparse, json, os, statistics, subprocess, sys, time

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--sphstab", required=True)
ap.add_argument("--rounds", type=int, default=3)
ap.add_argument("--steps", type=int, default=50)
ap.add_argument("--size", type=int, default=200)
# the initial velocity amplitude in c, the same field in both tools (1e-3: the near-static
# block of the first comparison; 0.1: particles moving as in a real run, pairs changing)
ap.add_argument("--amplitude", type=float, default=1e-3)
ap.add_argument("--out")
a = ap.parse_args()
if a.out is None:
    name = "results-alternated.json" if a.amplitude == 1e-3 else \
        f"results-alternated-A{a.amplitude:g}.json"
    a.out = os.path.join(here, name)


def load():
    return float(open("/proc/loadavg").read().split()[0])


def run(cmd, env):
    t0 = time.time()
    out = subprocess.run(cmd, env={**os.environ, **env}, capture_output=True, text=True,
                         check=True).stdout
    return json.loads(out), time.time() - t0


def pysph(threads):
    cmd = [sys.executable, os.path.join(here, "elastic_block.py"), "--steps", str(a.steps),
           "--size", str(a.size), "--amp", str(a.amplitude), "--json"] + \
        (["--openmp"] if threads > 1 else [])
    j, _ = run(cmd, {"OMP_NUM_THREADS": str(threads)})
    return j["ns_per_particle_step"]


def sphstab(threads):
    cmd = [a.sphstab, "throughput", "--threads", str(threads), "--size", str(a.size), "--steps",
           str(a.steps), "--repeats", "3", "--amplitude", str(a.amplitude), "--json"]
    j, _ = run(cmd, {})
    b = j["blocks"][0]
    return b["ns_per_particle_step"], b.get("state_bytes_per_particle")


rows = []
for r in range(a.rounds):
    row = {}
    for name, f in [("pysph_1", lambda: pysph(1)), ("sphstab_1", lambda: sphstab(1)),
                    ("pysph_2", lambda: pysph(2)), ("sphstab_2", lambda: sphstab(2))]:
        l0 = load()
        v = f()
        if isinstance(v, tuple):
            v, row["sphstab_bytes"] = v
        row[name] = v
        row[name + "_load"] = l0
        print(f"round {r + 1} {name}: {v:.1f} ns/particle-step (load {l0:.2f})", flush=True)
    row["ratio_1"] = row["pysph_1"] / row["sphstab_1"]
    row["ratio_2"] = row["pysph_2"] / row["sphstab_2"]
    rows.append(row)
med = {k: statistics.median(r[k] for r in rows)
       for k in ["pysph_1", "sphstab_1", "pysph_2", "sphstab_2", "ratio_1", "ratio_2"]}
res = {"rounds": rows, "medians": med, "command": " ".join(sys.argv),
       "date_utc": time.strftime("%Y-%m-%d %H:%M:%S", time.gmtime())}
json.dump(res, open(a.out, "w"), indent=1)
print(json.dumps(med, indent=1))
