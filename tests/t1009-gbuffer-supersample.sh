#!/bin/sh
test_description='reflect-gbuffer --supersample and the resolve of reflect-export'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"

imgdump="$builddir/tests/imgdump"

# The data lines of an ascii stream, without its header.
body () {
	sed '1,/^$/d' "$1"
}

test_expect_success 'N x N samples a pixel are a frame N times larger' '
	reflect-gbuffer -x 8 -y 2 --supersample=4 | reflect-info >info &&
	test_grep "NCOLS=32$" info &&
	test_grep "NROWS=8$" info &&
	test_grep "SUPERSAMPLE=4$" info &&
	reflect-gbuffer -x 8 -y 2 | reflect-info >info &&
	! test_grep SUPERSAMPLE info
'

# Sample (a, b) of pixel (i, j) crosses the picture at
# (i + (a + 0.5)/N, j + (b + 0.5)/N): the centre of pixel (N i + a, N j + b)
# of the picture N times larger, so the two frames hold the same rays.
test_expect_success 'the samples are the centres of an N x N grid in the pixel' '
	reflect-gbuffer -x 4 -y 2 --supersample=3 -fa >ss.txt &&
	reflect-gbuffer -x 12 -y 6 -fa >big.txt &&
	body ss.txt >ss.body &&
	body big.txt >big.body &&
	cmp big.body ss.body
'

# From (0, 0, 1) looking down -Z at fov 90 (tan 45 = 1) on an 8x8 picture
# supersampled 4 times, the sample of column s (0..31) meets the plane
# z = 0 at x = 2(s + 0.5)/32 - 1.  The mirror ends at x = 0.3, which
# s = 20 (x = 0.28125) is left of and s = 21 (x = 0.34375) right of:
# columns 0..4 are covered, column 5 (s = 20..23) by one sample in four
# on every row, 6 and 7 not at all.
test_expect_success 'a vertical edge covers its pixels by the hand-counted fraction' '
	cat >edge.scene <<-\EOF &&
	probe box -20 -20 -20 20 20 20
	room off
	camera position 0 0 1 target 0 0 0 fov 90
	rect plane z 0 min -10 -10 max 0.3 10 roughness 0.2
	EOF
	reflect-gbuffer -x 8 -y 8 --supersample=4 -c mask edge.scene >edge.rfl &&
	reflect-export -c mask -o edge.exr edge.rfl &&
	"$imgdump" edge.exr >dump &&
	head -n 1 dump >size &&
	echo "8 8 1" >expect &&
	cmp expect size &&
	for row in 0 1 2 3 4 5 6 7
	do
		printf "1\n1\n1\n1\n1\n0.25\n0\n0\n" || return 1
	done >expect &&
	sed 1,2d dump >actual &&
	test_cmp_numbers expect actual 0
'

# A slanted edge: the half-plane 2x + y < sqrt(5)/10 of z = 0 (a 40 m
# rectangle whose tangent is (2, 1, 0), centred 19.9 m behind its edge).
# Each pixel's coverage is the count of its 16 sample centres inside it,
# counted here independently; 2x + y at a sample is (n + 0.5)/16 - 1,
# never within 0.005 of the edge.
test_expect_success 'a slanted edge: coverage is the share of samples inside' '
	cat >slant.scene <<-\EOF &&
	probe box -40 -40 -40 40 40 40
	room off
	camera position 0 0 1 target 0 0 0 fov 90
	rect center -17.7991011 -8.89955055 0 normal 0 0 1 size 40 40 tangent 2 1 0
	EOF
	reflect-gbuffer -x 8 -y 8 --supersample=4 -c mask slant.scene |
	reflect-export -c mask -o slant.exr &&
	"$imgdump" slant.exr | sed 1,2d >actual &&
	awk "BEGIN {
		for (j = 0; j < 8; j++) for (i = 0; i < 8; i++) {
			n = 0
			for (b = 0; b < 4; b++) for (a = 0; a < 4; a++) {
				x = 2 * (4 * i + a + 0.5) / 32 - 1
				y = 1 - 2 * (4 * j + b + 0.5) / 32
				if (2 * x + y < sqrt(5) / 10) n++
			}
			print n / 16
		}
	}" >expect &&
	test_cmp_numbers expect actual 0 &&
	grep -v "^0$" actual | grep -v "^1$" >partial &&
	test $(wc -l <partial) -ge 8
'

# Object numbers are not averaged: with N = 3 the centre sample is the
# pixel's own ray, so the resolved objid is the plain render's exactly.
test_expect_success 'objid takes the centre sample: N = 3 gives the plain objid' '
	reflect-gbuffer -x 64 -y 36 -c objid | reflect-export -c objid -o plain.exr &&
	reflect-gbuffer -x 64 -y 36 -c objid --supersample=3 |
	reflect-export -c objid -o ss.exr &&
	"$imgdump" plain.exr >plain &&
	"$imgdump" ss.exr >ss &&
	cmp plain ss &&
	sort -u plain | wc -l >n &&
	test $(cat n) -gt 5
'

