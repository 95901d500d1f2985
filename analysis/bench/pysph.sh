#!/usr/bin/env bash
# sphstab against PySPH 1.0b2 side by side on the scenes of `sphstab throughput`, in 2D and 3D
# (analysis/pysph/README.md): the 2D elastic block (the same block, kernel, h, viscosity,
# artificial stress and initial velocity field in both) and the periodic 3D box of
# `throughput --dim 3` (the same lattice, periodicity, material, kernel, h, viscosity and
# velocity field; no artificial stress), at the initial velocity amplitudes 1e-3, 0.03 and 0.1 c,
# on 1 and 2 threads: each (dimension, amplitude) is one analysis/pysph/alternate.py run (the
# four runs alternated per round, medians over ROUNDS), and the script prints one Markdown
# table of the medians, one row per dimension and amplitude.
#
#   analysis/bench/pysph.sh [ROUNDS] [PYTHON]
#
# ROUNDS: rounds per row (default 3). PYTHON: the interpreter with PySPH (default
# /work/pysph-venv/bin/python; its install: analysis/pysph/README.md).
# Environment (all optional):
#   DIMS     the dimensions to run, "2 3" (default), "2" or "3";
#   SIZE2    particles per side in 2D (default 200: 40,000 particles);
#   SIZE3    particles per side in 3D (default 30: 27,000 particles; one serial PySPH run then
#            takes ~40 s here);
#   STEPS    timed steps per run (default 50; sphstab times 3 repeats of them);
#   SPHSTAB  a sphstab binary to use; unset, the script builds this checkout first
#            (cargo build --release; CARGO_TARGET_DIR is honoured);
#   OUT      where each row's rounds and medians go, as $OUT/D<dim>-A<amplitude>.json (default
#            a new temporary directory; the committed measurements in analysis/pysph/ are not
#            overwritten).
# The full default run (2D and 3D, 3 rounds) takes ~30 minutes on the 2-core machine.
set -euo pipefail
cd "$(dirname "$0")/../.."
rounds=${1:-3}
py=${2:-/work/pysph-venv/bin/python}
dims=${DIMS:-2 3}
size2=${SIZE2:-200}
size3=${SIZE3:-30}
steps=${STEPS:-50}
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "error: ROUNDS must be a positive integer, got $rounds" >&2; exit 2; }
for v in "$size2" "$size3" "$steps"; do
    [[ $v =~ ^[1-9][0-9]*$ ]] || { echo "error: SIZE2, SIZE3 and STEPS must be positive integers, got $v" >&2; exit 2; }
done
for d in $dims; do
    [[ $d == 2 || $d == 3 ]] || { echo "error: DIMS must list 2 and/or 3, got '$dims'" >&2; exit 2; }
done
"$py" -c "import pysph" 2>/dev/null || { echo "error: $py cannot import pysph (install: analysis/pysph/README.md)" >&2; exit 2; }
if [[ -n ${SPHSTAB:-} ]]; then
    bin=$SPHSTAB
    [[ -x $bin ]] || { echo "error: SPHSTAB=$bin is not an executable" >&2; exit 2; }
else
    cargo build --release --quiet
    bin=${CARGO_TARGET_DIR:-$PWD/target}/release/sphstab
fi
outdir=${OUT:-$(mktemp -d)}
mkdir -p "$outdir"
echo "results: $outdir" >&2
echo "load at start: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
echo "| dim | particles | amplitude (c) | PySPH 1 thread (ns) | sphstab 1 thread (ns) | PySPH / sphstab, 1 thread | PySPH 2 threads (ns) | sphstab 2 threads (ns) | PySPH / sphstab, 2 threads |"
echo "|---|---|---|---|---|---|---|---|---|"
for dim in $dims; do
    if [[ $dim == 2 ]]; then size=$size2; else size=$size3; fi
    for amp in 0.001 0.03 0.1; do
        out=$outdir/D$dim-A$amp.json
        "$py" analysis/pysph/alternate.py --sphstab "$bin" --rounds "$rounds" --steps "$steps" \
            --dim "$dim" --size "$size" --amplitude "$amp" --out "$out" >&2
        "$py" - "$out" <<'EOF'
import json, sys
j = json.load(open(sys.argv[1]))
m = j["medians"]
print(f"| {j['dim']}D | {j['particles']:,} | {j['amplitude']:g} "
      f"| {m['pysph_1']:,.0f} | {m['sphstab_1']:,.0f} | {m['ratio_1']:.2f}× "
      f"| {m['pysph_2']:,.0f} | {m['sphstab_2']:,.0f} | {m['ratio_2']:.2f}× |")
EOF
    done
done
echo "load at end: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
