#!/bin/sh
test_description='doc/farm: a trace split by sample and frame ranges, under GNU parallel on this machine and as a Slurm array, is the one run'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

farm=$srcdir/doc/farm

# relmax A B: the largest |a - b| / |a| over the numbers of two column
# files (|a| below 1e-6 counts as 1e-6), as t0520 measures merges.
relmax () {
	paste -d " " "$1" "$2" | awk '{
		n = NF / 2
		for (i = 1; i <= n; i++) {
			d = $i - $(i + n); if (d < 0) d = -d
			m = $i < 0 ? -$i : $i; if (m < 1e-6) m = 1e-6
			if (d / m > mx) mx = d / m
		}
	} END { printf "%.3g\n", mx + 0 }'
}

# ascii IN OUT: the frames of a stream as ascii, one by one (a running
# mean restarted at every FRAME is each frame as it is).
ascii () {
	reflect-accumulate -q -a --reset=FRAME -fa "$1" >"$2"
}

# within A B: the R G B of two ascii streams agree to 2.4e-6 relative,
# the bound t0520 derives for a merge of sample ranges (float sums of
# 16 samples in two orders, and the merge's roundings).
within () {
	column "$1" R G B >a &&
	column "$2" R G B >b &&
	test $(wc -l <a) -eq $(wc -l <b) &&
	r=$(relmax a b) && echo "largest relative difference $r" &&
	awk -v r=$r "BEGIN { exit !(r <= 2.4e-6) }"
}

# The embedded scene for the splits by samples, a scene file (sent to the
# machines by the recipe) for those by frames.
test_expect_success 'setup: the one-machine runs' '
	cp "$srcdir/doc/examples/room-floor.scene" . &&
	reflect-trace -q -x 32 -y 24 --samples=16 -n 3 --orbit=40 default >full.rfl &&
	ascii full.rfl full.txt &&
	test $(grep -c "^FRAME=" full.txt) -eq 3 &&
	column full.txt R >r &&
	test $(awk "\$1 > 0" r | wc -l) -gt 1000 &&
	reflect-trace -q -x 24 -y 16 --samples=4 -n 4 --orbit=60 -h room-floor.scene >frames.rfl &&
	test $(od -An -tf4 -v frames.rfl | tr -s " " "\n" | awk "\$1 > 0" | wc -l) -gt 100
'

test_expect_success 'ranges.sh: ranges of unequal lengths that cover every sample once' '
	sh "$farm/ranges.sh" 2 10 4 >jobs &&
	printf "%s\n" "0 0 0 2" "0 1 2 3" "0 2 5 2" "0 3 7 3" \
		"1 0 0 2" "1 1 2 3" "1 2 5 2" "1 3 7 3" >expect &&
	diff -u expect jobs &&
	test_expect_code 2 sh "$farm/ranges.sh" 1 3 4 2>err &&
	test_grep "usage: ranges.sh" err
'

# The Slurm array needs no Slurm to check its arithmetic: its tasks,
# run one by one with the index Slurm would give, then the merge.
test_expect_success 'Slurm array: 3 frames x 3 ranges of 16 samples merge into the one run' '
	for t in 0 1 2 3 4 5 6 7 8
	do
		SLURM_ARRAY_TASK_ID=$t sh "$farm/trace-array.sh" parts 3 16 3 default \
			-x 32 -y 24 --orbit=40 || return 1
	done &&
	test $(ls parts | wc -l) -eq 9 &&
	test ! -f parts/part-2-2.rfl.tmp &&
	sh "$farm/merge.sh" parts 3 3 >slurm.rfl &&
	ascii slurm.rfl slurm.txt &&
	test $(grep -c "^SAMPLES=16$" slurm.txt) -eq 3 &&
	test "$(grep "^FRAME=" slurm.txt | tr "\n" " ")" = "FRAME=0 FRAME=1 FRAME=2 " &&
	within full.txt slurm.txt
'

test_expect_success 'Slurm array: a frame split alone is the full run'"'"'s pixels, byte for byte' '
	for t in 0 1 2 3
	do
		SLURM_ARRAY_TASK_ID=$t sh "$farm/trace-array.sh" fparts 4 4 1 room-floor.scene \
			-x 24 -y 16 --orbit=60 -h || return 1
	done &&
	sh "$farm/merge.sh" fparts 4 1 >slurm-frames.rfl &&
	cmp frames.rfl slurm-frames.rfl
'

test_expect_success 'Slurm array: a task past the last, or none, is refused' '
	SLURM_ARRAY_TASK_ID=9 test_expect_code 1 sh "$farm/trace-array.sh" parts 3 16 3 \
		default 2>err &&
	test_grep "task 9: past the last, 8" err &&
	(
		unset SLURM_ARRAY_TASK_ID &&
		test_expect_code 2 sh "$farm/trace-array.sh" parts 3 16 3 default 2>err
	) &&
	test_grep "no SLURM_ARRAY_TASK_ID" err &&
	rm -f parts/part-0-1.rfl &&
	test_expect_code 1 sh "$farm/merge.sh" parts 3 3 >/dev/null 2>err &&
	test_grep "part-0-1.rfl.: missing" err
