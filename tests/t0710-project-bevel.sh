#!/bin/sh
test_description='bevel projection: hand-derived exits, the box at radius 0, roughen, refusals'
. "$srcdir/tests/lib.sh"

# gbuf FILE CENTER ROW...: an ascii G-buffer (P N V roughness) of one row
# in the spec's room, -3 0 -2 .. 3 3 2, captured at CENTER
gbuf () {
	out=$1
	center=$2
	shift 2
	{
		printf '#?REFLECT1\nNCOLS=%d\nNROWS=1\nNCOMP=10\n' $#
		printf 'CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness\n'
		printf 'PROBE_BOX=-3 0 -2 3 3 2\nPROBE_CENTER=%s\nFORMAT=ascii\n\n' "$center"
		for row
		do
			echo "$row"
		done
	} >"$out"
}

# the projection's outputs of each pixel: D hit.dist probe.dist
outputs () {
	sed -n '/^$/,$p' "$1" | sed 1d | awk '{ print $14, $15, $16, $17, $18 }'
}

# Radius 1, faces on the box: the inner box is -2 1 -1 .. 2 2 1 (half
# extents 2 0.5 1 about the centre 0 1.5 0).  From the centre with N = V
# = d, so that R = d:
#   +X: the face x = 3, t = 3;
#   the edge along z at x = 2, y = 2, its point at 45 degrees
#   (2 + 1/sqrt 2, 2 + 1/sqrt 2, 0) = (2.707107, 2.707107, 0), 1.207107
#   above the centre's height: t = sqrt(2.707107^2 + 1.207107^2) =
#   2.964040, d = (0.913319, 0.407252, 0);
#   the corner at (2, 2, 1), its point along (1, 1, 1)/sqrt 3:
#   (2.577350, 2.577350, 1.577350), t = sqrt(2.577350^2 + 1.077350^2 +
#   1.577350^2) = 3.208031, d = (0.803416, 0.335829, 0.491689).
# Grown (offset=1), the inner box is the room: the same edge's point
# (3.707107, 3.707107, 0), t = sqrt(3.707107^2 + 2.207107^2) = 4.314389,
# d = (0.859238, 0.511566, 0).
test_expect_success 'exits on a face, an edge and a corner, by hand' '
	gbuf rays.txt "0 1.5 0" \
		"0 1.5 0 1 0 0 1 0 0 0.1" \
		"0 1.5 0 0.913319 0.407252 0 0.913319 0.407252 0 0.1" \
		"0 1.5 0 0.803416 0.335829 0.491689 0.803416 0.335829 0.491689 0.1" &&
	reflect-project -fa -m bevel:radius=1 rays.txt >out.txt &&
	outputs out.txt >got &&
	cat >expect <<-\EOF &&
	1 0 0 3 3
	0.913319 0.407252 0 2.964040 2.964040
	0.803416 0.335829 0.491689 3.208031 3.208031
	EOF
	test_cmp_numbers expect got 2e-5 &&
	gbuf grown.txt "0 1.5 0" \
		"0 1.5 0 0.859238 0.511566 0 0.859238 0.511566 0 0.1" &&
	reflect-project -fa -m bevel:radius=1:offset=1 grown.txt >out.txt &&
	outputs out.txt >got &&
	echo "0.859238 0.511566 0 4.314389 4.314389" >expect &&
	test_cmp_numbers expect got 2e-5
'

test_expect_success 'the shape is centred on the box, the lookup on the capture point' '
	# captured at (1, 1.5, 0): the same ray from (0, 1.5, 0) leaves at
	# the same edge point; D = (1.707107, 1.207107, 0) / 2.090770 =
	# (0.816497, 0.577350, 0), probe.dist 2.090770
	gbuf off.txt "1 1.5 0" "0 1.5 0 0.913319 0.407252 0 0.913319 0.407252 0 0.1" &&
	reflect-project -fa -m bevel:radius=1 off.txt >out.txt &&
	outputs out.txt >got &&
	echo "0.816497 0.577350 0 2.964040 2.090770" >expect &&
	test_cmp_numbers expect got 2e-5
