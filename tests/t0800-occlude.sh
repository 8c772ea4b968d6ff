#!/bin/sh
test_description='reflect-occlude: box and horizon occlusion, by hand and by the spec'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"
SQ="'"

# shaded FILE CHANNELS ROW...: an ascii stream of one row in the spec's room
shaded () {
	out=$1
	channels=$2
	shift 2
	{
		printf '#?REFLECT1\nNCOLS=%d\nNROWS=1\nNCOMP=%d\n' $# $(echo $channels | wc -w)
		printf 'CHANNELS=%s\n' "$channels"
		printf 'PROBE_BOX=-3 0 -2 3 3 2\nPROBE_CENTER=0 1.5 0\nFORMAT=ascii\n\n'
		for row
		do
			echo "$row"
		done
	} >"$out"
}

# the pixels of an ascii stream, one a line
pixels () {
	sed -n '/^$/,$p' "$1" | sed 1d | tr "\t" " "
}

test_expect_success 'box: sat(multiplier d^power), lerped by intensity, on spec and R G B' '
	# hit.dist 0.5, 2, +inf, -1 (outside: 0), 0.25; spec (2, 4, 8), R G B 1
	shaded in.txt "hit.dist spec.R spec.G spec.B R G B" \
		"0.5 2 4 8 1 1 1" "2 2 4 8 1 1 1" "inf 2 4 8 1 1 1" "-1 2 4 8 1 1 1" \
		"0.25 2 4 8 1 1 1" &&
	reflect-occlude -fa in.txt >out.txt &&
	pixels out.txt >got &&
	cat >expect <<-\EOF &&
	0.5 1 2 4 0.5 0.5 0.5 0.5
	2 2 4 8 1 1 1 1
	inf 2 4 8 1 1 1 1
	-1 0 0 0 0 0 0 0
	0.25 0.5 1 2 0.25 0.25 0.25 0.25
	EOF
	test_cmp_numbers expect got 1e-6 &&
	# intensity 0.5: 1 - 0.5 (1 - so); power 2: d^2; multiplier 4: sat(4 d)
	reflect-occlude -fa -m box:intensity=0.5 in.txt | pixels - | cut -d" " -f8 >i &&
	printf "%s\n" 0.75 1 1 0.5 0.625 >e && test_cmp_numbers e i 1e-6 &&
	reflect-occlude -fa -m box:power=2 in.txt | pixels - | cut -d" " -f8 >p &&
	printf "%s\n" 0.25 1 1 0 0.0625 >e && test_cmp_numbers e p 1e-6 &&
	reflect-occlude -fa -m box:multiplier=4 in.txt | pixels - | cut -d" " -f8 >m &&
	printf "%s\n" 1 1 1 0 1 >e && test_cmp_numbers e m 1e-6 &&
	# power 0: d^0 = 1, so sat(multiplier) everywhere but at d = +inf
	reflect-occlude -fa -m box:power=0:multiplier=0.3 in.txt | pixels - | cut -d" " -f8 >z &&
	printf "%s\n" 0.3 0.3 1 0.3 0.3 >e && test_cmp_numbers e z 1e-6
'

test_expect_success 'a second occlusion multiplies, and the channel keeps the product' '
	reflect-occlude in.txt | reflect-occlude -fa -m box:intensity=0.5 >twice.txt &&
	pixels twice.txt | sed -n 1p >got &&
	# 0.5 then 0.75: spec 2 x 0.375, occlusion 0.375
	echo "0.5 0.75 1.5 3 0.375 0.375 0.375 0.375" >expect &&
	test_cmp_numbers expect got 1e-6
'

