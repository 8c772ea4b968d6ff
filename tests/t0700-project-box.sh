#!/bin/sh
test_description='box projection: hand-derived cases, symmetry and limits'
. "$srcdir/tests/lib.sh"

# gbuf FILE ROW...: an ascii G-buffer (P N V) of one row, the spec's room
gbuf () {
	out=$1
	shift
	{
		printf '#?REFLECT1\nNCOLS=%d\nNROWS=1\nNCOMP=9\n' $#
		printf 'CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z\n'
		printf 'PROBE_BOX=-3 0 -2 3 3 2\nPROBE_CENTER=0 1.5 0\nFORMAT=ascii\n\n'
		for row
		do
			echo "$row"
		done
	} >"$out"
}

# the projection's outputs of each pixel: R D hit.dist probe.dist
outputs () {
	sed -n '/^$/,$p' "$1" | sed 1d | awk '{ print $10, $11, $12, $13, $14, $15, $16, $17 }'
}

test_expect_success 'probe at the centre, axis directions: D and distances are the walls' '
	# N = V along an axis reflects R along it: the wall distances from
	# (0,1.5,0) are 3 3 1.5 1.5 2 2
	gbuf axes.txt "0 1.5 0 1 0 0 1 0 0" "0 1.5 0 -1 0 0 -1 0 0" \
		"0 1.5 0 0 1 0 0 1 0" "0 1.5 0 0 -1 0 0 -1 0" \
		"0 1.5 0 0 0 1 0 0 1" "0 1.5 0 0 0 -1 0 0 -1" &&
	reflect-project -fa axes.txt >out.txt &&
	outputs out.txt >got &&
	cat >expect <<-\EOF &&
	1 0 0 1 0 0 3 3
	-1 0 0 -1 0 0 3 3
	0 1 0 0 1 0 1.5 1.5
	0 -1 0 0 -1 0 1.5 1.5
	0 0 1 0 0 1 2 2
	0 0 -1 0 0 -1 2 2
	EOF
	test_cmp_numbers expect got 1e-6
'

test_expect_success 'a mirrored scene gives mirrored results' '
	# P (1,1,0.5), N tilted, V toward a camera; mirrored in x (the box and
	# the probe are symmetric in x)
	gbuf a.txt "1 1 0.5 0.6 0.8 0 0 0.6 0.8" &&
	gbuf b.txt "-1 1 0.5 -0.6 0.8 0 0 0.6 0.8" &&
	reflect-project -fa a.txt >oa.txt && reflect-project -fa b.txt >ob.txt &&
	outputs oa.txt | awk "{ print -\$1, \$2, \$3, -\$4, \$5, \$6, \$7, \$8 }" >mirrored &&
	outputs ob.txt >got &&
	test_cmp_numbers mirrored got 1e-6 &&
	# and by hand: N.V = 0.48, R = 0.96 N - V = (0.576, 0.168, -0.8); the
	# first wall is z = -2 at t = 2.5/0.8 = 3.125, hit (2.8, 1.525, -2)
	awk "{ print \$1, \$2, \$3, \$7 }" <got >g2 &&
	echo "-0.576 0.168 -0.8 3.125" >e2 &&
	test_cmp_numbers e2 g2 1e-6
'

test_expect_success 'zero direction components: an exact axis has no NaN' '
	# the camera straight above (0.5, 0, 0.25): R = (0, 1, 0) exactly; the
	# ceiling at t = 3, hit (0.5, 3, 0.25), from the probe (0.5, 1.5, 0.25)
	gbuf zero.txt "0.5 0 0.25 0 1 0 0 1 0" "0.5 0 0.25 -0 1 -0 -0 1 -0" &&
	reflect-project -fa zero.txt >out.txt &&
	outputs out.txt >got &&
	cat >expect <<-\EOF &&
	0 1 0 0.312347524 0.937042571 0.156173762 3 1.60078106
	0 1 0 0.312347524 0.937042571 0.156173762 3 1.60078106
	EOF
	test_cmp_numbers expect got 1e-6 &&
	! grep -i nan out.txt
'

test_expect_success 'a point outside the box: D = R and infinite distances' '
	gbuf out.txt "4 1 0 -1 0 0 -1 0 0" "0 -0.5 0 0 1 0 0 1 0" &&
	reflect-project -fa out.txt >o.txt &&
	outputs o.txt >got &&
	printf "%s\n" "-1 0 0 -1 0 0 inf inf" "0 1 0 0 1 0 inf inf" >expect &&
	test_cmp_numbers expect got 1e-6
'

test_expect_success 'a point on a wall (within rounding) leaving it: distance 0' '
	gbuf wall.txt "3.0000001 1 0 1 0 0 1 0 0" &&
	reflect-project -fa wall.txt >o.txt &&
	outputs o.txt >got &&
	# R = (1,0,0) leaves through x = 3 at once: the lookup is P - C =
	# (3, -0.5, 0), of length sqrt(9.25)
	echo "1 0 0 0.986393924 -0.164398987 0 0 3.04138127" >expect &&
	test_cmp_numbers expect got 1e-5
'

test_expect_success 'the probe off the box centre' '
	gbuf off.txt "0 1 0 1 0 0 1 0 0" &&
	reflect-project -fa --center=1,1,0 off.txt >o.txt &&
	outputs o.txt >got &&
	echo "1 0 0 1 0 0 3 2" >expect &&
	test_cmp_numbers expect got 1e-6
'

test_expect_success 'box projection off, and the infinite mode: D = R' '
	gbuf t.txt "1 1 0.5 0.6 0.8 0 0 0.6 0.8" &&
	reflect-project -fa --box-projection=off t.txt >off.txt &&
	reflect-project -fa -m infinite t.txt >inf.txt &&
	echo "0.576 0.168 -0.8 0.576 0.168 -0.8 inf inf" >expect &&
	outputs off.txt >g1 && test_cmp_numbers expect g1 1e-6 &&
	outputs inf.txt >g2 && test_cmp_numbers expect g2 1e-6
'

test_done
