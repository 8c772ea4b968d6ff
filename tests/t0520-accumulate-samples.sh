#!/bin/sh
test_description='SAMPLES: weighted merges in reflect-accumulate, sample ranges of raytraced and reflect-trace'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

# frame FILE KEYS V1 V2: appends a 2x1 frame, spec.R = V1 and V2, with the
# header lines KEYS ("" for none, else e.g. "SAMPLES=3").
frame () {
	{
		printf '#?REFLECT1\n' &&
		if test -n "$2"
		then
			printf '%s\n' "$2"
		fi &&
		printf 'NCOLS=2\nNROWS=1\nNCOMP=1\nCHANNELS=spec.R\nFORMAT=ascii\n\n%s\n%s\n' \
			"$3" "$4"
	} >>"$1"
}

# relmax A B: the largest |a - b| / |a| over the numbers of two column files
# (|a| below 1e-6 counts as 1e-6).
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

# 1 once and 3 three times: (1 + 3 x 3) / 4 = 2.5, and 10, 30: 25.  The
# spread (West): M2 = 3 (3 - 1)(3 - 2.5) = 3, 30 times 10 for the second
# pixel; the mean's variance M2 / ((n - 1) W) = 3 / 4, SE 0.8660254.
test_expect_success 'mean: frames weighted by SAMPLES, hand-derived' '
	frame w.txt SAMPLES=1 1 10 &&
	frame w.txt SAMPLES=3 3 30 &&
	reflect-accumulate --stats -fa w.txt >out.txt &&
	column out.txt spec.R spec.R.se >got &&
	printf "2.5 0.8660254\n25 8.660254\n" >expect &&
	test_cmp_numbers expect got 1e-6 &&
	test_grep "^SAMPLES=4$" out.txt &&
	test_grep "^ACCUMULATED=2$" out.txt
'

test_expect_success 'mean: a frame without SAMPLES counts one sample' '
	frame n.txt "" 1 10 &&
	frame n.txt SAMPLES=3 3 30 &&
	reflect-accumulate -fa n.txt >out.txt &&
	column out.txt spec.R >got &&
	printf "2.5\n25\n" >expect &&
	diff -u expect got &&
	test_grep "^SAMPLES=4$" out.txt
'

test_expect_success 'mean: SAMPLES=1 everywhere gives the bytes of no SAMPLES' '
	for v in 1 2 4 8 0.3 7.1
	do
		frame plain.txt "" $v $v &&
		frame ones.txt SAMPLES=1 $v $v || return 1
	done &&
	reflect-accumulate -a --stats -fa plain.txt >plain-a.txt &&
	reflect-accumulate -a --stats -fa ones.txt >ones-a.txt &&
	column plain-a.txt spec.R spec.R.se >a &&
	column ones-a.txt spec.R spec.R.se >b &&
	test $(wc -l <a) -eq 12 &&
	diff -u a b
'

test_expect_success 'mean: -a gives the running sum of SAMPLES, --reset starts it afresh' '
	frame r.txt "SAMPLES=2
FRAME=0" 1 1 &&
	frame r.txt "SAMPLES=5
FRAME=0" 1 1 &&
	frame r.txt "SAMPLES=7
FRAME=1" 1 1 &&
	reflect-accumulate -a --reset=FRAME -fa r.txt >out.txt &&
	test "$(grep "^SAMPLES=" out.txt | tr "\n" " ")" = "SAMPLES=2 SAMPLES=7 SAMPLES=7 "
'

# ema weighs frames by age, not by SAMPLES (reflect-mode-ema(7)).
test_expect_success 'ema: the same values with and without SAMPLES' '
	frame e1.txt "" 1 10 && frame e1.txt "" 3 30 && frame e1.txt "" 2 5 &&
	frame e2.txt SAMPLES=1 1 10 && frame e2.txt SAMPLES=9 3 30 &&
	frame e2.txt SAMPLES=2 2 5 &&
	reflect-accumulate -fa -m ema:weight=0.5 e1.txt >o1.txt &&
	reflect-accumulate -fa -m ema:weight=0.5 e2.txt >o2.txt &&
	column o1.txt spec.R >a && column o2.txt spec.R >b &&
	printf "2\n12.5\n" >expect &&
	diff -u expect a && diff -u a b &&
	test_grep "^SAMPLES=12$" o2.txt
'

for bad in 0 -1 x 1.5 " 2" 4294967296 99999999999999999999 ""
do
	test_expect_success "mean: SAMPLES='$bad' is refused, naming the key and the file" "
		rm -f bad.txt &&
		frame bad.txt SAMPLES=1 1 1 &&
		frame bad.txt 'SAMPLES=$bad' 1 1 &&
		test_expect_code 1 reflect-accumulate bad.txt >out 2>err &&
		test_grep \"reflect-accumulate: 'bad.txt': frame 2: header key SAMPLES='$bad' is not a whole number\" err &&
		test ! -s out
	"
