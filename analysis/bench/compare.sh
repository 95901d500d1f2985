#!/usr/bin/env bash
# Times a previous revision of sphstab against the working tree, back to back on the same
# commands, and prints per command the median CPU time (user + sys) of each and their ratio.
#
#   analysis/bench/compare.sh REV [ROUNDS] [COMMANDS_FILE]
#
# REV: any git revision (e.g. a commit before an optimisation). ROUNDS (default 5): the two
# binaries run alternately, old then new, ROUNDS times per command, so that machine load drifts
# hit both alike. COMMANDS_FILE (default analysis/bench/commands.txt): one sphstab argument list
# per line (no `cargo run`), '#' comments allowed; every command must exist in both revisions.
# Prints a Markdown table; the load average at the start and the end goes on stderr.
set -euo pipefail
cd "$(dirname "$0")/../.."
rev=${1:?usage: analysis/bench/compare.sh REV [ROUNDS] [COMMANDS_FILE]}
rounds=${2:-5}
cmds=${3:-analysis/bench/commands.txt}
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "error: ROUNDS must be a positive integer, got $rounds" >&2; exit 2; }
[[ -f $cmds ]] || { echo "error: no commands file $cmds" >&2; exit 2; }
old_sha=$(git rev-parse --verify "$rev^{commit}" 2>/dev/null) || { echo "error: unknown revision $rev" >&2; exit 2; }
work=${TMPDIR:-/tmp}/sphstab-bench-${old_sha:0:12}
if [[ ! -x $work/target/release/sphstab ]]; then
    rm -rf "$work"
    git worktree add --detach -f "$work" "$old_sha" >/dev/null
    (cd "$work" && cargo build --release --quiet)
fi
cargo build --release --quiet
old=$work/target/release/sphstab
new=$PWD/target/release/sphstab
echo "load at start: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
cpu() { # CPU seconds (user + sys, µs resolution from getrusage) of one run, output discarded
    python3 - "$@" <<'PY'
import resource, subprocess, sys
r = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
if r.returncode != 0:
    sys.stderr.write(r.stderr.decode())
    sys.exit(1)
u = resource.getrusage(resource.RUSAGE_CHILDREN)
print(u.ru_utime + u.ru_stime)
PY
}
echo "| command | old ${old_sha:0:8} (s CPU, median of $rounds) | new (s CPU) | old / new |"
echo "|---|---:|---:|---:|"
grep -v '^\s*\(#\|$\)' "$cmds" | while read -r line; do
    read -ra args <<<"$line"
    o=(); n=()
    for ((i = 0; i < rounds; i++)); do
        o+=("$(cpu "$old" "${args[@]}")")
        n+=("$(cpu "$new" "${args[@]}")")
    done
    python3 - "$line" "${#o[@]}" "${o[@]}" "${n[@]}" <<'PY'
import statistics, sys
line, k = sys.argv[1], int(sys.argv[2])
o = [float(x) for x in sys.argv[3:3 + k]]
n = [float(x) for x in sys.argv[3 + k:]]
mo, mn = statistics.median(o), statistics.median(n)
ratio = f"{mo / mn:.2f}" if mn > 0 else "n/a"
print(f"| `{line}` | {mo:.4f} | {mn:.4f} | {ratio} |")
PY
done
echo "load at end: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
