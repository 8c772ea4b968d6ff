#!/bin/sh
test_description='reflect-compare --metric=flip: the reference implementation'"'"'s means, the map, thresholds, refusals'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

pairs="$srcdir/tests/flip"

# fill FILE W H "R G B": a stream of one colour
fill () {
	awk -v n=$(($2 * $3)) -v c="$4" 'BEGIN { for (i = 0; i < n; i++) print c }' |
		stream "$1" $2 $3 "R G B"
}

test_expect_success 'every pair agrees with the reference implementation within 1e-5' '
	grep -v "^#" "$pairs/REFERENCE" >ref &&
	test_line_count 8 ref &&
	while read mean a b rest
	do
		opts=${rest%%#*} &&
		test_expect_code 3 reflect-compare $opts -fa "$pairs/$a" "$pairs/$b" >got &&
		echo "$mean" >want &&
		cut -d" " -f1 got >have &&
		test_cmp_numbers want have 1e-5 || {
			echo "$a against $b ($opts): $(cat have), reference $mean" >&2
			return 1
		}
	done <ref
'

test_expect_success 'HDR-FLIP'"'"'s automatic exposures are the reference implementation'"'"'s' '
	test_expect_code 3 reflect-compare --metric=flip -fa "$pairs/sky-test.exr" \
		"$pairs/sky-ref.exr" | cut -d" " -f5- >got &&
	echo "-4.6975 2.5102 8" >want &&
	test_cmp_numbers want got 1e-4 &&
	test_expect_code 3 reflect-compare --metric=flip -fa "$pairs/glossy-test.exr" \
		"$pairs/glossy-ref.exr" | cut -d" " -f5- >got &&
	echo "-7.4196 0.5821 9" >want &&
	test_cmp_numbers want got 1e-4 &&
	# a start given, the stop and count still from the reference
	test_expect_code 3 reflect-compare --metric=flip --start-exposure=-1 -fa \
		"$pairs/sky-test.exr" "$pairs/sky-ref.exr" | cut -d" " -f5- >got &&
	echo "-1 2.5102 4" >want &&
	test_cmp_numbers want got 1e-4
'

test_expect_success 'identical pictures: 0 everywhere, exit 0, LDR and HDR' '
	for f in gradient-ref.png sky-ref.exr
	do
		reflect-compare --metric=flip -fa "$pairs/$f" "$pairs/$f" >got &&
		cut -d" " -f1-4 got >have &&
		echo "0 0 0 4096" >want &&
		test_cmp_numbers want have 0 || return 1
	done &&
	reflect-compare --metric=flip "$pairs/gradient-ref.png" "$pairs/gradient-ref.png" >out &&
	test_grep "LDR-FLIP, R G B, 4096 pixels" out &&
	test_grep "^PASS$" out
'

# Green against blue, flat: no features, and the colour error is the
# largest there is (cmax), which FLIP maps to 1 exactly; the map shows
# magma'"'"'s two ends.
test_expect_success 'the map: the pictures'"'"' size, magma from 0 to 1' '
	fill g.txt 8 6 "0 1 0" &&
	fill b.txt 8 6 "0 0 1" &&
	test_expect_code 3 reflect-compare --metric=ldr-flip -fa -o top.png g.txt b.txt >got &&
	echo "1 1 100 48" >want &&
	test_cmp_numbers want got 1e-5 &&
	"$builddir/tests/imgdump" -8 top.png >dump &&
	sed -n 1p dump >size &&
	echo "8 6 3" >want &&
	diff want size &&
	sed 1,2d dump | sort -u >colours &&
	echo "252 253 191" >want &&
	diff want colours &&
	reflect-compare --metric=ldr-flip -o bottom.png g.txt g.txt >out &&
	"$builddir/tests/imgdump" -8 bottom.png | sed 1,2d | sort -u >colours &&
	echo "0 0 4" >want &&
	diff want colours &&
	# the size of a real pair, and the same map on one thread or two
	test_expect_code 3 reflect-compare --metric=flip -j 1 -o j1.png \
		"$pairs/patches-test.png" "$pairs/patches-ref.png" >out1 &&
	test_expect_code 3 reflect-compare --metric=flip -j 2 -o j2.png \
		"$pairs/patches-test.png" "$pairs/patches-ref.png" >out2 &&
	cmp j1.png j2.png &&
	diff out1 out2 &&
	"$builddir/tests/imgdump" j1.png | sed -n 1p >size &&
	echo "128 96 3" >want &&
	diff want size
'

test_expect_success '--json: the metric, the mean, the exposures, the result' '
	test_expect_code 3 reflect-compare --metric=flip --json "$pairs/sky-test.exr" \
		"$pairs/sky-ref.exr" >j &&
	test_grep "\"metric\": \"hdr-flip\"," j &&
	test_grep "\"pixels\": 4096," j &&
	test_grep "\"mean\": 0.04460" j &&
	test_grep "\"exposures\": 8," j &&
	test_grep "\"ppd\": 67.02064" j &&
	test_grep "\"result\": \"fail\"" j &&
	reflect-compare --metric=flip --json "$pairs/edges-ref.png" "$pairs/edges-ref.png" >j &&
	test_grep "\"metric\": \"ldr-flip\"," j &&
	! grep -q exposure j &&
	test_grep "\"result\": \"pass\"" j
'

# gradient: mean 0.0439, max 0.1823; 33.3 % of the pixels over
# 0.05 (the share -f a prints)
test_expect_success 'thresholds on the per-pixel FLIP, with exit statuses' '
	g="$pairs/gradient-test.png $pairs/gradient-ref.png" &&
	reflect-compare --metric=flip --fail=0.19 $g >out &&
	test_grep "^PASS$" out &&
	test_expect_code 3 reflect-compare --metric=flip --fail=0.18 $g >out &&
	test_grep "^FAIL$" out &&
	share=$(reflect-compare --metric=flip --fail=0.05 --failpercent=100 -fa $g |
		cut -d" " -f3) &&
	test "$(echo "$share" | awk "{ print (\$1 > 1 && \$1 < 99) }")" = 1 &&
	above=$(echo "$share" | awk "{ print \$1 + 0.01 }") &&
	below=$(echo "$share" | awk "{ print \$1 - 0.01 }") &&
	reflect-compare --metric=flip --fail=0.05 --failpercent=$above $g >out &&
	test_expect_code 3 reflect-compare --metric=flip --fail=0.05 --failpercent=$below $g >out &&
	test_expect_code 3 reflect-compare --metric=flip --fail=1 --hardfail=0.1 $g >out &&
	reflect-compare --metric=flip --fail=1 --warn=0.1 $g >out &&
	test_grep "^WARNING$" out
'

# 4 x 2, the left half on the mask: green against blue there, the same
# grey on the right; the filters see the whole picture, the figures the
# mask alone.
test_expect_success 'a mask leaves pixels out of the figures and greys them on the map' '
	stream ma.txt 4 2 "R G B mask" <<-\EOF &&
	0 1 0 1
	0 1 0 1
	0.5 0.5 0.5 0
	0.5 0.5 0.5 0
	0 1 0 1
	0 1 0 1
	0.5 0.5 0.5 0
	0.5 0.5 0.5 0
	EOF
	stream mb.txt 4 2 "R G B" <<-\EOF &&
	0 0 1
	0 0 1
	0.5 0.5 0.5
	0.5 0.5 0.5
	0 0 1
	0 0 1
	0.5 0.5 0.5
	0.5 0.5 0.5
	EOF
	test_expect_code 3 reflect-compare --metric=ldr-flip --mask --objid=none --erode=0 \
		-fa -o m.png ma.txt mb.txt >got &&
	test "$(cut -d" " -f4 got)" = 4 &&
	test_expect_code 3 reflect-compare --metric=ldr-flip -fa ma.txt mb.txt >all &&
	test "$(cut -d" " -f4 all)" = 8 &&
	awk "{ exit !(\$1 > 0.5) }" got &&
	awk -v m="$(cut -d" " -f1 got)" "{ exit !(\$1 < m) }" all &&
	"$builddir/tests/imgdump" -8 m.png | sed -n 5p >grey &&
	echo "38 38 38" >want &&
	diff want grey
'

test_expect_success 'refused: nonsense named, with the fix' '
	p="$pairs/gradient-test.png" r="$pairs/gradient-ref.png" &&
	test_expect_code 1 reflect-compare --metric=hdr-flip $p $r 2>err &&
	test_grep "hdr-flip compares linear pictures, and .*gradient-test.png. is display sRGB: use --metric=ldr-flip" err &&
	test_expect_code 1 reflect-compare --metric=flip $p "$pairs/sky-ref.exr" 2>err &&
	test_grep "is display sRGB, .*sky-ref.exr. linear: name the metric" err &&
	test_expect_code 1 reflect-compare --metric=flip "$pairs/edges-test.png" $r 2>err &&
	test_grep "is 96x64, .*64x64: compare pictures of one size" err &&
	test_expect_code 1 reflect-compare --metric=flop $p $r 2>err &&
	test_grep "metric: .flop. is not diff, flip, ldr-flip or hdr-flip" err &&
	test_expect_code 1 reflect-compare --metric=flip --start-exposure=1 $p $r 2>err &&
	test_grep "are HDR-FLIP.s, and .* is LDR-FLIP" err &&
	test_expect_code 1 reflect-compare --metric=flip -c R,G $p $r 2>err &&
	test_grep "names 2 channels, not three" err &&
	test_expect_code 1 reflect-compare --metric=flip --viewing=0.7,0.7 $p $r 2>err &&
	test_grep "is not DISTANCE,WIDTH,PIXELS" err &&
	test_expect_code 1 reflect-compare --metric=flip --ppd=0 $p $r 2>err &&
	test_grep "ppd" err &&
	test_expect_code 1 reflect-compare --metric=flip --scale=2 $p $r 2>err &&
	test_grep "FLIP.s map is 0 to 1" err &&
	test_expect_code 1 reflect-compare --metric=flip --exposures=2.5 \
		"$pairs/sky-test.exr" "$pairs/sky-ref.exr" 2>err &&
	test_grep "not a whole number" err &&
	test_expect_code 1 reflect-compare --metric=flip --start-exposure=2 --stop-exposure=1 \
		"$pairs/sky-test.exr" "$pairs/sky-ref.exr" 2>err &&
	test_grep "start exposure 2 is above its stop exposure 1" err
'

test_expect_success 'refused: a reference too dark for exposures, values not finite' '
	fill k.txt 4 4 "0 0 0" &&
	fill w.txt 4 4 "1 1 1" &&
	test_expect_code 1 reflect-compare --metric=flip w.txt k.txt >out 2>err &&
	test ! -s out &&
	test_grep "k.txt. (the reference): more than half its pixels are black" err &&
	test_grep "give --start-exposure and --stop-exposure" err &&
	# given, they serve
	test_expect_code 3 reflect-compare --metric=flip --start-exposure=0 --stop-exposure=0 \
		--exposures=1 -fa w.txt k.txt >got &&
	test "$(cut -d" " -f4- got)" = "16 0 0 1" &&
	# start and stop given, the count follows from them alone
	test_expect_code 3 reflect-compare --metric=flip --start-exposure=-1 --stop-exposure=1.5 \
		-fa w.txt k.txt >got &&
	test "$(cut -d" " -f5-7 got)" = "-1 1.5 3" &&
	stream n.txt 2 1 "R G B" <<-\EOF &&
	0.5 nan 0.5
	0.5 0.5 0.5
	EOF
	fill m.txt 2 1 "0.5 0.5 0.5" &&
	test_expect_code 1 reflect-compare --metric=flip n.txt m.txt 2>err &&
	test_grep "1 values are not finite (the first at pixel 0, 0): FLIP compares finite colours" err
'

test_done