# The spec's worked vectors (its section 15): the box -3 0 -2 .. 3 3 2,
# captured at (0, 1.5, 0), the camera at (-2, 1.6, -1.5), the floor's
# normal (0, 1, 0): specOcc 1, 0.6267 and 1 at (1, 0, 0.5), (2.5, 0, 1.5)
# and (0, 0, 0), where the box lies 2.6297, 0.6267 and 3.9576 away.
test_expect_success 'box: the spec worked vectors (specOcc)' '
	for p in "1 0 0.5" "2.5 0 1.5" "0 0 0"
	do
		echo "$p" | awk "{
			vx = -2 - \$1; vy = 1.6 - \$2; vz = -1.5 - \$3
			l = sqrt(vx * vx + vy * vy + vz * vz)
			print \$1, \$2, \$3, 0, 1, 0, vx / l, vy / l, vz / l, 0.5
		}" || return 1
	done >rows &&
	{
		printf "#?REFLECT1\nNCOLS=3\nNROWS=1\nNCOMP=10\n" &&
		printf "CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness\n" &&
		printf "PROBE_BOX=-3 0 -2 3 3 2\nPROBE_CENTER=0 1.5 0\nFORMAT=ascii\n\n" &&
		cat rows
	} >floor.txt &&
	reflect-project floor.txt | reflect-shade -m none 2>/dev/null |
		reflect-occlude -fa >o.txt &&
	pixels o.txt | awk "{ print \$(NF) }" >got &&
	printf "%s\n" 1 0.6267 1 >expect &&
	test_cmp_numbers expect got 1e-4
'

test_expect_success 'box: scale=box is the same at any scale, the default is not' '
	# the same room and hit twice as large: d / (smallest half extent)
	shaded small.txt "hit.dist spec.R spec.G spec.B" "0.6 1 1 1" &&
	shaded large.txt "hit.dist spec.R spec.G spec.B" "1.2 1 1 1" &&
	sed "s/^PROBE_BOX=.*/PROBE_BOX=-6 0 -4 6 6 4/" large.txt >large2.txt &&
	reflect-occlude -fa -m box:scale=box small.txt | pixels - | cut -d" " -f5 >a &&
	reflect-occlude -fa -m box:scale=box large2.txt | pixels - | cut -d" " -f5 >b &&
	echo 0.4 >e && test_cmp_numbers e a 1e-6 && test_cmp_numbers e b 1e-6 &&
	reflect-occlude -fa small.txt | pixels - | cut -d" " -f5 >c &&
	reflect-occlude -fa large2.txt | pixels - | cut -d" " -f5 >d &&
	echo 0.6 >e && test_cmp_numbers e c 1e-6 &&
	echo 1 >e && test_cmp_numbers e d 1e-6
'

test_expect_success 'box: follows the projection, the bevel too' '
	reflect-gbuffer -x 64 -y 36 >g.rfl &&
	reflect-project -m box g.rfl | reflect-shade -m none 2>/dev/null >sb.rfl &&
	reflect-project -m bevel:radius=1.2 g.rfl | reflect-shade -m none 2>/dev/null >sv.rfl &&
	reflect-occlude -h sb.rfl >ob.raw &&
	reflect-occlude -h sv.rfl >ov.raw &&
	! cmp -s ob.raw ov.raw &&
	reflect-occlude sv.rfl | reflect-info -s >stats &&
	grep "^	occlusion " stats | awk "{ exit !(\$2 >= 0 && \$3 <= 1 && \$6 == 0) }"
'

test_expect_success 'horizon: N = Ng is exactly 1; a mirror is the path tracer test' '
	# N up; R = (-0.6, 0.8, 0) for V = (0.6, 0.8, 0).  Ng = 2 N (any
	# length is the same normal): 1.  Ng tilted 60 degrees toward -x
	# has R.Ng = 0.92 (above: 1), toward +x -0.12 (below: 0)
	shaded h.txt "N.X N.Y N.Z Ng.X Ng.Y Ng.Z V.X V.Y V.Z roughness spec.R spec.G spec.B" \
		"0 1 0 0 2 0 0.6 0.8 0 0.5 1 1 1" \
		"0 1 0 -0.866025 0.5 0 0.6 0.8 0 0.001 1 1 1" \
		"0 1 0 0.866025 0.5 0 0.6 0.8 0 0.001 1 1 1" &&
	reflect-occlude -fa -m horizon h.txt | pixels - | awk "{ print \$NF }" >got &&
	printf "%s\n" 1 1 0 >expect &&
	test_cmp_numbers expect got 1e-6