done

test_expect_success 'raytraced: SAMPLES is its samples=, other modes write none' '
	reflect-gbuffer -x 48 -y 32 | reflect-project >g.rfl &&
	reflect-shade -m raytraced:samples=12 g.rfl | reflect-info >info &&
	test_grep "^	SAMPLES=12$" info &&
	reflect-shade -m raytraced:samples=4 g.rfl | reflect-shade -m hdrp | reflect-info >info &&
	! grep SAMPLES= info
'

test_expect_success 'raytraced: a range past total= is refused' '
	test_expect_code 1 reflect-shade -m raytraced:samples=4:first=13:total=16 g.rfl \
		>out 2>err &&
	test_grep "first=13 and samples=4 reach past total=16" err
'

# K runs of N rays, first=0, N, 2N, .. total=K N, merged, against one run of
# K N rays: the same rays, weighted alike, summed in another order.  A
# float sum of n non-negative terms is within (n - 1) u of the exact sum
# (u = 2^-24): at most 15 u for 16 rays in one run, 3 u a run of 4 and
# the merge's few roundings on the other side, some 40 u = 2.4e-6 of
# the value in all.  One range alone is a different picture (the negative
# control, > 1e-2), so the bound tells a split from a mix-up.
for spec in pattern=deterministic pattern=blue pattern=white \
	pattern=blue:sampler=mis
do
	test_expect_success "raytraced $spec: 4 ranges of 4 rays merge into 16 rays" "
		reflect-shade -fa -m raytraced:samples=16:$spec g.rfl >full.txt &&
		for k in 0 4 8 12
		do
			reflect-shade -m raytraced:samples=4:first=\$k:total=16:$spec g.rfl ||
				return 1
		done | reflect-accumulate -fa >merged.txt &&
		test_grep '^SAMPLES=16$' merged.txt &&
		column full.txt spec.R spec.G spec.B >a &&
		column merged.txt spec.R spec.G spec.B >b &&
		r=\$(relmax a b) && echo \"largest relative difference \$r\" &&
		awk -v r=\$r 'BEGIN { exit !(r <= 2.4e-6) }' &&
		reflect-shade -fa -m raytraced:samples=4:first=4:total=16:$spec g.rfl >one.txt &&
		column one.txt spec.R spec.G spec.B >c &&
		r=\$(relmax a c) && echo \"one range alone: \$r\" &&
		awk -v r=\$r 'BEGIN { exit !(r > 1e-2) }'
	"
done

test_expect_success 'raytraced: ranges of unequal lengths merge as well' '
	reflect-shade -fa -m raytraced:samples=12:pattern=blue g.rfl >full.txt &&
	{
		reflect-shade -m raytraced:samples=3:total=12:pattern=blue g.rfl &&
		reflect-shade -m raytraced:samples=9:first=3:total=12:pattern=blue g.rfl
	} | reflect-accumulate -fa >merged.txt &&
	column full.txt spec.R spec.G spec.B >a &&
	column merged.txt spec.R spec.G spec.B >b &&
	r=$(relmax a b) && echo "largest relative difference $r" &&
	awk -v r=$r "BEGIN { exit !(r <= 2.4e-6) }"
'

