#!/bin/sh
# One task of a split trace as a Slurm job array (doc/farm.md):
#
#   n=$((FRAMES * PARTS))
#   id=$(sbatch --parsable --array=0-$((n - 1)) doc/farm/trace-array.sh \
#       DIR FRAMES SAMPLES PARTS SCENE [OPTION...])
#   sbatch --dependency=afterok:$id --wrap \
#       "sh doc/farm/merge.sh DIR FRAMES PARTS >OUT"
#
# Task T traces frame T / PARTS, sample range T mod PARTS: samples
# P SAMPLES / PARTS to (P + 1) SAMPLES / PARTS - 1 (ranges.sh's
# arithmetic), into DIR/part-F-P.rfl, which merge.sh reads.  DIR is on
# a filesystem every node shares; SCENE a scene file, or "default"
# for the embedded scene; the options go to reflect-trace.
#SBATCH --job-name=reflect-trace
#SBATCH --cpus-per-task=4
#SBATCH --output=reflect-trace-%A_%a.log
set -e
test $# -ge 5 || {
	echo "usage: trace-array.sh DIR FRAMES SAMPLES PARTS SCENE [OPTION...]" >&2
	exit 2
}
dir=$1 frames=$2 samples=$3 parts=$4 scene=$5
shift 5
task=${SLURM_ARRAY_TASK_ID:?"trace-array.sh: no SLURM_ARRAY_TASK_ID (run it with sbatch --array)"}
test "$task" -lt $((frames * parts)) || {
	echo "trace-array.sh: task $task: past the last, $((frames * parts - 1))" >&2
	exit 1
}
f=$((task / parts))
p=$((task % parts))
first=$((p * samples / parts))
n=$(((p + 1) * samples / parts - first))
mkdir -p "$dir"
# Written aside and renamed: a task killed half-way leaves no part that
# merge.sh would take for whole.
reflect-trace -q ${SLURM_CPUS_PER_TASK:+-j "$SLURM_CPUS_PER_TASK"} "$@" -n "$frames" --frame="$f" \
	--first="$first" --samples="$n" --total="$samples" "$scene" \
	>"$dir/part-$f-$p.rfl.tmp"
mv "$dir/part-$f-$p.rfl.tmp" "$dir/part-$f-$p.rfl"
