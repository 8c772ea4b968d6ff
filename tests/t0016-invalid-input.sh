#!/bin/sh
test_description='NaN, Inf, zero vectors and out-of-range values: refused by default, clamped or zeroed on request'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

SQ="'"
GB="P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness"
PROBE="PROBE_BOX=-3 0 -2 3 3 2"
CENTER="PROBE_CENTER=0 1.5 0"

# A floor pixel seen from (-2, 1.6, -1.5), its view unit by hand:
# P = (1, 0, 0.5), V = (-3, 1.6, -2) / |(-3, 1.6, -2)| = / 3.9446.
good="1 0 0.5 0 1 0 -0.760532 0.405617 -0.507021 0.3"

test_expect_success 'G-buffers with one bad pixel each' '
	for bad in "nan 0 0.5 0 1 0 -0.760532 0.405617 -0.507021 0.3" \
		"1 0 0.5 0 0 0 -0.760532 0.405617 -0.507021 0.3" \
		"1 0 0.5 0 1 0 inf 0.405617 -0.507021 0.3" \
		"1 0 0.5 0 1e30 0 -0.760532 0.405617 -0.507021 0.3" \
		"1 0 0.5 0 1e-30 0 -0.760532 0.405617 -0.507021 0.3"
	do
		n=$((${n:-0} + 1)) &&
		printf "%s\n" "$good" "$good" "$good" "$good" "$bad" "$good" |
		stream bad$n.txt 3 2 "$GB" "$PROBE" "$CENTER" || return 1
	done &&
	printf "%s\n" "$good" "$good" "$good" "$good" "$good" "$good" |
	stream good.txt 3 2 "$GB" "$PROBE" "$CENTER"
'

# The pixel is row 2, pixel 2 (counted from 1, as the reader counts).
test_expect_success 'reflect-project refuses each, naming frame, row, pixel and channel' '
	for n in 1 2 3 4 5
	do
		test_expect_code 1 reflect-project bad$n.txt >/dev/null 2>err$n &&
		test_one_line_message reflect-project err$n &&
		test_grep "^reflect-project: ${SQ}bad$n.txt${SQ}: frame 1, row 2, pixel 2: " err$n &&
		test_grep "(--invalid=clamp or --invalid=zero goes on)$" err$n || return 1
	done &&
	test_grep "channel ${SQ}P.X${SQ} is nan" err1 &&
	test_grep "N is (0, 0, 0), not a direction" err2 &&
	test_grep "V is (inf, 0.405617, -0.507021), not finite" err3 &&
	test_grep "N is (0, 1e+30, 0), too long to normalise in float" err4 &&
	test_grep "N is (0, 1e-30, 0), too short to normalise in float" err5
'

test_expect_success 'a bad pixel in a later frame names that frame' '
	cat good.txt bad1.txt >two.txt &&
	test_expect_code 1 reflect-project two.txt >/dev/null 2>err &&
	test_grep "${SQ}two.txt${SQ}: frame 2, row 2, pixel 2: channel ${SQ}P.X${SQ} is nan" err
'

# Two bad pixels on different threads' rows: the first in row order is
# named whatever the thread count.
test_expect_success 'the first bad pixel is named at any thread count' '
	printf "%s\n" "$good" "$good" "$good" "$good" "$good" \
		"1 0 0.5 0 1 0 0 0 0 0.3" \
		"nan 0 0.5 0 1 0 -0.760532 0.405617 -0.507021 0.3" "$good" "$good" |
	stream late.txt 3 3 "$GB" "$PROBE" "$CENTER" &&
	for j in 1 2
	do
		test_expect_code 1 reflect-project -j $j late.txt >/dev/null 2>err &&
		test_grep "frame 1, row 2, pixel 3: V is (0, 0, 0), not a direction" err || return 1
	done
'

test_expect_success '--invalid=zero: the bad pixel is 0, the others as without it' '
	reflect-project -fa good.txt >good.out &&
	reflect-project -fa --invalid=zero bad2.txt >zero.out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "${SQ}bad2.txt${SQ}: frame 1: 1 pixel with invalid input zeroed" err &&
	column zero.out R.X R.Y R.Z D.X D.Y D.Z hit.dist probe.dist >got &&
	column good.out R.X R.Y R.Z D.X D.Y D.Z hit.dist probe.dist >want &&
	sed -n 5p got >bad.line && echo "0 0 0 0 0 0 0 0" >zeros &&
	cmp_numbers zeros bad.line 0 &&
	sed 5d got >rest && sed 5d want >want.rest &&
	cmp_numbers want.rest rest 0
'

