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

test_expect_success 'a bad --invalid is a usage error' '
	test_expect_code 1 reflect-project --invalid=maybe good.txt 2>err &&
	test_grep "^reflect-project: --invalid: ${SQ}maybe${SQ} is not error, clamp or zero$" err &&
	test_expect_code 1 reflect-shade --invalid=maybe 2>err </dev/null &&
	test_grep "is not error, clamp or zero$" err
'

test_done
