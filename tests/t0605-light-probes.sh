#!/bin/sh
test_description='mirror-ball and angular-map light probes in, in Debevec'"'"'s axes'
. "$srcdir/tests/lib.sh"

imgdump="$builddir/tests/imgdump"

# probe_image FILE EXPR: a 64x64 float EXR whose pixel is EXPR of
# (u, v) in [-1, 1]^2 at its centre, v up (awk; r is their radius).
probe_image () {
	awk -v expr="$2" 'BEGIN {
		print "#?REFLECT1"; print "NCOLS=64"; print "NROWS=64"; print "NCOMP=3"
		print "CHANNELS=R G B"; print "FORMAT=ascii"; print ""
		for (y = 0; y < 64; y++) for (x = 0; x < 64; x++) {
			u = 2 * (x + 0.5) / 64 - 1; v = 1 - 2 * (y + 0.5) / 64; r = sqrt(u * u + v * v)
			if (expr == "ball") val = r < 0.5 ? 1 : 0
			else val = 1 + (u > 0) + 2 * (v > 0)
			print val, val, val
		}
	}' >"$1.txt" &&
	reflect-export -o "$1" "$1.txt"
}

# texel FILE FACE I J: the cube level 0 texel (faces of 16) as "R G B".
texel () {
	sed -n "$((3 + $2 * 256 + $4 * 16 + $3))p" "$1"
}

# A mirror ball reflects the direction theta from +Z at radius
# sin(theta/2): the disc r < 0.5 is theta < 60 degrees.  The +Z face's
# centre (theta 0) sees it, the +X face's (90 degrees, r 0.71) and the
# -Z face's (the rim) do not.
test_expect_success 'a mirror ball: the centre is +Z, 60 degrees at half the radius' '
	probe_image ball.exr ball &&
	reflect-prefilter --layout=mirrorball --levels=2 -o ball.rfl ball.exr 2>/dev/null &&
	reflect-export -o "ball%d.exr" ball.rfl &&
	"$imgdump" ball0.exr >dump &&
	head -n 1 dump >size &&
	echo "16 96 3" >expect &&
	cmp expect size &&
	texel dump 4 7 7 >got && echo "1 1 1" >expect && test_cmp_numbers expect got 1e-6 &&
	texel dump 0 7 7 >got && echo "0 0 0" >expect && test_cmp_numbers expect got 1e-6 &&
	texel dump 5 7 7 >got && test_cmp_numbers expect got 1e-6
'

# An angular map's quadrants: 1 + (u > 0) + 2 (v > 0), u along +X, v
# along +Y.  Texel (11, 4) of a face of 16 is (a, b) = (0.4375, -0.4375):
# on +X the direction (1, 0.4375, 0.4375), up and right of the centre
# (4); on -X (-1, 0.4375, -0.4375), up and left (3); on -Y (0.4375, -1,
# -0.4375): down and right (2).
test_expect_success 'an angular map: +X to the right, +Y up' '
	probe_image quad.exr quadrants &&
	reflect-prefilter --layout=angular --levels=2 -o quad.rfl quad.exr 2>/dev/null &&
	reflect-export -o "quad%d.exr" quad.rfl &&
	"$imgdump" quad0.exr >dump &&
	texel dump 0 11 4 >got && echo "4 4 4" >expect && test_cmp_numbers expect got 1e-6 &&
	texel dump 1 11 4 >got && echo "3 3 3" >expect && test_cmp_numbers expect got 1e-6 &&
	texel dump 3 11 4 >got && echo "2 2 2" >expect && test_cmp_numbers expect got 1e-6
'

test_expect_success 'a square image is never guessed; bad sizes are refused' '
	test_expect_code 1 reflect-prefilter -o x.rfl ball.exr 2>err &&
	test_grep "give --layout=mirrorball or --layout=angular" err &&
	awk "BEGIN { print \"#?REFLECT1\"; print \"NCOLS=8\"; print \"NROWS=4\"; print \"NCOMP=3\"
		print \"CHANNELS=R G B\"; print \"FORMAT=ascii\"; print \"\"
		for (i = 0; i < 32; i++) print 1, 1, 1 }" >wide.txt &&
	reflect-export -o wide.exr wide.txt &&
	test_expect_code 1 reflect-prefilter --layout=angular -o x.rfl wide.exr 2>err &&
	test_grep "an angular map is square, not 8x4" err &&
	test_expect_code 1 reflect-prefilter --layout=ball -o x.rfl ball.exr 2>err &&
	test_grep "mirrorball or angular" err
'

test_done
