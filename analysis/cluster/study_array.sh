#!/usr/bin/env bash
#SBATCH --job-name=sphstab-shard
#SBATCH --cpus-per-task=2
#SBATCH --mem=4G
#SBATCH --time=02:00:00
#SBATCH --output=sphstab-shard-%A_%a.log
#
# Runs a long sphstab study (pairing, tradeoff, art-stress, atlas) in N shards — as a Slurm job
# array, with GNU parallel or a plain loop on one machine — and merges them into the report of
# the unsharded run (the same JSON bytes apart from runtime_s and threads, and for tradeoff the
# measured costs). Run it from the repository root, after `cargo build --release`.
#
#   analysis/cluster/study_array.sh shard I/N DIR STUDY [FLAGS...]   shard I of N -> DIR/shard-I-of-N.json
#   analysis/cluster/study_array.sh shard N DIR STUDY [FLAGS...]     the same, I = $SLURM_ARRAY_TASK_ID
#   analysis/cluster/study_array.sh merge N DIR [MERGE FLAGS...]     sphstab merge of the N files
#   analysis/cluster/study_array.sh local N DIR STUDY [FLAGS...]     every shard here (GNU parallel
#                                                                    if installed), then merge
#
# Slurm (16 array tasks, then the merge once they all succeeded):
#
#   jid=$(sbatch --parsable --array=0-15 analysis/cluster/study_array.sh shard 16 shards/pairing pairing --config analysis/pairing3d.json)
#   sbatch --dependency=afterok:$jid analysis/cluster/study_array.sh merge 16 shards/pairing
#
# GNU parallel or a loop on one machine (JOBS shards at a time share the cores, see below):
#
#   parallel -j 2 analysis/cluster/study_array.sh shard {}/8 shards/pairing pairing --config analysis/pairing3d.json ::: $(seq 0 7)
#   for i in $(seq 0 7); do analysis/cluster/study_array.sh shard $i/8 shards/pairing pairing --config analysis/pairing3d.json; done
#   analysis/cluster/study_array.sh merge 8 shards/pairing
#   JOBS=2 analysis/cluster/study_array.sh local 8 shards/pairing pairing --config analysis/pairing3d.json
#
# The merge prints what the study prints (its table; --json: the JSON; --out FILE: the JSON to a
# file), and for a study run from an analysis config with an `output` it writes the figure and
# its data into figures/, as the unsharded run does. It refuses missing, repeated or foreign
# shards; this script first names the missing ones and the array tasks that rerun them.
#
# Environment:
#   SPHSTAB      the binary (default: target/release/sphstab, else sphstab on the PATH)
#   MAX_MEMORY   --max-memory of every shard (default 2G). Shards merge only when they ran within
#                one budget, so it is fixed here rather than left to each node's RAM.
#   MAX_STEPS    --max-steps of every shard (default: sphstab's)
#   JOBS         shards at a time in `local` (default 1); each gets RAYON_NUM_THREADS = cores/JOBS
#   FORCE=1      recompute a shard whose file exists (default: keep it, so a requeued array
#                computes only what is missing)
#
# tradeoff times its scenes: its cost columns compare across configurations only when every shard
# runs on the same kind of machine, with its cores to itself (JOBS=1, or identical nodes).

set -euo pipefail

die() {
    echo "study_array.sh: $*" >&2
    exit 2
}

if [[ -n "${SPHSTAB:-}" ]]; then
    bin=$SPHSTAB
elif [[ -x target/release/sphstab ]]; then
    bin=target/release/sphstab
else
    bin=$(command -v sphstab) || die "no sphstab binary: run cargo build --release, or set SPHSTAB"
fi

budget=(--max-memory "${MAX_MEMORY:-2G}")
if [[ -n "${MAX_STEPS:-}" ]]; then
    budget+=(--max-steps "$MAX_STEPS")
fi

is_count() {
    [[ $1 =~ ^[1-9][0-9]*$ ]]
}

# shard file of shard $1 of $2 in $3
shard_file() {
    echo "$3/shard-$1-of-$2.json"
}