'

test_expect_success 'mirrored in x, mirrored results' '
	gbuf a.txt "0 1.5 0" "1 0.5 0.5 0.6 0.8 0 0 0.6 0.8 0.1" "2.5 2.8 1.7 -0.3 0.2 0.93 -0.5 0.7 0.5 0.1" &&
	gbuf b.txt "0 1.5 0" "-1 0.5 0.5 -0.6 0.8 0 0 0.6 0.8 0.1" "-2.5 2.8 1.7 0.3 0.2 0.93 0.5 0.7 0.5 0.1" &&
	reflect-project -fa -m bevel:radius=0.8 a.txt >oa.txt &&
	reflect-project -fa -m bevel:radius=0.8 b.txt >ob.txt &&
	outputs oa.txt | awk "{ print -\$1, \$2, \$3, \$4, \$5 }" >mirrored &&
	outputs ob.txt >got &&
	test_cmp_numbers mirrored got 1e-6
'

test_expect_success 'radius 0 is box, byte for byte' '
	reflect-gbuffer -x 64 -y 36 >g.rfl &&
	reflect-project -h -m box g.rfl >box.raw &&
	reflect-project -h -m bevel:radius=0 g.rfl >bevel.raw &&
	cmp box.raw bevel.raw &&
	reflect-project -h -m bevel:radius=0.5 g.rfl >round.raw &&
	! cmp -s box.raw round.raw
'

test_expect_success 'the header records the shape; the next projection replaces it' '
	reflect-project -m bevel:radius=0.5 g.rfl >b.rfl &&
	reflect-info b.rfl | grep "^	PROBE_BEVEL=0.5$" &&
	reflect-project -m bevel:radius=0.25:offset=1 g.rfl | reflect-info >info &&
	grep "^	PROBE_BEVEL=0.25 grown$" info &&
	reflect-project -m box b.rfl | reflect-info >info &&
	! grep PROBE_BEVEL info
'

test_expect_success 'roughen: one step of R + K 2 alpha t, mirrors untouched' '
	# the edge ray at roughness 0 (alpha 0) and 0.5 (alpha 0.25)
	gbuf r.txt "0 1.5 0" \
		"0 1.5 0 0.913319 0.407252 0 0.913319 0.407252 0 0" \
		"0 1.5 0 0.913319 0.407252 0 0.913319 0.407252 0 0.5" &&
	reflect-project -fa -m bevel:radius=0.3 r.txt >plain.txt &&
	reflect-project -fa -m bevel:radius=0.3:roughen=0.4 r.txt >rough.txt &&
	outputs plain.txt >p &&
	outputs rough.txt >q &&
	sed -n 1p p >p1 && sed -n 1p q >q1 &&
	test_cmp_numbers p1 q1 0 &&
	# R_eff = 0.3 + 0.4 x 2 x 0.25 x t(0.3)
	t=$(sed -n 2p p | cut -d" " -f4) &&
	r=$(awk -v t=$t "BEGIN { print 0.3 + 0.4 * 2 * 0.25 * t }") &&
	reflect-project -fa -m bevel:radius=$r r.txt >wide.txt &&
	outputs wide.txt | sed -n 2p >w2 &&
	sed -n 2p q >q2 &&
	test_cmp_numbers w2 q2 1e-5 &&
	! test_cmp_numbers p1 w2 1e-3 2>/dev/null
'

test_expect_success 'roughen stops at the smallest half extent' '
	gbuf big.txt "0 1.5 0" "0 1.5 0 0.913319 0.407252 0 0.913319 0.407252 0 1" &&
	reflect-project -fa -m bevel:radius=0.3:roughen=100 big.txt >a.txt &&
	reflect-project -fa -m bevel:radius=1.5 big.txt >b.txt &&
	outputs a.txt >ga && outputs b.txt >gb &&
	test_cmp_numbers gb ga 1e-6