'

# Under an environment of one radiance the factor is exact: the raytraced
# mode, which drops its rays below Ng, gives none's result times it.
test_expect_success 'horizon: under a uniform sky, the raytraced result of a bumped surface' '
	awk -v n=16 "BEGIN { for (k = 0; k < 5; k++) {
		printf \"#?REFLECT1\\nENVMAP=CUBE\\nLEVEL=%d\\nLEVELS=5\\nPREFILTER=ggx\\n\", k
		printf \"MAPPING=unity\\nSTEPS=4\\nNCOLS=%d\\nNROWS=%d\\n\", n, 6 * n
		printf \"NCOMP=3\\nCHANNELS=R G B\\nFORMAT=ascii\\n\\n\"
		for (j = 0; j < 6 * n * n; j++) print 1, 1, 1
		n = n / 2 } }" >sky.rfl &&
	reflect-gbuffer -x 160 -y 90 | reflect-project >g160.rfl &&
	reflect-shade -m none --final --diffuse=off --env=sky.rfl g160.rfl 2>/dev/null |
		reflect-occlude -fa -m horizon >none.txt &&
	reflect-shade -fa -m raytraced:samples=256 --final --diffuse=off --env=sky.rfl g160.rfl >rt.txt 2>/dev/null &&
	column none.txt occlusion G >a &&
	column rt.txt G >b &&
	paste -d" " a b | awk "\$1 < 0.999 {
		n++; e += (\$2 - \$3) ^ 2; u += (\$2 / \$1 - \$3) ^ 2; s += \$3
	} END {
		printf \"%d pixels: %.4f occluded, %.4f not\\n\", n, sqrt(e / n) / (s / n), sqrt(u / n) / (s / n)
		exit !(n > 50 && sqrt(e / n) < 0.03 * s / n && sqrt(u / n) > 0.08 * s / n)
	}"
'

test_expect_success 'horizon: leaves the flat room of the default scene alone' '
	reflect-occlude -m horizon sb.rfl | reflect-info -s >stats &&
	# the bumped pillar is darkened somewhere, the rest is 1
	grep "^	occlusion " stats | awk "{ exit !(\$2 < 0.9 && \$3 == 1) }" &&
	reflect-occlude -fa -m horizon sb.rfl | pixels - >all &&
	awk "{ n++; if (\$NF == 1) one++ } END { exit !(one > 0.9 * n) }" all
'

test_expect_success 'the same bytes at 1 and 2 threads' '
	reflect-occlude -h -j1 -m horizon sv.rfl >a.raw &&
	reflect-occlude -h -j2 -m horizon sv.rfl >b.raw &&
	cmp a.raw b.raw &&
	reflect-occlude -h -j1 sv.rfl >c.raw &&
	reflect-occlude -h -j2 sv.rfl >d.raw &&
	cmp c.raw d.raw
'

test_expect_success 'refused: no reflection, no channel, unknown mode or parameter' '
	reflect-project g.rfl >p.rfl &&
	test_expect_code 1 reflect-occlude p.rfl >/dev/null 2>err &&
	test_grep "no channel .spec.R.: occlusion darkens a shaded reflection; run reflect-shade first" err &&
	shaded nong.txt "R.X R.Y R.Z N.X N.Y N.Z roughness spec.R spec.G spec.B" "0 1 0 0 1 0 0.5 1 1 1" &&
	test_expect_code 1 reflect-occlude -m horizon nong.txt >/dev/null 2>err &&
	test_grep "no channel .Ng.X." err &&
	test_expect_code 1 reflect-occlude -m nosuch sb.rfl >/dev/null 2>err &&
	test_grep "unknown occlusion mode .nosuch." err &&
	test_expect_code 1 reflect-occlude -m box:scale=metres sb.rfl >/dev/null 2>err &&
	test_grep "scale" err &&
	shaded noprobe.txt "hit.dist spec.R spec.G spec.B" "1 1 1 1" &&
	sed "/^PROBE_/d" noprobe.txt >np.txt &&
	test_expect_code 1 reflect-occlude -m box:scale=box np.txt >/dev/null 2>err &&
	test_grep "scale=box needs the probe box" err
