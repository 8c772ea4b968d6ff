#!/bin/sh
# doc/farm/tiles-parallel.sh OUT TILES SCENE [OPTION...]: reflect-trace
# of SCENE cut into TILES bands of rows (--tile=I/TILES), the jobs spread
# by GNU parallel over the machines of $SSHLOGINFILE (parallel's
# --sshloginfile) or else of $SSHLOGIN (its -S; by default ":", this
# machine alone), then put together by reflect-join into OUT: the one
# run's frames, byte for byte (doc/farm.md).  SCENE is a scene file, or
# "default" for the embedded scene; the options go to every reflect-trace
# (-x, -y, --samples, -n, --orbit ...).  Every machine needs reflect's
# tools on its PATH.  The scene is copied to each machine (--basefile)
# and the tiles come back (--return).  The tiles stay in OUT.tiles/
# until the join is done.
set -e
test $# -ge 3 || {
	echo "usage: tiles-parallel.sh OUT TILES SCENE [OPTION...]" >&2
	exit 2
}
out=$1 tiles=$2 scene=$3
shift 3

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

work=$out.tiles
rm -rf "$work"
mkdir -p "$work"
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
	seq 0 $((tiles - 1)) | parallel --will-cite "$@" --halt now,fail=1 \
		$base --return 'tile-{}.rfl' --cleanup \
		"reflect-trace -q $options --tile={}/$tiles $file >tile-{}.rfl"
)
# Any order will do: reflect-join places each tile by its REGION, and
# refuses a missing or doubled one.
reflect-join "$work"/tile-*.rfl >"$out"
rm -rf "$work"
