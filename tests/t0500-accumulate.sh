#!/bin/sh
test_description='reflect-accumulate: mean, ema, standard errors, resets, refusals'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

# frames FILE V...: one 2x1 frame per value v: spec.R = v, v * 3 on the
# two pixels, X = the frame's number (passed through, not averaged),
# FRAME = its number.
frames () {
	fr_file=$1
	shift
	fr_n=0
	: >"$fr_file"
	for v
	do
		printf '#?REFLECT1\nFRAME=%s\nNCOLS=2\nNROWS=1\nNCOMP=2\nCHANNELS=spec.R X\n' \
			$fr_n >>"$fr_file" &&
		printf 'FORMAT=ascii\n\n%s %s\n%s %s\n' $v $fr_n \
			$(awk -v v=$v 'BEGIN { print v * 3 }') $fr_n >>"$fr_file" || return 1
		fr_n=$((fr_n + 1))
	done
}

test_expect_success 'mean: the running means of 1 2 4 8, exactly' '
	frames four.txt 1 2 4 8 &&
	reflect-accumulate -a -fa four.txt >out.txt &&
	test $(grep -c "^#?REFLECT" out.txt) -eq 4 &&
	column out.txt spec.R X >got &&
	cat >expect <<-\EOF &&
	1 0
	3 0
	1.5 1
	4.5 1
	2.33333325 2
	7 2
	3.75 3
	11.25 3
	EOF
	diff -u expect got &&
	test_grep "^ACCUMULATE=mean$" out.txt &&
	test "$(grep "^ACCUMULATED=" out.txt | tr "\n" " ")" = \
		"ACCUMULATED=1 ACCUMULATED=2 ACCUMULATED=3 ACCUMULATED=4 "
'

test_expect_success 'mean: one frame at the end, the other channels from the last frame' '
	reflect-accumulate -fa four.txt >one.txt &&
	test $(grep -c "^#?REFLECT" one.txt) -eq 1 &&
	column one.txt spec.R X >got &&
	printf "3.75 3\n11.25 3\n" >expect &&
	diff -u expect got &&
	test_grep "^FRAME=3$" one.txt
'

# The standard error of the mean of 1 2 4 8: s^2 = sum (x - 3.75)^2 / 3
# = (7.5625 + 3.0625 + 0.0625 + 18.0625) / 3 = 9.5833, SE = sqrt(s^2 / 4)
# = 1.547848; three times the values, three times the SE.  One frame
# has no spread to tell: +inf.
test_expect_success 'mean --stats: the standard error of known samples' '
	reflect-accumulate --stats -fa four.txt >se.txt &&
	test_grep "^CHANNELS=spec.R X spec.R.se$" se.txt &&
	column se.txt spec.R.se >got &&
	printf "1.547848\n4.643544\n" >expect &&
	test_cmp_numbers expect got 2e-6 &&
	frames single.txt 5 &&
	reflect-accumulate --stats -fa single.txt >se1.txt &&
	column se1.txt spec.R spec.R.se >got &&
	printf "5 inf\n15 inf\n" >expect &&
	diff -u expect got
'

# The textbook EMA (warmup=0): mu_1 = x_1, mu_k = (1 - w) mu_{k-1} + w x_k,
# in closed form mu_k = (1 - w)^(k-1) x_1 + sum_{i>1} w (1 - w)^(k-i) x_i.
test_expect_success 'ema: the closed form after k frames' '
	frames five.txt 1 2 4 8 16 &&
	reflect-accumulate -a -fa -m ema:weight=0.25:warmup=0 five.txt >ema.txt &&
	column ema.txt spec.R | awk "NR % 2 == 1" >got &&
	awk "BEGIN {
		w = 0.25; split(\"1 2 4 8 16\", x, \" \")
		for (k = 1; k <= 5; k++) {
			m = (1 - w) ^ (k - 1) * x[1]
			for (i = 2; i <= k; i++) m += w * (1 - w) ^ (k - i) * x[i]
			printf \"%.7g\n\", m
		}
	}" >expect &&
	test_cmp_numbers expect got 1e-5
'

# With warmup (the default) the first 1 / weight frames are their mean:
# weight 0.25 averages frames 1..4 plainly, then frame 5 has the weight.
test_expect_success 'ema: warmup is the plain mean, then the weight' '
	reflect-accumulate -a -fa -m ema:weight=0.25 five.txt >warm.txt &&
	column warm.txt spec.R | awk "NR % 2 == 1" >got &&
	printf "1\n1.5\n2.333333\n3.75\n6.8125\n" >expect &&
	test_cmp_numbers expect got 1e-5
'

# --reset=CAMERA: frames 0 1 under one camera, 2 3 under another; the
# result is the mean of frames 2 and 3 alone.
test_expect_success '--reset: a change of a header key starts afresh' '
	frames a.txt 1 2 &&
	frames b.txt 4 8 &&
	{ sed "s/^FRAME=/CAMERA=0 0 5 0 0 0 0 1 0 45\nFRAME=/" a.txt &&
	  sed "s/^FRAME=/CAMERA=0 1 5 0 0 0 0 1 0 45\nFRAME=/" b.txt; } >cams.txt &&
	reflect-accumulate -fa --reset=CAMERA cams.txt >reset.txt &&
	column reset.txt spec.R >got &&
	printf "6\n18\n" >expect &&
	diff -u expect got &&
	test_grep "^ACCUMULATED=2$" reset.txt &&
	reflect-accumulate -fa cams.txt >noreset.txt &&
	column noreset.txt spec.R >got &&
	printf "3.75\n11.25\n" >expect &&
	diff -u expect got