'

# The reflection occlusion darkens, and the occlusion before it, were
# read unchecked: a NaN spec.R went out as NaN, -inf as -inf, an
# occlusion of NaN as NaN, under every --invalid.  Pixel 1 is good; in
# pixel 2 spec.R is NaN, in 3 spec.G -inf, in 4 the occlusion NaN.  The
# host reads them for every occlusion mode.
test_expect_success 'the reflection and the occlusion it had keep the rules' '
	shaded bad.txt "hit.dist spec.R spec.G spec.B R G B occlusion" \
		"1 0.5 0.5 0.5 1 1 1 1" "1 nan 0.5 0.5 1 1 1 1" \
		"1 0.5 -inf 0.5 1 1 1 1" "1 0.5 0.5 0.5 1 1 1 nan" &&
	test_expect_code 1 reflect-occlude bad.txt >/dev/null 2>err &&
	test_one_line_message reflect-occlude err &&
	test_grep "${SQ}bad.txt${SQ}: frame 1, row 1, pixel 2: channel ${SQ}spec.R${SQ} is nan" err &&
	shaded occ.txt "hit.dist spec.R spec.G spec.B occlusion" "1 1 1 1 1.5" &&
	test_expect_code 1 reflect-occlude occ.txt >/dev/null 2>err &&
	test_grep "pixel 1: channel ${SQ}occlusion${SQ} is 1.5, outside \[0, 1\]" err &&
	reflect-occlude -fa --invalid=clamp bad.txt >c.txt 2>err &&
	test_grep "frame 1: 3 pixels with invalid input clamped" err &&
	column c.txt spec.R spec.G occlusion >got &&
	printf "%s\n" "0.5 0.5 1" "0 0.5 1" "0.5 -3.40282347e+38 1" "0.5 0.5 0" >want &&
	cmp_numbers want got 0 &&
	reflect-occlude -fa --invalid=zero bad.txt >z.txt 2>err &&
	test_grep "frame 1: 3 pixels with invalid input zeroed" err &&
	column z.txt spec.R spec.G spec.B R G B occlusion >got &&
	printf "%s\n" "0.5 0.5 0.5 1 1 1 1" "0 0 0 0 0 0 0" "0 0 0 0 0 0 0" "0 0 0 0 0 0 0" >want &&
	cmp_numbers want got 0
'

# multiplier (d / unit)^power past the float range: 0 x inf made NaN.
test_expect_success 'box: an extreme multiplier or power stays in [0, 1]' '
	shaded far.txt "hit.dist spec.R spec.G spec.B" "1e30 1 1 1" "0 1 1 1" &&
	reflect-occlude -fa -m box:multiplier=0:power=2 far.txt | column - occlusion >got &&
	printf "0\n0\n" >want &&
	cmp_numbers want got 0 &&
	reflect-occlude -fa -m box:multiplier=1e300 far.txt | column - occlusion >got &&
	printf "1\n0\n" >want &&
	cmp_numbers want got 0
'

test_expect_success 'the projection box and the occlusion box load side by side' '
	reflect-project -v -m box g.rfl 2>err >/dev/null &&
	test_grep "^reflect-project: mode .box. from .*/projection-box\.so.$" err &&
	reflect-occlude -v -m box sb.rfl 2>err >/dev/null &&
	test_grep "^reflect-occlude: mode .box. from .*/occlusion-box\.so. (" err
'

test_done
