#!/bin/sh
# doc/farm/ranges.sh FRAMES SAMPLES PARTS: the jobs of a split trace, one
# a line, "F P FIRST N": frame F, sample range P of PARTS, samples FIRST
# to FIRST + N - 1 of SAMPLES.  Range P runs from P SAMPLES / PARTS to
# (P + 1) SAMPLES / PARTS: lengths differ by one at most, and together
# they are every sample once.  trace-array.sh does the same arithmetic
# for one task.
set -e
if ! { test $# -eq 3 && test "$3" -ge 1 && test "$2" -ge "$3"; }
then
	echo "usage: ranges.sh FRAMES SAMPLES PARTS (1 <= PARTS <= SAMPLES)" >&2
	exit 2
fi
frames=$1 samples=$2 parts=$3
f=0
while test "$f" -lt "$frames"
do
	p=0
	while test "$p" -lt "$parts"
	do
		first=$((p * samples / parts))
		echo "$f $p $first $(((p + 1) * samples / parts - first))"
		p=$((p + 1))
	done
	f=$((f + 1))
done
