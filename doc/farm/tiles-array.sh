#!/bin/sh
# One tile of a trace as a Slurm job array (doc/farm.md):
#
#   id=$(sbatch --parsable --array=0-$((TILES - 1)) doc/farm/tiles-array.sh \
#       DIR TILES SCENE [OPTION...])
#   sbatch --dependency=afterok:$id --wrap "reflect-join DIR/tile-*.rfl >OUT"
#
# Task T traces band T of TILES bands of rows (reflect-trace --tile=T/TILES)
# into DIR/tile-T.rfl; reflect-join puts them together, refusing a tile
# that is missing.  DIR is on a filesystem every node shares; SCENE a
# scene file, or "default" for the embedded scene; the options go to
# reflect-trace.
#SBATCH --job-name=reflect-tile
#SBATCH --cpus-per-task=4
#SBATCH --output=reflect-tile-%A_%a.log
set -e
test $# -ge 3 || {
	echo "usage: tiles-array.sh DIR TILES SCENE [OPTION...]" >&2
	exit 2
}
dir=$1 tiles=$2 scene=$3
shift 3
task=${SLURM_ARRAY_TASK_ID:?"tiles-array.sh: no SLURM_ARRAY_TASK_ID (run it with sbatch --array)"}
mkdir -p "$dir"
# Written aside and renamed: a task killed half-way leaves no tile that
# reflect-join would take for whole.  reflect-trace refuses a task past
# the last tile itself (--tile=I/N with I >= N).
reflect-trace -q ${SLURM_CPUS_PER_TASK:+-j "$SLURM_CPUS_PER_TASK"} "$@" \
	--tile="$task/$tiles" "$scene" >"$dir/tile-$task.rfl.tmp"
mv "$dir/tile-$task.rfl.tmp" "$dir/tile-$task.rfl"
