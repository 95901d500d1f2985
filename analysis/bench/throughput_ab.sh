#!/usr/bin/env bash
# Two sphstab binaries alternated on `throughput` (1 thread): for each argument set, ROUNDS
# rounds of OLD then NEW, each `throughput ARGS --threads 1 --steps 10 --repeats 2 --json`, and
# the medians of their ns per particle-step and of the per-round ratio old/new (with its range).
# Alternating exposes both binaries to the same drift of a shared machine's load.
#
#   analysis/bench/throughput_ab.sh OLD_BIN NEW_BIN ROUNDS "ARGS" ["ARGS" ...]
#   e.g. analysis/bench/throughput_ab.sh /tmp/before/sphstab target/release/sphstab 5 \
#        "--dim 3 --size 22 --amplitude 0.1" "--amplitude 0.1 --no-pair-reuse"
#
# (To compare two revisions, build the old one in a worktree first, as compare.sh does.)
set -euo pipefail
[[ $# -ge 4 ]] || { echo "usage: $0 OLD_BIN NEW_BIN ROUNDS \"ARGS\" [\"ARGS\" ...]" >&2; exit 2; }
old=$1; new=$2; rounds=$3; shift 3
for b in "$old" "$new"; do
    [[ -x $b ]] || { echo "error: $b is not an executable" >&2; exit 2; }
done
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "error: ROUNDS must be a positive integer, got $rounds" >&2; exit 2; }
ns() {
    "$1" throughput $2 --threads 1 --steps 10 --repeats 2 --json |
        python3 -c "import json, sys; print(json.load(sys.stdin)['blocks'][0]['ns_per_particle_step'])"
}
for args in "$@"; do
    o=(); n=()
    for _ in $(seq "$rounds"); do
        o+=("$(ns "$old" "$args")")
        n+=("$(ns "$new" "$args")")
    done
    python3 - "$args" "${o[*]}" "${n[*]}" <<'PY'
import statistics as st, sys
o = [float(x) for x in sys.argv[2].split()]
n = [float(x) for x in sys.argv[3].split()]
r = [a / b for a, b in zip(o, n)]
print(f"{sys.argv[1]}: old {st.median(o):,.0f} ns, new {st.median(n):,.0f} ns; "
      f"old/new per round: median {st.median(r):.2f} (range {min(r):.2f}-{max(r):.2f})")
PY
done
