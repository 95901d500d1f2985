#!/usr/bin/env python3
"""SPlisHSPlasH's WCSPH against `sphstab throughput --dim 3` on the same 3D block, alternated.

    /work/splish-venv/bin/python alternate.py --sphstab /work/targets/main/release/sphstab
        [--rounds 3] [--sizes 30,50] [--threads 1,2] [--boundaries none,particles] [--steps 20]
        [--out FILE]

Each round runs, one process at a time, for every size and thread count: wcsph_block.py once per
--boundaries entry (SPlisHSPlasH with OMP_NUM_THREADS = threads), then
`sphstab throughput --dim 3 --material hydro --h 1.0 --size S --amplitude 0.1 --threads T
--steps N --repeats 1 --json`. Both time one loop of --steps steps after one warm-up step (wall
clock, set-up excluded) and report ns per particle-step. Alternating exposes both tools to the
same drift of the machine's load; ratios are taken per round and their medians reported, with
the 1-minute load average before every run.

Ratios: time SPlisHSPlasH ns / sphstab ns per particle-step (below 1: SPlisHSPlasH faster);
memory sphstab / SPlisHSPlasH bytes per particle, from sphstab's allocator peak
(`bytes_per_particle`) and SPlisHSPlasH's peak RSS above the RSS after `import pysplishsplash`
(`rss_net_bytes_per_particle`). The whole-process peak RSS of both (wait4) is recorded too.
Neighbour counts are reported self excluded for both (sphstab's `neighbours_per_particle`
counts the particle itself; 1 is subtracted). Writes --out (JSON; default a new temporary file).
"""
import argparse, json, os, statistics, subprocess, sys, tempfile, time

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--sphstab", required=True, help="the sphstab binary")
ap.add_argument("--rounds", type=int, default=3)
ap.add_argument("--steps", type=int, default=20, help="timed steps of each run (default 20)")
ap.add_argument("--sizes", default="30,50", help="particles per side, comma-separated")
ap.add_argument("--threads", default="1,2", help="thread counts, comma-separated")
ap.add_argument("--boundaries", default="none,particles",
                help="SPlisHSPlasH scenes (wcsph_block.py --boundary), comma-separated")
ap.add_argument("--amplitude", type=float, default=0.1, help="initial velocity amplitude in c")
ap.add_argument("--out", help="JSON results (default: a new temporary file)")
a = ap.parse_args()
sizes = [int(s) for s in a.sizes.split(",")]
threads = [int(t) for t in a.threads.split(",")]
boundaries = a.boundaries.split(",")
if a.rounds < 1 or a.steps < 1 or not sizes or not threads:
    sys.exit("error: --rounds, --steps must be >= 1 and --sizes, --threads non-empty")
for b in boundaries:
    if b not in ("none", "particles"):
        sys.exit(f"error: unknown boundary {b!r} (none, particles)")
if a.out is None:
    fd, a.out = tempfile.mkstemp(prefix="splishsplash-alternate-", suffix=".json")
    os.close(fd)


def load():
    with open("/proc/loadavg") as f:
        return float(f.read().split()[0])