'

test_expect_success '--channels: what is named is combined, the rest passes' '
	reflect-accumulate -fa --channels=X four.txt >x.txt &&
	column x.txt spec.R X >got &&
	printf "8 1.5\n24 1.5\n" >expect &&
	diff -u expect got &&
	test_expect_code 1 reflect-accumulate --channels=Y four.txt 2>err &&
	test_one_line_message reflect-accumulate err &&
	test_grep "no channel .Y." err
'

test_expect_success 'frames of another size or channel list: named and refused' '
	frames two.txt 1 2 &&
	stream wide.txt 3 1 "spec.R X" <<-\EOF &&
	1 1
	1 1
	1 1
	EOF
	cat two.txt wide.txt >mixed.txt &&
	test_expect_code 1 reflect-accumulate mixed.txt 2>err &&
	test_one_line_message reflect-accumulate err &&
	test_grep "frame 3 is 3x1, the first frame was 2x1" err &&
	stream other.txt 2 1 "spec.G X" <<-\EOF &&
	1 1
	1 1
	EOF
	cat two.txt other.txt >mixed.txt &&
	test_expect_code 1 reflect-accumulate mixed.txt 2>err &&
	test_grep "frame 3.s channel 1 is .spec.G., the first frame.s was .spec.R." err
'

test_expect_success 'an empty stream, no channel to combine, NaN: refused' '
	: | test_expect_code 1 reflect-accumulate 2>err &&
	test_one_line_message reflect-accumulate err &&
	test_grep "empty input" err &&
	stream plain.txt 1 1 "P.X" <<-\EOF &&
	1
	EOF
	test_expect_code 1 reflect-accumulate plain.txt 2>err &&
	test_grep "no spec.\* or R G B channel" err &&
	stream nan.txt 2 1 "spec.R X" <<-\EOF &&
	1 1
	nan 1
	EOF
	cat two.txt nan.txt >bad.txt &&
	test_expect_code 1 reflect-accumulate bad.txt 2>err &&
	test_one_line_message reflect-accumulate err &&
	test_grep "frame 3, row 1, pixel 2: channel .spec.R. is nan" err &&
	test_expect_code 1 reflect-accumulate -m ema:weight=2 four.txt 2>err &&
	test_grep "weight" err &&
	test_expect_code 1 reflect-accumulate -m none four.txt 2>err &&
	test_grep "reflect-shade" err
'

test_expect_success 'setup: 16 animated one-ray frames of a small scene' '
	reflect-gbuffer -x 48 -y 32 -n 16 | reflect-project >scene.rfl &&
	reflect-prefilter --size=32 -o room.rfl 2>/dev/null &&
	reflect-shade -m raytraced:samples=1:animate=1:pattern=white --env=room.rfl \
		scene.rfl >noisy.rfl
'

for m in mean ema:weight=0.2
do
	test_expect_success "$m: the bytes do not depend on the thread count" '
		reflect-accumulate -h -a --stats -j1 -m $m noisy.rfl >j1 &&
		reflect-accumulate -h -a --stats -j2 -m $m noisy.rfl >j2 &&
		reflect-accumulate -h -a --stats -j3 -m $m noisy.rfl >j3 &&
		test $(wc -c <j1) -gt 0 &&
		cmp j1 j2 &&
		cmp j1 j3
	'
done

# 16 frames of one white-noise ray each, averaged, against one frame of
# 16 rays: the same estimator (the frames' footprint is that of 16 rays:
# frames=16), so the same error within noise; and a fraction of one
# frame's error.
test_expect_success '16 one-ray frames, averaged, are as good as 16 rays' '
	reflect-gbuffer -x 48 -y 32 | reflect-project >one.rfl &&
	reflect-shade -fa -m raytraced:samples=2048:pattern=deterministic --env=room.rfl \
		one.rfl >ref.txt &&
	reflect-shade -m raytraced:samples=1:animate=1:pattern=white:frames=16 \
		--env=room.rfl scene.rfl | reflect-accumulate -fa >avg.txt &&
	reflect-shade -fa -m raytraced:samples=16:pattern=white --env=room.rfl \
		one.rfl >k16.txt &&
	reflect-shade -fa -m raytraced:samples=1:pattern=white:frames=16 --env=room.rfl \
		one.rfl >k1.txt &&
	for f in ref avg k16 k1
	do
		column $f.txt spec.G >$f || return 1
	done &&
	e_avg=$(paste avg ref | awk "{ d = \$1 - \$2; s += d * d } END { print sqrt(s / NR) }") &&
	e_k16=$(paste k16 ref | awk "{ d = \$1 - \$2; s += d * d } END { print sqrt(s / NR) }") &&
	e_k1=$(paste k1 ref | awk "{ d = \$1 - \$2; s += d * d } END { print sqrt(s / NR) }") &&
	echo "RMSE: 16 frames averaged $e_avg, 16 rays $e_k16, one frame $e_k1" &&
	awk -v a=$e_avg -v b=$e_k16 -v c=$e_k1 \
		"BEGIN { exit !(a < 1.3 * b && b < 1.3 * a && a < 0.4 * c) }"
'

test_done
