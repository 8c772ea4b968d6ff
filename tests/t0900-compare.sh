#!/bin/sh
test_description='reflect-compare: figures by hand, the eroded mask, thresholds and exit statuses'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

SQ="'"

# rgb FILE W H VALUE...: an ascii stream of R G B, one value a pixel (the
# same in the three channels), rows top first
rgb () {
	f=$1 w=$2 h=$3
	shift 3
	for v
	do
		echo "$v $v $v" || return 1
	done | stream "$f" $w $h "R G B"
}

test_expect_success 'identical pictures: 0, PSNR inf, exit 0' '
	rgb a.txt 2 2 0.1 0.2 0.3 0.4 &&
	reflect-compare a.txt a.txt >out &&
	test_grep "^PASS$" out &&
	reflect-compare -fa a.txt a.txt >got &&
	echo "0 0 inf 0 0 4" >expect &&
	test_cmp_numbers expect got 0
'

test_expect_success 'a constant offset: RMSE, relative RMSE, PSNR and max by hand' '
	# A = B + 0.5 everywhere: RMSE 0.5, B'"'"'s mean 0.25, relative 2,
	# PSNR 20 log10(1 / 0.5) = 6.0206, max 0.5, every pixel over 1e-6
	rgb b.txt 2 2 0.6 0.7 0.8 0.9 &&
	test_expect_code 3 reflect-compare -fa b.txt a.txt >got &&
	echo "0.5 2 6.0206 0.5 100 4" >expect &&
	test_cmp_numbers expect got 1e-4 &&
	# with peak 2: 20 log10(4) = 12.0412
	test_expect_code 3 reflect-compare -fa --peak=2 b.txt a.txt | cut -d" " -f3 >p &&
	echo 12.0412 >e && test_cmp_numbers e p 1e-4
'

test_expect_success 'thresholds as oiiotool --diff has them, with exit statuses' '
	# two of four pixels off by 0.5, two by 0.05
	rgb c.txt 2 2 0.6 0.7 0.35 0.45 &&
	reflect-compare --fail=0.6 c.txt a.txt >out &&
	test_grep "^PASS$" out &&
	test_expect_code 3 reflect-compare --fail=0.1 c.txt a.txt >out &&
	test_grep "^FAIL$" out &&
	reflect-compare --fail=0.1 --failpercent=50 c.txt a.txt >out &&
	test_expect_code 3 reflect-compare --fail=0.1 --failpercent=49 c.txt a.txt >out &&
	test_expect_code 3 reflect-compare --fail=1 --hardfail=0.3 c.txt a.txt >out &&
	reflect-compare --fail=1 --hardfail=0.6 c.txt a.txt >out &&
	reflect-compare --fail=1 --warn=0.1 c.txt a.txt >out &&
	test_grep "^WARNING$" out &&
	reflect-compare --fail=1 --warn=0.1 --warnpercent=50 c.txt a.txt >out &&
	test_grep "^PASS$" out
'

