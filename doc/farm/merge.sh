#!/bin/sh
# doc/farm/merge.sh DIR FRAMES PARTS: the pieces of a split trace, as
# trace-parallel.sh and trace-array.sh leave them (DIR/part-F-P.rfl: frame
# F, sample range P), made into the one run's stream on stdout.  Each
# frame's ranges go through reflect-accumulate's mean, which weighs every
# range by its SAMPLES key, so that ranges of unequal lengths make the
# mean of all their samples; the frames follow in order.  A frame of one
# range is its bytes as they are: a split by frames alone is the full
# run's pixels, byte for byte (the headers differ in the command line
# they record).
set -e
test $# -eq 3 || {
	echo "usage: merge.sh DIR FRAMES PARTS" >&2
	exit 2
}
dir=$1 frames=$2 parts=$3
f=0
while test "$f" -lt "$frames"
do
	p=0
	set --
	while test "$p" -lt "$parts"
	do
		test -f "$dir/part-$f-$p.rfl" || {
			echo "merge.sh: '$dir/part-$f-$p.rfl': missing (did every job finish?)" >&2
			exit 1
		}
		set -- "$@" "$dir/part-$f-$p.rfl"
		p=$((p + 1))
	done
	if test "$parts" -eq 1
	then
		cat "$1"
	else
		cat "$@" | reflect-accumulate -m mean
	fi
	f=$((f + 1))
done
