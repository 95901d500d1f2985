#!/usr/bin/env bash
# sphstab against PySPH 1.0b2 side by side on the 2D elastic block of `sphstab throughput`
# (analysis/pysph/README.md: the same block, kernel, h, viscosity, artificial stress and initial
# velocity field in both), at the initial velocity amplitudes 1e-3, 0.03 and 0.1 c, on 1 and 2
# threads: each amplitude is one analysis/pysph/alternate.py run (the four runs alternated per
# round, medians over ROUNDS), and the script prints one Markdown table of the medians.
#
#   analysis/bench/pysph.sh [ROUNDS] [PYTHON]
#
# ROUNDS: rounds per amplitude (default 3). PYTHON: the interpreter with PySPH (default
# /work/pysph-venv/bin/python; its install: analysis/pysph/README.md). Builds sphstab first.
# Writes each amplitude's rounds and medians to $OUT/A<amplitude>.json (OUT: default a new
# temporary directory; the committed measurements in analysis/pysph/ are not overwritten).
set -euo pipefail
cd "$(dirname "$0")/../.."
rounds=${1:-3}
py=${2:-/work/pysph-venv/bin/python}
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "error: ROUNDS must be a positive integer, got $rounds" >&2; exit 2; }
"$py" -c "import pysph" 2>/dev/null || { echo "error: $py cannot import pysph (install: analysis/pysph/README.md)" >&2; exit 2; }
cargo build --release --quiet
bin=${CARGO_TARGET_DIR:-$PWD/target}/release/sphstab
outdir=${OUT:-$(mktemp -d)}
mkdir -p "$outdir"
echo "results: $outdir" >&2
echo "load at start: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
echo "| amplitude (c) | PySPH 1 thread (ns) | sphstab 1 thread (ns) | PySPH / sphstab, 1 thread | PySPH 2 threads (ns) | sphstab 2 threads (ns) | PySPH / sphstab, 2 threads |"
echo "|---|---|---|---|---|---|---|"
for amp in 0.001 0.03 0.1; do
    out=$outdir/A$amp.json
    "$py" analysis/pysph/alternate.py --sphstab "$bin" --rounds "$rounds" --amplitude "$amp" --out "$out" >&2
    "$py" - "$out" "$amp" <<'EOF'
import json, sys
m = json.load(open(sys.argv[1]))["medians"]
print(f"| {sys.argv[2]} | {m['pysph_1']:,.0f} | {m['sphstab_1']:,.0f} | {m['ratio_1']:.2f}× "
      f"| {m['pysph_2']:,.0f} | {m['sphstab_2']:,.0f} | {m['ratio_2']:.2f}× |")
EOF
done
echo "load at end: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