# 7 x 5, mask 1 everywhere, objid 2 in column 5 (from 0), 1 elsewhere.
# Erode 1 keeps the interior (columns 1..5, rows 1..3) but the columns
# next to the other object (4, 5): columns 1..3, 9 pixels; erode 2 keeps
# column 2 of row 2 alone; erode 0 all 35; without objid, the interior's
# 15.
test_expect_success 'the eroded mask, on a known one' '
	for y in 0 1 2 3 4
	do
		for x in 0 1 2 3 4 5 6
		do
			o=1 && test $x = 5 && o=2
			echo "0.5 0.5 0.5 1 $o" || return 1
		done || return 1
	done | stream m.txt 7 5 "R G B mask objid" &&
	for y in 0 1 2 3 4
	do
		for x in 0 1 2 3 4 5 6
		do
			echo "0.25 0.25 0.25" || return 1
		done || return 1
	done | stream z.txt 7 5 "R G B" &&
	for e in 0:35 1:9 2:1
	do
		test_expect_code 3 reflect-compare -fa --mask --erode=${e%:*} m.txt z.txt >got &&
		test "$(cut -d" " -f6 got)" = ${e#*:} || return 1
	done &&
	test_expect_code 3 reflect-compare -fa --mask --objid=none m.txt z.txt >got &&
	test "$(cut -d" " -f6 got)" = 15 &&
	# the mask may come from B
	test_expect_code 3 reflect-compare -fa --mask z.txt m.txt >got &&
	test "$(cut -d" " -f6 got)" = 9
'

test_expect_success 'a value that is not finite fails, and is counted' '
	rgb n.txt 2 2 0.1 nan 0.3 0.4 &&
	test_expect_code 3 reflect-compare n.txt a.txt >out &&
	test_grep "not finite   3 values" out &&
	test_expect_code 3 reflect-compare --json n.txt a.txt >j &&
	test_grep "\"max_error\": \"inf\"" j &&
	test_grep "\"nonfinite\": 3" j &&
	test_grep "\"result\": \"fail\"" j
'

# A file name is the user's: quotes, backslashes and control bytes in it
# must not break the JSON around it.
test_expect_success '--json: names with quotes, backslashes and tabs escaped' '
	name=$(printf "q\"b\\\\c\td.txt") &&
	cp a.txt "$name" &&
	reflect-compare --json "$name" a.txt >j &&
	test_grep "^  \"a\": \"q\\\\\"b\\\\\\\\c\\\\u0009d.txt\",$" j &&
	test_grep "^  \"b\": \"a.txt\",$" j &&
	test_grep "^  \"max_channel\": \"R\",$" j
'

test_expect_success 'channels: R G B by default, else spec.*; -c names any' '
	stream s.txt 1 1 "spec.R spec.G spec.B x" <<-\EOF &&
	1 2 3 9
	EOF
	stream t.txt 1 1 "x spec.B spec.G spec.R" <<-\EOF &&
	9 3 2 1.5
	EOF
	test_expect_code 3 reflect-compare s.txt t.txt >out &&
	test_grep "spec.R spec.G spec.B, 1 pixels" out &&
	reflect-compare -c x s.txt t.txt >out &&
	test_grep "^PASS$" out &&
	test_expect_code 1 reflect-compare -c q s.txt t.txt 2>err &&
	test_grep "has no channel .q." err
'

# Two pictures whose colours differ but whose other channels agree: a
# comparison of colour finds them apart, and one with no colour in
# common is refused, never a pass on the mask or the ids.
test_expect_success 'no colour in common: refused, naming what each side has' '
	stream c1.txt 2 1 "R G B mask objid" <<-\EOF &&
	0.1 0.2 0.3 1 4
	0.4 0.5 0.6 1 4
	EOF
	stream c2.txt 2 1 "mask objid" <<-\EOF &&
	1 4
	1 4
	EOF
	stream c3.txt 2 1 "spec.R spec.G spec.B mask objid" <<-\EOF &&
	0.9 0.9 0.9 1 4
	0.9 0.9 0.9 1 4
	EOF
	for pair in "c1.txt c2.txt" "c2.txt c1.txt" "c1.txt c3.txt" "c2.txt c2.txt"
	do
		test_expect_code 1 reflect-compare $pair >out 2>err &&
		test ! -s out &&
		test_grep "no colour to compare" err &&
		test_grep ".mask. .objid." err || return 1
	done &&
	echo "reflect-compare: no colour to compare: neither R G B nor spec.R spec.G spec.B is in both (${SQ}c2.txt${SQ} has ${SQ}mask${SQ} ${SQ}objid${SQ}; ${SQ}c2.txt${SQ} has ${SQ}mask${SQ} ${SQ}objid${SQ}); name them with -c, as A_NAME=B_NAME where they differ" >expect &&
	diff -u expect err
'

test_expect_success '-c A_NAME=B_NAME: channels named differently on each side' '
	stream h1.txt 2 1 "half1.R half1.G" <<-\EOF &&
	0.5 1
	0.25 2
	EOF
	stream h2.txt 2 1 "half2.G half2.R" <<-\EOF &&
	1 0.5
	2 0.75
	EOF
	# half1.R against half2.R: 0 and 0.5 apart, RMSE sqrt(0.125)
	test_expect_code 3 reflect-compare -fa -c half1.R=half2.R h1.txt h2.txt >got &&
	cut -d" " -f1 got >rmse &&
	echo 0.353553391 >expect &&
	test_cmp_numbers expect rmse 1e-8 &&
	reflect-compare -c half1.G=half2.G h1.txt h2.txt >out &&
	test_grep "half1.G=half2.G, 2 pixels" out &&
	test_grep "^PASS$" out &&
	test_expect_code 1 reflect-compare -c half1.R=half1.R h1.txt h2.txt 2>err &&
	test_grep ".h2.txt. has no channel .half1.R." err &&
	for bad in "=half2.R" "half1.R=" "a=b=c"
	do
		test_expect_code 1 reflect-compare -c "$bad" h1.txt h2.txt 2>err &&
		test_grep "is not A_NAME=B_NAME" err || return 1
	done
'

test_expect_success 'an empty mask compares nothing and never passes' '
	stream e1.txt 2 1 "R G B mask" <<-\EOF &&
	0.1 0.2 0.3 0
	0.4 0.5 0.6 0
	EOF
	stream e2.txt 2 1 "R G B" <<-\EOF &&
	9 9 9
	9 9 9
	EOF
	test_expect_code 1 reflect-compare --mask --objid=none e1.txt e2.txt >out 2>err &&
	test ! -s out &&
	test_grep "no pixel to compare: the mask .mask. is empty" err
'

# A supersampled stream is the picture at twice its size: compared and
# drawn resolved, as reflect-export writes it.
test_expect_success 'a SUPERSAMPLE stream is resolved before it is compared' '
	reflect-gbuffer --supersample=2 -x 12 -y 8 | reflect-project |
		reflect-shade -m hdrp --final 2>/dev/null >ss.rfl &&
	reflect-export --depth=float -o ss.exr ss.rfl &&
	"$builddir/tests/imgdump" ss.exr | sed -n 1p >size &&
	echo "12 8 3" >expect &&
	diff expect size &&
	reflect-compare ss.exr ss.rfl >out &&
	test_grep "R G B, 96 pixels" out &&
	test_grep "^PASS$" out &&
	reflect-compare ss.rfl ss.rfl >out &&
	test_grep "96 pixels" out &&
	sed "s/^SUPERSAMPLE=2$/SUPERSAMPLE=5/" ss.rfl >bad.rfl &&
	test_expect_code 1 reflect-compare bad.rfl ss.rfl 2>err &&
	test_grep "SUPERSAMPLE=.5. is not a whole number in \[1, 16\] that divides the 24x16" err
'

test_expect_success 'an image against a stream, and a heat map with its bar' '
	reflect-gbuffer -x 40 -y 30 | reflect-project | reflect-shade -m none --final \
		2>/dev/null >shaded.rfl &&
	reflect-export -c R,G,B --depth=float -o shaded.exr shaded.rfl &&
	reflect-compare shaded.exr shaded.rfl >out &&
	test_grep "^PASS$" out &&
	reflect-shade -m hdrp --final shaded.rfl 2>/dev/null >other.rfl &&
	test_expect_code 3 reflect-compare -o heat.png other.rfl shaded.rfl >out &&
	"$builddir/tests/imgdump" heat.png | sed -n 1p >size &&
	# 40 columns, a gap of 4, the bar of 16, labels of 8 characters
	echo "116 30 3" >expect &&
	diff expect size
'

test_expect_success 'refused: one size for both, readable files, usage' '
	rgb small.txt 1 1 0.5 &&
	test_expect_code 1 reflect-compare small.txt a.txt 2>err &&
	test_grep "is 1x1, .a.txt. 2x2: compare pictures of one size" err &&
	test_expect_code 1 reflect-compare nope a.txt 2>err &&
	test_grep "nope" err &&
	test_expect_code 1 reflect-compare a.txt 2>err &&
	test_grep "^usage: reflect-compare" err &&
	test_expect_code 1 reflect-compare --mask=nomask a.txt a.txt 2>err &&
	test_grep "mask channel .nomask." err
'

truth="${REFLECT_TRUTH:-$srcdir/../shared/truth}"
if test -f "$truth/room-floor.gbuf.exr"
then
	test_expect_success 'the truth README scoring, as tests/truthscore has it' '
		reflect-import --box=-5,0,-5,5,4,5 --center=0,2,0 "$truth/room-floor.gbuf.exr" |
			reflect-project | reflect-shade -m hdrp --final \
			--env="$truth/room-floor.probe.cube.exr" >hdrp.rfl 2>/dev/null &&
		reflect-import "$truth/room-floor.ref.exr" >ref.rfl &&
		"$builddir/tests/truthscore" hdrp.rfl ref.rfl >want &&
		test_expect_code 3 reflect-compare -fa --mask hdrp.rfl "$truth/room-floor.ref.exr" >got &&
		awk "{ print \$6, \$2 }" got >g &&
		test_cmp_numbers want g 1e-6
	'
else
	test_skip 'the truth README scoring, as tests/truthscore has it' "no references in $truth"
fi

test_done