# Two sample rows of four: one output row of two pixels.  With the box,
# each pixel is the mean of its 2 x 2 samples: (0 + 0.5 + 0.25 + 0.25)/4
# = 0.25 and (0 + 1 + 2 + 3)/4 = 1.5.  With the Gaussian of
# sigma 0.5 (taps within 1.5 pixels: all four columns), the samples sit
# at 0.25 0.75 1.25 1.75; from pixel 0 (centre 0.5) they are -0.25 0.25
# 0.75 1.25 away, weights exp(-2 d^2) = 0.8824969 0.8824969 0.3246525
# 0.0439369, sum 2.1335832; the two rows weigh a half each.  The lone 1
# (row 0, column 3) gives pixel 0: 0.5 * 0.0439369 / 2.1335832 =
# 0.0102966 and pixel 1 (mirror image): 0.5 * 0.8824969 / 2.1335832 =
# 0.2068108.
test_expect_success 'the box and the Gaussian weigh the samples as derived' '
	cat >four.txt <<-\EOF &&
	#?REFLECT1
	NCOLS=4
	NROWS=2
	NCOMP=1
	CHANNELS=mask
	FORMAT=ascii
	SUPERSAMPLE=2

	0
	0.5
	0
	1
	0.25
	0.25
	2
	3
	EOF
	reflect-export -c mask -o box.exr four.txt &&
	"$imgdump" box.exr >dump &&
	printf "2 1 1\nmask\n0.25\n1.5\n" >expect &&
	test_cmp_numbers expect dump 1e-7 &&
	sed "s/^0.5$/0/; s/^0.25$/0/; s/^2$/0/; s/^3$/0/" four.txt >impulse.txt &&
	reflect-export -c mask --filter=gaussian:0.5 -o g.exr impulse.txt &&
	"$imgdump" g.exr | sed 1,2d >actual &&
	printf "0.0102966\n0.2068108\n" >expect &&
	test_cmp_numbers expect actual 2e-7
'

test_expect_success 'a constant stays constant under the Gaussian, borders too' '
	awk "BEGIN {
		print \"#?REFLECT1\"; print \"NCOLS=12\"; print \"NROWS=9\"
		print \"NCOMP=3\"; print \"CHANNELS=R G B\"; print \"FORMAT=ascii\"
		print \"SUPERSAMPLE=3\"; print \"\"
		for (i = 0; i < 108; i++) print \"0.7 2 0.125\"
	}" >flat.txt &&
	reflect-export --filter=gaussian:1.2 -o flat.exr flat.txt &&
	"$imgdump" flat.exr >dump &&
	head -n 1 dump >size &&
	echo "4 3 3" >expect &&
	cmp expect size &&
	for i in 1 2 3 4 5 6 7 8 9 10 11 12
	do
		echo "0.7 2 0.125" || return 1
	done >expect &&
	sed 1,2d dump >actual &&
	test_cmp_numbers expect actual 1e-6
'

test_expect_success '--downsample=1 keeps every sample, --downsample=N resolves any frame' '
	reflect-gbuffer -x 6 -y 4 --supersample=2 -c mask edge.scene >two.rfl &&
	reflect-export -c mask --downsample=1 -o full.exr two.rfl &&
	"$imgdump" full.exr | head -n 1 >size &&
	echo "12 8 1" >expect &&
	cmp expect size &&
	reflect-gbuffer -x 12 -y 8 -c mask edge.scene | reflect-export -c mask \
		--downsample=2 -o by2.exr &&
	reflect-export -c mask -o ss2.exr two.rfl &&
	"$imgdump" by2.exr >a &&
	"$imgdump" ss2.exr >b &&
	cmp a b
'

test_expect_success 'the whole pipeline carries the key, and is the same at 1 and 2 threads' '
	reflect-gbuffer -x 40 -y 24 --supersample=2 >g.rfl &&
	reflect-project <g.rfl | reflect-shade -m raytraced:samples=4 -j 1 >one.rfl &&
	reflect-project <g.rfl | reflect-shade -m raytraced:samples=4 -j 2 >t2.rfl &&
	body one.rfl >one.body &&
	body t2.rfl >t2.body &&
	cmp one.body t2.body &&
	reflect-info one.rfl >info &&
	test_grep "SUPERSAMPLE=2$" info &&
	reflect-export -c spec -o one.exr one.rfl &&
	"$imgdump" one.exr | head -n 1 >size &&
	echo "40 24 3" >expect &&
	cmp expect size &&
	reflect-gbuffer -x 40 -y 24 --supersample=2 -j 1 >g1.rfl &&
	body g.rfl >g.body &&
	body g1.rfl >g1.body &&
	cmp g.body g1.body
'

test_expect_success 'bad sample counts and resolves are refused with the fix' '
	for n in 0 17 1.5 x ""
	do
		test_expect_code 1 reflect-gbuffer -x 4 -y 4 --supersample="$n" \
			>/dev/null 2>err || return 1
		test_grep "supersample" err || return 1
	done &&
	test_expect_code 1 reflect-gbuffer -x 10000 --supersample=16 >/dev/null 2>err &&
	test_grep "^reflect-gbuffer: -x -y --supersample: a frame of 160000 x 5760 pixels is over the limit of 65536 pixels a side" err &&
	test_expect_code 1 reflect-export -c mask --downsample=3 -o x.exr two.rfl 2>err &&
	test_grep "12x8 frame does not downsample by 3" err &&
	test_expect_code 1 reflect-export -c mask --filter=tent -o x.exr two.rfl 2>err &&
	test_grep "is not box or gaussian" err &&
	test_expect_code 1 reflect-export -c mask --filter=gaussian:0 -o x.exr two.rfl 2>err &&
	test_grep "filter=gaussian" err &&
	sed "s/^SUPERSAMPLE=2$/SUPERSAMPLE=two/" four.txt >bad.txt &&
	test_expect_code 1 reflect-export -c mask -o x.exr bad.txt 2>err &&
	test_grep "SUPERSAMPLE=.two. is not a whole number" err
'

test_done
