#!/usr/bin/env bash
# sphstab against SPlisHSPlasH 2.19's WCSPH (pysplishsplash from PyPI) side by side on a 3D block
# (analysis/splishsplash/README.md: the same lattice, units, support radius 2Δx (~26 neighbours),
# time step and initial velocity field at 0.1 c in both; sphstab periodic, SPlisHSPlasH a free
# block and a walled box), at 30³ and 50³ particles, on 1 and 2 threads: one
# analysis/splishsplash/alternate.py run (all runs alternated per round, medians over ROUNDS), and
# the script prints one Markdown table of the medians.
#
#   analysis/bench/splishsplash.sh [ROUNDS] [PYTHON]
#
# ROUNDS: rounds (default 3). PYTHON: the interpreter with pysplishsplash (default
# /work/splish-venv/bin/python; its install: analysis/splishsplash/README.md). The sphstab binary:
# $SPHSTAB if set, else `cargo build --release` here and ${CARGO_TARGET_DIR:-target}/release/sphstab.
# Writes the rounds and medians to $OUT (default a new temporary file). For a quick check,
# SIZES (default 30,50) and STEPS (timed steps per run, default 20) are passed to alternate.py.
set -euo pipefail
cd "$(dirname "$0")/../.."
rounds=${1:-3}
py=${2:-/work/splish-venv/bin/python}
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "error: ROUNDS must be a positive integer, got $rounds" >&2; exit 2; }
command -v "$py" >/dev/null 2>&1 || { echo "error: no Python interpreter $py (install: analysis/splishsplash/README.md)" >&2; exit 2; }
# the package's metadata only: importing pysplishsplash needs its GL library preloaded (wcsph_block.py does that)
"$py" -c "import importlib.metadata as m; m.version('pysplishsplash')" >/dev/null 2>&1 \
    || { echo "error: $py has no pysplishsplash (install: analysis/splishsplash/README.md)" >&2; exit 2; }
if [[ -n ${SPHSTAB:-} ]]; then
    bin=$SPHSTAB
else
    cargo build --release --quiet || { echo "error: cargo build --release failed" >&2; exit 2; }
    bin=${CARGO_TARGET_DIR:-$PWD/target}/release/sphstab
fi
[[ -x $bin ]] || { echo "error: no sphstab binary at $bin" >&2; exit 2; }
out=${OUT:-$(mktemp --suffix=.json)}
echo "results: $out" >&2
echo "load at start: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
"$py" analysis/splishsplash/alternate.py --sphstab "$bin" --rounds "$rounds" --out "$out" \
    --sizes "${SIZES:-30,50}" --steps "${STEPS:-20}" >&2 \
    || exit 2  # alternate.py has printed its one-line error
echo "load at end: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
"$py" - "$out" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))
meta = r["meta"]
print(f"SPlisHSPlasH {meta['splish_version']} ({meta['splish_precision']} precision) WCSPH "
      f"against `sphstab throughput --dim 3 --material hydro --h 1.0 --amplitude {meta['amplitude']}`, "
      f"{meta['steps']} timed steps, medians over {len(r['rounds'])} round(s); ns per particle-step "
      f"(wall clock), bytes per particle (sphstab: allocator peak; SPlisHSPlasH: peak RSS above "
      f"the RSS after import), neighbours per particle self excluded.")
print()
print("| particles | threads | SPlisHSPlasH scene (boundary particles) | SPlisHSPlasH (ns) | sphstab (ns) "
      "| SPlisHSPlasH / sphstab | sphstab slower by | neighbours SPlisHSPlasH / sphstab "
      "| bytes per particle SPlisHSPlasH / sphstab | memory sphstab / SPlisHSPlasH |")
print("|---|---|---|---|---|---|---|---|---|---|")
for m in r["medians"].values():
    scene = "free block" if m["boundary"] == "none" else "walled box"
    print(f"| {m['particles']:,} | {m['threads']} | {scene} ({m['boundary_particles']:,}) "
          f"| {m['splish_ns']:,.0f} | {m['sphstab_ns']:,.0f} | {m['ratio_time']:.2f} "
          f"| {1 / m['ratio_time']:.2f}× | {m['splish_neighbours']:.1f} / {m['sphstab_neighbours']:.1f} "
          f"| {m['splish_bytes']:,.0f} / {m['sphstab_bytes']:,.0f} | {m['ratio_memory']:.2f} |")
EOF