# Clamped: N = (0, 1e30, 0) is normalised to (0, 1, 0), the good pixel's
# own normal, so every output is the good one's; P.X = NaN becomes 0.
test_expect_success '--invalid=clamp: a long normal is normalised, NaN P becomes 0' '
	reflect-project -fa --invalid=clamp bad4.txt >clamp4.out 2>err &&
	test_grep "1 pixel with invalid input clamped" err &&
	column clamp4.out R.X R.Y R.Z D.X D.Y D.Z hit.dist probe.dist >got &&
	cmp_numbers want got 1e-6 &&
	printf "%s\n" "0 0 0.5 0 1 0 -0.760532 0.405617 -0.507021 0.3" |
	stream zerox.txt 1 1 "$GB" "$PROBE" "$CENTER" &&
	reflect-project -fa zerox.txt >zerox.out &&
	column zerox.out D.X D.Y D.Z hit.dist >want.p &&
	reflect-project -fa --invalid=clamp bad1.txt 2>/dev/null >clamp1.out &&
	column clamp1.out D.X D.Y D.Z hit.dist | sed -n 5p >got.p &&
	cmp_numbers want.p got.p 1e-6
'

test_expect_success 'walls (mask 0) may carry V = 0' '
	printf "%s\n" "1 0 0.5 0 1 0 0 0 0 0.3 0" "$good 1" |
	stream wall.txt 2 1 "$GB mask" "$PROBE" "$CENTER" &&
	reflect-project wall.txt >/dev/null
'

test_expect_success 'reflect-shade refuses roughness and mask outside [0, 1]' '
	level_chain chain.rfl 8 4 linear &&
	printf "%s\n" "0 1 0 0.5" "0 1 0 1.5" |
	stream r.txt 2 1 "D.X D.Y D.Z roughness" &&
	test_expect_code 1 reflect-shade -m none --env=chain.rfl r.txt >/dev/null 2>err &&
	test_grep "${SQ}r.txt${SQ}: frame 1, row 1, pixel 2: channel ${SQ}roughness${SQ} is 1.5, outside \\[0, 1\\]" err &&
	printf "%s\n" "0 1 0 0.5 1 0 0 0" "0 1 0 0.5 2 0 0 0" |
	stream m.txt 2 1 "D.X D.Y D.Z roughness mask P.X P.Y P.Z" "$PROBE" "$CENTER" &&
	test_expect_code 1 reflect-shade -m none --env=chain.rfl m.txt >/dev/null 2>err &&
	test_grep "row 1, pixel 2: channel ${SQ}mask${SQ} is 2, outside \\[0, 1\\]" err
'

# roughness 1.5 clamps to 1: lod 3 of the linear mapping, 3 steps.
test_expect_success 'reflect-shade --invalid=clamp: roughness 1.5 reads as 1' '
	reflect-shade -f a -m none --invalid=clamp --env=chain.rfl r.txt >r.out 2>/dev/null &&
	column r.out spec.R | sed -n 2p >got &&
	echo 3 >want &&
	cmp_numbers want got 1e-6
'

# What a pixel emits (a scene that emits, reflect-gbuffer's emission.R G
# B) is what a wall shows and, with --final, what a mirror adds: it went
# out as it came, NaN, inf and -5 included, under every mode and every
# --invalid.  Pixels 1 and 2 are walls, pixel 3 a mirror whose emission
# only --final reads.
SH="P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness mask D.X D.Y D.Z hit.dist probe.dist"
floor="1 0 0.5 0 1 0 -0.760532 0.405617 -0.507021 0.3"
mirror="0.760532 0.405617 0.507021 1 2"

test_expect_success 'reflect-shade refuses emission that is no radiance, in every mode' '
	printf "%s\n" "$floor 0 $mirror nan 1 1" "$floor 0 $mirror 1 -5 1" \
		"$floor 1 $mirror 1 1 inf" |
	stream e.txt 3 1 "$SH emission.R emission.G emission.B" "$PROBE" "$CENTER" &&
	level_chain chain.rfl 8 4 linear &&
	for m in none approx hdrp godot footprint raytraced
	do
		for final in "" --final
		do
			test_expect_code 1 reflect-shade -m $m $final --env=chain.rfl e.txt \
				>/dev/null 2>err &&
			test_one_line_message reflect-shade err &&
			test_grep "${SQ}e.txt${SQ}: frame 1, row 1, pixel 1: channel ${SQ}emission.R${SQ} is nan, not a radiance (finite, not negative)" err ||
			return 1
		done || return 1
	done
'

