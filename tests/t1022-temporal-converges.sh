#!/bin/sh
test_description='raytraced:animate=1 without frames=: accumulated frames converge'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

# Pixels of a small frame.
npix=$((48 * 32))

# rel A B: RMSE of A against the reference B over the mean of B (files of
# one number a line).
rel () {
	paste "$1" "$2" | awk '{ d = $1 - $2; s += d * d; r += $2; n++ }
		END { printf "%.6g\n", sqrt(s / n) / (r / n) }'
}

# frame_of FILE K: the K-th (from 1) frame's values of a column file.
frame_of () {
	sed -n "$(( ($2 - 1) * npix + 1 )),$(( $2 * npix ))p" "$1"
}

test_expect_success 'setup: 64 frames of one view, a small room, references' '
	reflect-gbuffer -x 48 -y 32 -n 64 | reflect-project >frames.rfl &&
	reflect-gbuffer -x 48 -y 32 | reflect-project >one.rfl &&
	reflect-prefilter --size=64 -o room.rfl 2>/dev/null &&
	reflect-shade -fa -m raytraced:samples=2048:pattern=deterministic --env=room.rfl \
		one.rfl >ref.txt &&
	column ref.txt spec.G >ref &&
	test $(wc -l <ref) = $npix &&
	reflect-shade -fa -m raytraced:samples=16 --env=room.rfl one.rfl >k16.txt &&
	column k16.txt spec.G >k16 &&
	e=$(rel k16 ref) &&
	echo "one frame of 16 rays: $e" &&
	echo $e >e_k16
'

test_expect_success 'animated one-ray frames: the same bytes at -j1 and -j2' '
	reflect-shade -j2 -m raytraced:samples=1:animate=1 --env=room.rfl \
		frames.rfl >anim.rfl &&
	reflect-shade -h -j1 -m raytraced:samples=1:animate=1 --env=room.rfl \
		frames.rfl >j1 &&
	reflect-shade -h -j2 -m raytraced:samples=1:animate=1 --env=room.rfl \
		frames.rfl >j2 &&
	test $(wc -c <j1) -gt $((64 * npix * 12)) &&
	cmp j1 j2 &&
	for m in mean ema
	do
		reflect-accumulate -h -j1 -a -m $m anim.rfl >acc1 &&
		reflect-accumulate -h -j2 -a -m $m anim.rfl >acc2 &&
		cmp acc1 acc2 || return 1
	done
'

# Frame f has f frames before it: its rays have the footprint of f + 1
# rays, as frames=f+1 gives them (white noise: no split of one set, so
# the very same rays).
for f in 0 1 5 63
do
	test_expect_success "frame $f reads as frames=$((f + 1)) does" '
		reflect-gbuffer -x 48 -y 32 -n 64 --frame=$f | reflect-project >f.rfl &&
		reflect-shade -h -m raytraced:samples=1:animate=1:pattern=white \
			--env=room.rfl f.rfl >auto &&
		reflect-shade -h -m raytraced:samples=1:animate=1:pattern=white:frames=$((f + 1)) \
			--env=room.rfl f.rfl >told &&
		cmp auto told &&
		reflect-shade -h -m raytraced:samples=1:animate=1:pattern=white:frames=1 \
			--env=room.rfl f.rfl >one &&
		if test $f = 0; then cmp auto one; else ! cmp -s auto one; fi
	'
done

test_expect_success 'animate=0: no frames= is frames=1, byte for byte' '
	reflect-shade -h -m raytraced:samples=2 --env=room.rfl frames.rfl >a &&
	reflect-shade -h -m raytraced:samples=2:frames=1 --env=room.rfl frames.rfl >b &&
	cmp a b
'

test_expect_success 'setup: the running mean and ema, and frames=1 (the old footprint)' '
	reflect-accumulate -fa -a -m mean anim.rfl >mean.txt &&
	column mean.txt spec.G >mean &&
	reflect-accumulate -fa -a -m ema anim.rfl >ema.txt &&
	column ema.txt spec.G >ema &&
	reflect-shade -m raytraced:samples=1:animate=1:frames=1 --env=room.rfl frames.rfl |
		reflect-accumulate -fa -a -m mean >old.txt &&
	column old.txt spec.G >old &&
	test $(wc -l <mean) = $((64 * npix)) &&
	for n in 1 4 16 64
	do
		frame_of mean $n >m$n && frame_of ema $n >e$n && frame_of old $n >o$n &&
		echo "$n frames: mean $(rel m$n ref), ema $(rel e$n ref), frames=1 $(rel o$n ref)" ||
		return 1
	done
'

# A mean that converges at the Monte-Carlo rate or faster halves its
# error from 16 frames to 64; one with a blur that never averages out
# (frames=1: every ray the footprint of one) stalls at that blur.
# Measured when written: 0.464 0.236 0.129 0.042 against 0.056 for 16
# rays in one frame; frames=1 0.327 at 16 frames, 0.321 at 64.
test_expect_success 'mean: the error falls with the frames, at least as 1 / sqrt(N)' '
	e1=$(rel m1 ref) && e4=$(rel m4 ref) && e16=$(rel m16 ref) && e64=$(rel m64 ref) &&
	echo "mean of 1, 4, 16, 64 frames: $e1 $e4 $e16 $e64" &&
	awk -v a=$e1 -v b=$e4 -v c=$e16 -v d=$e64 -v k=$(cat e_k16) \
		"BEGIN { exit !(a > b && b > c && c > d && d < 0.5 * c && d < k) }"
'

test_expect_success 'frames=1 keeps the one-ray footprint: its mean stalls' '
	o16=$(rel o16 ref) && o64=$(rel o64 ref) && e64=$(rel m64 ref) &&
	echo "frames=1: 16 frames $o16, 64 frames $o64; without frames= $e64" &&
	awk -v a=$o16 -v b=$o64 -v c=$e64 "BEGIN { exit !(b > 0.9 * a && c < 0.25 * b) }"
'

# The target: a TAA history (ema, weight 0.1: some 19 frames)
# after 64 frames within 1.5 times one frame of 16 rays.  Measured when
# written: 0.0806 against 0.0559 (1.44x).
test_expect_success 'ema after 64 frames: within 1.5x of one frame of 16 rays' '
	e=$(rel e64 ref) && k=$(cat e_k16) &&
	echo "ema of 64 frames $e, one frame of 16 rays $k" &&
	awk -v e=$e -v k=$k "BEGIN { exit !(e < 1.5 * k) }"
'

test_done
