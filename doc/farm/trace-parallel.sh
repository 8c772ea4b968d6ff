#!/bin/sh
# doc/farm/trace-parallel.sh OUT FRAMES SAMPLES PARTS SCENE [OPTION...]:
# reflect-trace of FRAMES frames at SAMPLES samples a pixel, each frame
# split into PARTS sample ranges, the FRAMES x PARTS jobs spread by GNU
# parallel over the machines of $SSHLOGINFILE (parallel's --sshloginfile)
# or else of $SSHLOGIN (its -S; by default ":", this machine alone), then
# merged into OUT: the one run's stream (doc/farm.md).  SCENE is a scene
# file, or "default" for the embedded scene; the options go to every
# reflect-trace (-x, -y, --orbit, --path, -j ...).  Every machine needs
# reflect's tools on its PATH.  The scene is copied to each machine
# (--basefile) and the parts come back (--return); a scene that names
# meshes or textures needs them there too, or a shared filesystem.  The
# parts stay in OUT.parts/ until the merge is done.
set -e
test $# -ge 5 || {
	echo "usage: trace-parallel.sh OUT FRAMES SAMPLES PARTS SCENE [OPTION...]" >&2
	exit 2
}
here=$(cd "$(dirname "$0")" && pwd)
out=$1 frames=$2 samples=$3 parts=$4 scene=$5
shift 5

# quote WORD: WORD as one word of a shell command line, for parallel,
# which runs its command through a shell (on the far machine too).
quote () {
	printf "'%s'" "$(printf '%s' "$1" | sed "s/'/'\\\\''/g")"
}
options=
for o in "$@"
do
	options="$options $(quote "$o")"
done

work=$out.parts
rm -rf "$work"
mkdir -p "$work"
jobs=$(sh "$here/ranges.sh" "$frames" "$samples" "$parts")
base=
file=default
if test "$scene" != default
then
	cp "$scene" "$work/farm.scene"
	base="--basefile farm.scene"
	file=farm.scene
fi
if test -n "${SSHLOGINFILE:-}"
then
	set -- --sshloginfile "$SSHLOGINFILE"
else
	set -- -S "${SSHLOGIN:-:}"
fi
# $base is one option and its word, or nothing: split on purpose.
# shellcheck disable=SC2086
(
	cd "$work" &&
	echo "$jobs" | parallel --will-cite "$@" --halt now,fail=1 --colsep ' ' \
		$base --return 'part-{1}-{2}.rfl' --cleanup \
		"reflect-trace -q $options -n $frames --frame={1} --first={3} --samples={4}" \
		"--total=$samples $file >part-{1}-{2}.rfl"
)
sh "$here/merge.sh" "$work" "$frames" "$parts" >"$out"
rm -rf "$work"
