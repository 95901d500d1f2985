#!/usr/bin/env python3
"""Regenerates the analysis golden data of tests/it/golden_analysis.rs.

Each case is a list of `sphstab` arguments; its JSON output is stored with the arguments in
cases.json. The committed file was produced by the code before issue 13's performance work
(git revision 3bf5745's src/, built in release mode), with:

    cargo build --release && python3 tests/golden/analysis/generate.py target/release/sphstab

Do not regenerate it from newer code unless a result is *meant* to change (say why in the commit).
"""
import json, subprocess, sys

FORMS = ["classical", "nonlocal", "local", "lnl", "cll", "total-lagrangian",
         "eulerian-stress-points", "lagrangian-stress-points", "least-squares", "eulerian-nodal"]
KERNELS = ["m4", "m5", "m6", "wendland-c2", "wendland-c4", "wendland-c6", "gaussian", "lucy",
           "efg-cubic", "efg-quartic", "mollifier"]

cases = []
# the 1D atlas over every form and kernel (3 h × 4 σ̄ × 64 κ)
cases.append(["atlas", "--h-points", "3", "--stress-points", "4", "--kappas", "64", "--json"])
# ... and with 9 σ̄ values (the atlas interpolates the Jacobian in σ̄ from 5 values on)
cases.append(["atlas", "--h-points", "4", "--stress-points", "9", "--stress-min", "-0.9",
              "--stress-max", "0.9", "--kappas", "128", "--json"])
# 1D dispersion curves: every form × kernel, in tension and compression
for f in FORMS:
    for k in KERNELS:
        cases.append(["dispersion", "--form", f, "--kernel", k, "--h", "1.3", "--stress", "0.02",
                      "--points", "48", "--json"])
    cases.append(["dispersion", "--form", f, "--kernel", "wendland-c2", "--h", "2.1",
                  "--stress", "-0.3", "--points", "48", "--json"])
# dissipative 1D (eigenvalue route), and κ → 0 resolution
cases.append(["dispersion", "--form", "nonlocal", "--kernel", "m4", "--h", "1.3", "--av-alpha", "1",
              "--points", "48", "--json"])
cases.append(["dispersion", "--form", "classical", "--kernel", "m4", "--h", "1.3", "--delta", "0.1",
              "--points", "48", "--json"])
cases.append(["dispersion", "--form", "classical", "--kernel", "gaussian", "--h", "1.0",
              "--points", "4096", "--json"])
for f in ["classical", "nonlocal", "total-lagrangian", "least-squares"]:
    cases.append(["query", "--form", f, "--json"])
    cases.append(["timestep", "--form", f, "--json"])
# 2D and 3D
for args in (["--material", "hydro"], ["--form", "nonlocal"], ["--form", "total-lagrangian"],
             ["--lattice", "hex", "--stress", "0.05"], ["--material", "hydro", "--av-alpha", "1"],
             ["--form", "classical", "--art-eps", "0.3"]):
    cases.append(["map", "--dim", "2", "--n", "24", "--json"] + args)
    cases.append(["query", "--dim", "2", "--grid", "16", "--json"] + args)
    cases.append(["dispersion", "--dim", "2", "--points", "16", "--json"] + args)
cases.append(["map", "--n", "24", "--json"])
for args in (["--material", "hydro"], ["--lattice", "fcc", "--form", "nonlocal"]):
    cases.append(["map", "--dim", "3", "--n", "12", "--json"] + args)
    cases.append(["query", "--dim", "3", "--grid", "6", "--json"] + args)
cases.append(["map", "--dim", "3", "--n", "12", "--plane", "diagonal", "--json"])

out = []
for c in cases:
    r = subprocess.run([sys.argv[1]] + c, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{c}: exit {r.returncode}: {r.stderr}")
    out.append({"args": c, "output": json.loads(r.stdout)})
with open(__file__.rsplit("/", 1)[0] + "/cases.json", "w") as f:
    json.dump({"generated_by": "tests/golden/analysis/generate.py", "cases": out}, f)
print(f"{len(out)} cases")