'

test_expect_success 'Slurm array: tiles joined are the one run, byte for byte' '
	reflect-trace -q -x 32 -y 23 --samples=4 -n 2 --orbit=40 -h room-floor.scene >still.raw &&
	for t in 2 0 1
	do
		SLURM_ARRAY_TASK_ID=$t sh "$farm/tiles-array.sh" tiles 3 room-floor.scene \
			-x 32 -y 23 --samples=4 -n 2 --orbit=40 || return 1
	done &&
	test $(ls tiles | wc -l) -eq 3 &&
	reflect-join -h tiles/tile-*.rfl >joined.raw &&
	cmp still.raw joined.raw &&
	SLURM_ARRAY_TASK_ID=3 test_expect_code 1 sh "$farm/tiles-array.sh" tiles 3 \
		room-floor.scene -x 32 -y 23 2>err &&
	test_grep "no band 3 of 3" err &&
	rm tiles/tile-1.rfl &&
	test_expect_code 1 reflect-join tiles/tile-*.rfl >/dev/null 2>err &&
	test_grep "no tile holds pixel 0,7 of the 32x23 frame" err
'

if ! parallel --version 2>/dev/null | grep -q "GNU parallel"
then
	for t in 'parallel -S :: sample ranges merge into the one run' \
		'parallel -S :: a frame split is the full run'"'"'s pixels, byte for byte' \
		'parallel -S :: the sweep scores as the jobs run one by one' \
		'parallel -S :: tiles joined are the one run, byte for byte'
	do
		test_skip "$t" 'no GNU parallel'
	done
	test_done
fi

test_expect_success 'parallel -S :: sample ranges merge into the one run' '
	SSHLOGIN=: sh "$farm/trace-parallel.sh" par.rfl 3 16 3 default \
		-x 32 -y 24 --orbit=40 &&
	test ! -d par.rfl.parts &&
	ascii par.rfl par.txt &&
	within full.txt par.txt &&
	column slurm.txt R G B >a &&
	column par.txt R G B >b &&
	cmp a b &&
	reflect-trace -q -x 32 -y 24 --first=4 --samples=4 --total=16 -fa default >one.txt &&
	column full.txt R G B | head -n $((32 * 24)) >a &&
	column one.txt R G B >c &&
	r=$(relmax a c) && echo "one range alone: $r" &&
	awk -v r=$r "BEGIN { exit !(r > 1e-2) }"
'

test_expect_success 'parallel -S :: a frame split is the full run'"'"'s pixels, byte for byte' '
	SSHLOGIN=: sh "$farm/trace-parallel.sh" par-frames.rfl 4 4 1 room-floor.scene \
		-x 24 -y 16 --orbit=60 -h &&
	cmp frames.rfl par-frames.rfl
'

test_expect_success 'parallel -S :: tiles joined are the one run, byte for byte' '
	SSHLOGIN=: sh "$farm/tiles-parallel.sh" par-tiles.rfl 4 room-floor.scene \
		-x 32 -y 23 --samples=4 -n 2 --orbit=40 &&
	test ! -d par-tiles.rfl.tiles &&
	test $(grep -a -c "^FRAME=" par-tiles.rfl) -eq 2 &&
	! grep -a -q "^REGION=" par-tiles.rfl &&
	reflect-join -h par-tiles.rfl >par-tiles.raw &&
	cmp still.raw par-tiles.raw
'

# The sweep at a toy size (the table of doc/fidelity.md is 320x180, with
# truths of 4096 samples): its scores are those of the same commands run
# one after the other here.
test_expect_success 'parallel -S :: the sweep scores as the jobs run one by one' '
	SSHLOGIN=: SIZE=32x24 PROBE_SIZE=16 TRUTH_SAMPLES=8 MODES="none hdrp raytraced:samples=4" \
		sh "$farm/sweep.sh" table.md default room-floor.scene &&
	test ! -d table.md.work &&
	for n in default room-floor
	do
		s=default &&
		if test $n = room-floor
		then
			s=room-floor.scene
		fi &&
		reflect-gbuffer -q -x 32 -y 24 -c P,N,Ng,V,roughness,mask,objid,depth,emission $s |
			reflect-project >$n.g.rfl &&
		reflect-capture --hide-reflective -n 16 $s | reflect-prefilter -q -o $n.env.rfl - &&
		reflect-trace -q -x 32 -y 24 --samples=8 $s >$n.truth.rfl &&
		printf "| %s |" $n &&
		for m in none hdrp raytraced:samples=4
		do
			reflect-shade -q -m $m --final --env=$n.env.rfl $n.g.rfl >x.rfl &&
			reflect-compare -f a --mask --erode=1 x.rfl $n.truth.rfl |
				awk "{ printf \" %.4f |\", \$2 }" || return 1
		done &&
		echo || return 1
	done >rows &&
	cat table.md &&
	printf "%s\n" "| scene | none | hdrp | raytraced:samples=4 |" "|---|---|---|---|" >expect &&
	cat rows >>expect &&
	diff -u expect table.md &&
	! grep " 0.0000 |" table.md
'

test_done