# one shard: $1 = I/N or N (I from Slurm), $2 = DIR, then the study and its flags
run_shard() {
    local spec=$1 dir=$2 i n
    shift 2
    [[ $# -ge 1 ]] || die "shard: give the study and its flags after DIR"
    if [[ $spec == */* ]]; then
        i=${spec%/*}
        n=${spec#*/}
    else
        n=$spec
        i=${SLURM_ARRAY_TASK_ID:?shard N needs \$SLURM_ARRAY_TASK_ID (or give I/N)}
    fi
    if ! [[ $i =~ ^[0-9]+$ ]] || ! is_count "$n" || ((10#$i >= n)); then
        die "shard: '$spec' must be I/N with 0 <= I < N, or N"
    fi
    i=$((10#$i))
    if [[ -n "${SLURM_CPUS_PER_TASK:-}" && -z "${RAYON_NUM_THREADS:-}" ]]; then
        export RAYON_NUM_THREADS=$SLURM_CPUS_PER_TASK
    fi
    mkdir -p "$dir"
    local out
    out=$(shard_file "$i" "$n" "$dir")
    if [[ -s $out && "${FORCE:-0}" != 1 ]]; then
        echo "$out exists (FORCE=1 recomputes it)"
        return 0
    fi
    # written under a temporary name and renamed: a task killed half-way leaves no shard
    rm -f "$out" "$out.part"
    "$bin" "${budget[@]}" "$@" --shard "$i/$n" --out "$out.part"
    mv "$out.part" "$out"
}

# merge: $1 = N, $2 = DIR, then merge's flags
merge() {
    local n=$1 dir=$2 i missing=() files=()
    shift 2
    is_count "$n" || die "merge: N = '$n' must be a positive integer"
    for ((i = 0; i < n; i++)); do
        files+=("$(shard_file "$i" "$n" "$dir")")
        [[ -s ${files[-1]} ]] || missing+=("$i")
    done
    if ((${#missing[@]} > 0)); then
        local list
        list=$(
            IFS=,
            echo "${missing[*]}"
        )
        die "merge: shards $list of $n are missing in $dir (rerun them, e.g. sbatch --array=$list ...)"
    fi
    "$bin" "${budget[@]}" merge "${files[@]}" "$@"
}

# every shard on this machine, then the merge: $1 = N, $2 = DIR, then the study and its flags
local_run() {
    local n=$1 dir=$2 jobs=${JOBS:-1} cores
    shift 2
    is_count "$n" || die "local: N = '$n' must be a positive integer"
    is_count "$jobs" || die "local: JOBS = '$jobs' must be a positive integer"
    cores=$(nproc 2>/dev/null || echo 1)
    export RAYON_NUM_THREADS=${RAYON_NUM_THREADS:-$(((cores + jobs - 1) / jobs))}
    if ((jobs > 1)) && command -v parallel >/dev/null; then
        parallel -q --halt now,fail=1 -j "$jobs" bash "$0" shard "{}/$n" "$dir" "$@" ::: $(seq 0 $((n - 1)))
    elif ((jobs > 1)); then
        # no GNU parallel: JOBS background shards at a time
        local i pids=()
        for ((i = 0; i < n; i++)); do
            bash "$0" shard "$i/$n" "$dir" "$@" &
            pids+=($!)
            if ((${#pids[@]} == jobs)); then
                wait "${pids[0]}"
                pids=("${pids[@]:1}")
            fi
        done
        for p in "${pids[@]}"; do
            wait "$p"
        done
    else
        local i
        for ((i = 0; i < n; i++)); do
            run_shard "$i/$n" "$dir" "$@"
        done
    fi
    merge "$n" "$dir"
}

[[ $# -ge 3 ]] || die "usage: study_array.sh shard I/N|N DIR STUDY [FLAGS...] | merge N DIR [FLAGS...] | local N DIR STUDY [FLAGS...] (see the top of the script)"
mode=$1
shift
case $mode in
shard) run_shard "$@" ;;
merge) merge "$@" ;;
local) local_run "$@" ;;
*) die "unknown mode '$mode': shard, merge or local" ;;
esac
