#!/usr/bin/env bash
# Times a previous revision of sphstab against the working tree, back to back on the same
# commands, and prints per command the median CPU time (user + sys) and the median wall-clock
# time of each, and their ratios (CPU measures work; wall measures what a user waits, including
# the use of both cores). The child is started with posix_spawn and reaped with wait4, so its
# rusage is its own (a fork of the Python interpreter would add ~50 ms of CPU to each run).
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
cpu() { # "CPU wall" seconds of one run (CPU = user + sys from wait4's rusage), output discarded
    python3 - "$@" <<'PY'
import os, sys, time
devnull = os.open(os.devnull, os.O_WRONLY)
t = time.perf_counter()
pid = os.posix_spawn(sys.argv[1], sys.argv[1:], os.environ,
                     file_actions=[(os.POSIX_SPAWN_DUP2, devnull, 1)])
_, status, ru = os.wait4(pid, 0)
w = time.perf_counter() - t
if os.waitstatus_to_exitcode(status) != 0:
    sys.exit(f"failed: {' '.join(sys.argv[1:])}")
print(f"{ru.ru_utime + ru.ru_stime} {w}")
PY
}
echo "| command | old ${old_sha:0:8} CPU s (median of $rounds) | new CPU s | CPU old / new | old wall s | new wall s | wall old / new |"
echo "|---|---:|---:|---:|---:|---:|---:|"
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
o = [tuple(map(float, x.split())) for x in sys.argv[3:3 + k]]
n = [tuple(map(float, x.split())) for x in sys.argv[3 + k:]]
med = lambda v, i: statistics.median(x[i] for x in v)
r = lambda a, b: f"{a / b:.2f}" if b > 0 else "n/a"
co, cn, wo, wn = med(o, 0), med(n, 0), med(o, 1), med(n, 1)
print(f"| `{line}` | {co:.4f} | {cn:.4f} | {r(co, cn)} | {wo:.4f} | {wn:.4f} | {r(wo, wn)} |")
PY
done
echo "load at end: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