def run(cmd, env):
    """Runs cmd, returns (its stdout parsed as JSON, its peak RSS in bytes)."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        p = subprocess.Popen(cmd, env={**os.environ, **env}, stdout=out, stderr=err)
        _, status, usage = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        if p.returncode != 0:
            tail = err.read().decode(errors="replace").strip().splitlines()[-3:]
            raise SystemExit(f"error: {' '.join(cmd)} exited {p.returncode}: {' | '.join(tail)}")
        return json.loads(out.read()), usage.ru_maxrss * 1024


def splish(size, t, boundary):
    cmd = [sys.executable, os.path.join(here, "wcsph_block.py"), "--size", str(size), "--steps",
           str(a.steps), "--threads", str(t), "--boundary", boundary, "--amplitude",
           str(a.amplitude), "--json"]
    j, rss = run(cmd, {"OMP_NUM_THREADS": str(t)})
    if not j["finite"]:
        raise SystemExit(f"error: SPlisHSPlasH {size}³ {boundary}: non-finite positions")
    return {"ns": j["ns_per_particle_step"], "bytes": j["rss_net_bytes_per_particle"],
            "rss_bytes": rss / j["particles"], "neighbours": j["neighbours_per_particle"],
            "neighbours_fluid": j["neighbours_fluid_end"],
            "boundary_particles": j["boundary_particles"], "max_speed_end": j["max_speed_end"],
            "precision": j["precision"], "version": j["version"]}


def sphstab(size, t):
    cmd = [a.sphstab, "throughput", "--dim", "3", "--material", "hydro", "--h", "1.0", "--size",
           str(size), "--amplitude", str(a.amplitude), "--threads", str(t), "--steps",
           str(a.steps), "--repeats", "1", "--json"]
    j, rss = run(cmd, {})
    b = j["blocks"][0]
    return {"ns": b["ns_per_particle_step"], "bytes": b["bytes_per_particle"],
            "state_bytes": b["state_bytes_per_particle"], "rss_bytes": rss / b["particles"],
            "neighbours": b["neighbours_per_particle"] - 1.0,
            "full_builds_per_step": b["full_builds_per_step"],
            "max_speed_end": b["max_speed_end"], "domain": j["domain"]}


keys = [(s, t, b) for s in sizes for t in threads for b in boundaries]
rows = []
for r in range(a.rounds):
    row = {}
    for s in sizes:
        for t in threads:
            for b in boundaries:
                l0 = load()
                v = splish(s, t, b)
                v["load"] = l0
                row[f"splish_{s}_{t}_{b}"] = v
                print(f"round {r + 1} SPlisHSPlasH {s}³ {t} thread(s) boundary {b}: "
                      f"{v['ns']:,.1f} ns/particle-step, {v['bytes']:,.0f} B/particle, "
                      f"{v['neighbours']:.2f} neighbours (load {l0:.2f})", flush=True)
            l0 = load()
            v = sphstab(s, t)
            v["load"] = l0
            row[f"sphstab_{s}_{t}"] = v
            print(f"round {r + 1} sphstab {s}³ {t} thread(s): {v['ns']:,.1f} ns/particle-step, "
                  f"{v['bytes']:,.0f} B/particle, {v['neighbours']:.2f} neighbours "
                  f"(load {l0:.2f})", flush=True)
            for b in boundaries:
                sp, st = row[f"splish_{s}_{t}_{b}"], row[f"sphstab_{s}_{t}"]
                row[f"ratio_time_{s}_{t}_{b}"] = sp["ns"] / st["ns"]
                row[f"ratio_memory_{s}_{t}_{b}"] = st["bytes"] / sp["bytes"]
    rows.append(row)

med = {}
for s, t, b in keys:
    sp = [row[f"splish_{s}_{t}_{b}"] for row in rows]
    st = [row[f"sphstab_{s}_{t}"] for row in rows]
    med[f"{s}_{t}_{b}"] = {
        "size": s, "particles": s ** 3, "threads": t, "boundary": b,
        "boundary_particles": sp[0]["boundary_particles"],
        "splish_ns": statistics.median(x["ns"] for x in sp),
        "sphstab_ns": statistics.median(x["ns"] for x in st),
        "ratio_time": statistics.median(row[f"ratio_time_{s}_{t}_{b}"] for row in rows),
        "splish_bytes": statistics.median(x["bytes"] for x in sp),
        "sphstab_bytes": statistics.median(x["bytes"] for x in st),
        "ratio_memory": statistics.median(row[f"ratio_memory_{s}_{t}_{b}"] for row in rows),
        "splish_rss_bytes": statistics.median(x["rss_bytes"] for x in sp),
        "sphstab_rss_bytes": statistics.median(x["rss_bytes"] for x in st),
        "splish_neighbours": statistics.median(x["neighbours"] for x in sp),
        "sphstab_neighbours": statistics.median(x["neighbours"] for x in st),
        "loads": [x["load"] for x in sp] + [x["load"] for x in st],
    }
first = rows[0]
meta = {"splish_version": next(v["version"] for k, v in first.items() if k.startswith("splish_")),
        "splish_precision": next(v["precision"] for k, v in first.items()
                                 if k.startswith("splish_")),
        "sphstab": a.sphstab, "steps": a.steps, "amplitude": a.amplitude}
res = {"rounds": rows, "medians": med, "meta": meta, "command": " ".join(sys.argv),
       "date_utc": time.strftime("%Y-%m-%d %H:%M:%S", time.gmtime())}
with open(a.out, "w") as f:
    json.dump(res, f, indent=1)
print(f"results: {a.out}")
for k, m in med.items():
    print(f"{m['particles']:>7,} particles, {m['threads']} thread(s), SPlisHSPlasH boundary "
          f"{m['boundary']} ({m['boundary_particles']:,} boundary particles): SPlisHSPlasH "
          f"{m['splish_ns']:,.0f} ns, sphstab {m['sphstab_ns']:,.0f} ns per particle-step, "
          f"SPlisHSPlasH / sphstab {m['ratio_time']:.2f} (sphstab {1 / m['ratio_time']:.2f}× "
          f"slower); memory sphstab / SPlisHSPlasH {m['ratio_memory']:.2f} "
          f"({m['sphstab_bytes']:,.0f} / {m['splish_bytes']:,.0f} B per particle); neighbours "
          f"{m['splish_neighbours']:.1f} / {m['sphstab_neighbours']:.1f}")