'

test_expect_success 'a point outside the box: D = R, infinite distances, no NaN' '
	gbuf out.txt "0 1.5 0" "4 1 0 -1 0 0 -1 0 0 0.1" "0 -0.5 0 0 1 0 0 1 0 0.1" &&
	reflect-project -fa -m bevel:radius=1 out.txt >o.txt &&
	outputs o.txt >got &&
	printf "%s\n" "-1 0 0 inf inf" "0 1 0 inf inf" >expect &&
	test_cmp_numbers expect got 1e-6
'

test_expect_success 'a floor point under the rounded edge: leaving at once or through the room' '
	# (2.9, 0, 0) is outside the shape of radius 1 (inside the box): a
	# ray into the wall leaves at once (t = 0), one back into the room
	# crosses it and leaves further on
	gbuf rim.txt "0 1.5 0" "2.9 0 0 0.995037 0.0995037 0 0.995037 0.0995037 0 0.1" \
		"2.9 0 0 -0.707107 0.707107 0 -0.707107 0.707107 0 0.1" &&
	reflect-project -fa -m bevel:radius=1 rim.txt >o.txt &&
	outputs o.txt >got &&
	! grep -i nan got &&
	test "$(sed -n 1p got | cut -d" " -f4)" = 0 &&
	awk "NR == 2 && \$4 > 3 && \$4 < 4.5 { ok = 1 } END { exit !ok }" got
'

test_expect_success 'refused: too large or negative a radius, with the fix' '
	test_expect_code 1 reflect-project -m bevel:radius=1.6 g.rfl >/dev/null 2>err &&
	test_grep "radius 1.6 is more than the probe box.s smallest half extent, 1.5: give radius=1.5 or less" err &&
	test_expect_code 1 reflect-project -m bevel:radius=-0.1 g.rfl >/dev/null 2>err &&
	test_grep "radius.*out of its range" err &&
	reflect-project -m bevel:radius=0.5 -fa rays.txt |
		sed "s/^PROBE_BEVEL=0.5$/PROBE_BEVEL=nine/" >bad.txt &&
	test_expect_code 1 reflect-shade -m none bad.txt >/dev/null 2>err &&
	test_grep "PROBE_BEVEL: .nine. needs a radius of 0 or more" err &&
	reflect-project -m bevel:radius=0.5 -fa rays.txt |
		sed "s/^PROBE_BEVEL=0.5$/PROBE_BEVEL=2/" >big.txt &&
	test_expect_code 1 reflect-shade -m none big.txt >/dev/null 2>err &&
	test_grep "PROBE_BEVEL: radius 2 is more than half the box on axis Y (1.5)" err
'

test_expect_success 'the shading tools trace their rays to the declared shape' '
	# a nearly mirror pixel looking at the corner, captured off its
	# centre: the raytraced lobe, traced by the host to the rounded box,
	# reads what mode none reads at bevel D (0.51 and 0.55: the lobe
	# against a prefiltered level), not what the box D shows (2.27)
	gbuf sharp.txt "1 1.2 0.3" \
		"0 1.5 0 0.803416 0.335829 0.491689 0.803416 0.335829 0.491689 0.02" &&
	reflect-project -m bevel:radius=1 sharp.txt >sb.rfl &&
	reflect-project -m box sharp.txt >sx.rfl &&
	reflect-shade -fa -m none sb.rfl >none.txt &&
	reflect-shade -fa -m raytraced:samples=64 sb.rfl >rt.txt &&
	reflect-shade -fa -m none sx.rfl >box.txt &&
	spec () { sed -n "/^$/,\$p" "$1" | sed 1d | awk "{ print \$(NF-1) }"; } &&
	echo "$(spec none.txt) $(spec rt.txt) $(spec box.txt)" >g &&
	awk "{ exit !(\$2 > 0.85 * \$1 && \$2 < 1.15 * \$1 && \$3 > 3 * \$2) }" g
'

test_done