# White noise with other seeds: independent rays.  A run of 4 and one of
# 12 (each with the footprint of 16 rays: total=16) merged by their
# SAMPLES is the mean of 16 rays, whose error is that of one 16-ray run;
# merged as equals they would be (x4 + x12) / 2, of variance (1/4 +
# 1/12) / 4 = 1/12 against 1/16: an RMSE 1.15 times.  Three seeds over
# 96x64 pixels keep each RMSE within some 3 % of its expectation.
test_expect_success 'white noise: seeded runs of 4 and 12 rays merge into 16 rays' '
	reflect-gbuffer -x 96 -y 64 | reflect-project >g2.rfl &&
	reflect-shade -fa -m raytraced:samples=1024:pattern=deterministic g2.rfl >ref.txt &&
	column ref.txt spec.G >ref &&
	for s in 1 2 3
	do
		reflect-shade -fa -m raytraced:samples=16:pattern=white:seed=$((10 * s)) \
			g2.rfl >one-$s.txt &&
		reflect-shade -fa -m raytraced:samples=4:total=16:pattern=white:seed=$((10 * s + 1)) \
			g2.rfl >q-$s.txt &&
		reflect-shade -fa -m raytraced:samples=12:total=16:pattern=white:seed=$((10 * s + 2)) \
			g2.rfl >t-$s.txt &&
		cat q-$s.txt t-$s.txt | reflect-accumulate -fa >w-$s.txt &&
		cat q-$s.txt t-$s.txt | sed "/^SAMPLES=/d" | reflect-accumulate -fa >u-$s.txt &&
		for f in one w u
		do
			column $f-$s.txt spec.G >$f-$s || return 1
		done || return 1
	done &&
	cat ref ref ref >ref3 &&
	rmse () {
		cat "$@" | paste - ref3 | awk "{ d = \$1 - \$2; s += d * d }
			END { print sqrt(s / NR) }"
	} &&
	e_one=$(rmse one-1 one-2 one-3) && e_w=$(rmse w-1 w-2 w-3) && e_u=$(rmse u-1 u-2 u-3) &&
	echo "RMSE: 16 rays $e_one, 4 + 12 weighted $e_w, as equals $e_u" &&
	awk -v o=$e_one -v w=$e_w -v u=$e_u \
		"BEGIN { exit !(w < 1.1 * o && o < 1.1 * w && u > 1.08 * w) }"
'

# The issue's case: an accumulation of 16 one-ray frames (frames=16: the
# frames' blocks make one set of 16 rays) split by frame range into 4 and
# 12 frames, each accumulated (SAMPLES=4 and 12), then merged: the 16
# frames' mean to float rounding.  Merged as equals it would be far off.
test_expect_success 'an accumulation split by frame range, 4 + 12, merges into all 16' '
	M=raytraced:samples=1:animate=1:frames=16 &&
	reflect-gbuffer -x 48 -y 32 -n 16 | reflect-project | reflect-shade -m $M |
		reflect-accumulate -fa >all.txt &&
	for r in 0-3 4-15
	do
		reflect-gbuffer -x 48 -y 32 -n 16 --frames=$r | reflect-project |
			reflect-shade -m $M | reflect-accumulate -fa || return 1
	done >parts.txt &&
	reflect-accumulate -fa parts.txt >merged.txt &&
	test_grep "^SAMPLES=16$" merged.txt &&
	column all.txt spec.R spec.G spec.B >a &&
	column merged.txt spec.R spec.G spec.B >b &&
	r=$(relmax a b) && echo "largest relative difference $r" &&
	awk -v r=$r "BEGIN { exit !(r <= 2.4e-6) }" &&
	sed "/^SAMPLES=/d" parts.txt | reflect-accumulate -fa >equals.txt &&
	column equals.txt spec.R spec.G spec.B >c &&
	r=$(relmax a c) && echo "merged as equals: $r" &&
	awk -v r=$r "BEGIN { exit !(r > 1e-2) }"
'

test_expect_success 'reflect-trace: SAMPLES is its --samples' '
	reflect-trace -x 8 -y 6 --samples=12 | reflect-info >info &&
	test_grep "^	SAMPLES=12$" info &&
	test_grep "^	TRACE_SAMPLES=12$" info
'

test_expect_success 'reflect-trace: a range past --total is refused' '
	test_expect_code 1 reflect-trace -x 8 -y 6 --samples=4 --first=13 --total=16 \
		>out 2>err &&
	test_grep "reflect-trace: --first=13 and --samples=4 reach past --total=16" err &&
	test ! -s out
'

# The trace's samples are summed in double: the bound above holds with
# room to spare.  An odd first= splits the two sets unevenly.
for split in "0:4 4:4 8:4 12:4" "0:3 3:13" "0:5 5:6 11:5"
do
	test_expect_success "reflect-trace: ranges $split of 16 merge into 16 samples" "
		reflect-trace -x 48 -y 32 --samples=16 -fa >full.txt &&
		for r in $split
		do
			reflect-trace -x 48 -y 32 --first=\${r%:*} --samples=\${r#*:} --total=16 ||
				return 1
		done | reflect-accumulate -fa >merged.txt &&
		test_grep '^SAMPLES=16$' merged.txt &&
		column full.txt R G B >a &&
		column merged.txt R G B >b &&
		r=\$(relmax a b) && echo \"largest relative difference \$r\" &&
		awk -v r=\$r 'BEGIN { exit !(r <= 2.4e-6) }' &&
		reflect-trace -x 48 -y 32 --first=4 --samples=4 --total=16 -fa >one.txt &&
		column one.txt R G B >c &&
		r=\$(relmax a c) && echo \"one range alone: \$r\" &&
		awk -v r=\$r 'BEGIN { exit !(r > 1e-2) }'
	"
done

test_done