test_expect_success '--invalid=clamp: NaN and -5 emit 0, inf the largest float' '
	for m in none approx hdrp godot footprint raytraced
	do
		reflect-shade -fa -m $m --invalid=clamp --env=chain.rfl e.txt >c.out 2>err &&
		test_grep "frame 1: 2 pixels with invalid input clamped" err &&
		column c.out spec.R spec.G spec.B | sed -n 1,2p >got &&
		printf "0 1 1\n1 0 1\n" >want &&
		cmp_numbers want got 0 &&
		reflect-shade -fa -m $m --final --invalid=clamp --env=chain.rfl e.txt >c.out 2>err &&
		test_grep "frame 1: 3 pixels with invalid input clamped" err &&
		column c.out R G B >got &&
		sed -n 1,2p got >wall && cmp_numbers want wall 0 &&
		awk "NR == 3 && !(\$1 >= 1 && \$1 < 100 && \$3 > 3.40282e38 && \$3 < 3.40283e38) { exit 1 }" got ||
		return 1
	done
'

test_expect_success '--invalid=zero: the pixel with a bad emission is 0' '
	for m in none approx hdrp godot footprint raytraced
	do
		reflect-shade -fa -m $m --invalid=zero --env=chain.rfl e.txt >z.out 2>err &&
		column z.out spec.R spec.G spec.B | sed -n 1,2p >got &&
		printf "0 0 0\n0 0 0\n" >want &&
		cmp_numbers want got 0 &&
		reflect-shade -fa -m $m --final --invalid=zero --env=chain.rfl e.txt >z.out 2>err &&
		test_grep "frame 1: 3 pixels with invalid input zeroed" err &&
		column z.out spec.R spec.G spec.B R G B >got &&
		printf "0 0 0 0 0 0\n0 0 0 0 0 0\n0 0 0 0 0 0\n" >want &&
		cmp_numbers want got 0 || return 1
	done
'

# The final colour reads the material itself: metallic and albedo out of
# [0, 1] were clamped without a word, and N and V taken at their length,
# so that a normal 4 long read the grazing term of n.v = 4.
test_expect_success 'reflect-shade --final holds its material to the rules' '
	MAT="$SH metallic albedo.R albedo.G albedo.B" &&
	printf "%s\n" "$floor 1 $mirror 0.5 0.9 0.8 0.7" "$floor 1 $mirror 2 0.9 0.8 0.7" \
		"$floor 1 $mirror 0.5 0.9 nan 0.7" |
	stream f.txt 3 1 "$MAT" "$PROBE" "$CENTER" &&
	test_expect_code 1 reflect-shade -m none --final --env=chain.rfl f.txt >/dev/null 2>err &&
	test_grep "row 1, pixel 2: channel ${SQ}metallic${SQ} is 2, outside \[0, 1\]" err &&
	reflect-shade -fa -m none --final --invalid=clamp --env=chain.rfl f.txt >f.out 2>/dev/null &&
	column f.out R G B | sed -n 2p >got &&
	printf "%s\n" "$floor 1 $mirror 1 0.9 0.8 0.7" | stream one.txt 1 1 "$MAT" "$PROBE" "$CENTER" &&
	reflect-shade -fa -m none --final --env=chain.rfl one.txt | column - R G B >want &&
	cmp_numbers want got 1e-6 &&
	printf "%s\n" "1 0 0.5 0 4 0 -0.760532 0.405617 -0.507021 0.3 1 $mirror 0.5 0.9 0.8 0.7" |
	stream long.txt 1 1 "$MAT" "$PROBE" "$CENTER" &&
	printf "%s\n" "$floor 1 $mirror 0.5 0.9 0.8 0.7" | stream unit.txt 1 1 "$MAT" "$PROBE" "$CENTER" &&
	reflect-shade -fa -m none --final --env=chain.rfl long.txt | column - R G B diffuse.R >got &&
	reflect-shade -fa -m none --final --env=chain.rfl unit.txt | column - R G B diffuse.R >want &&
	cmp_numbers want got 1e-5 &&
	printf "%s\n" "1 0 0.5 0 0 0 -0.760532 0.405617 -0.507021 0.3 1 $mirror 0.5 0.9 0.8 0.7" |
	stream zeron.txt 1 1 "$MAT" "$PROBE" "$CENTER" &&
	test_expect_code 1 reflect-shade -m none --final --env=chain.rfl zeron.txt >/dev/null 2>err &&
	test_grep "N is (0, 0, 0), not a direction" err
'

test_expect_success 'a bad --invalid is a usage error' '
	test_expect_code 1 reflect-project --invalid=maybe good.txt 2>err &&
	test_grep "^reflect-project: --invalid: ${SQ}maybe${SQ} is not error, clamp or zero$" err &&
	test_expect_code 1 reflect-shade --invalid=maybe 2>err </dev/null &&
	test_grep "is not error, clamp or zero$" err
'

test_done
