#!/bin/sh
test_description='reflect-report: reflect-compare'"'"'s figures, a page that fetches nothing, its pictures, refusals'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

SQ="'"

# picture FILE W H EXPR: a linear R G B stream whose pixel x, y has the
# colour EXPR gives r, g and b in awk (x, y and a hash h in [0, 1) known)
picture () {
	awk -v w=$2 -v h=$3 'BEGIN {
		for (y = 0; y < h; y++)
			for (x = 0; x < w; x++) {
				hh = ((x * 7919 + y * 104729) % 1000) / 1000
				'"$4"'
				print r, g, b
			}
	}' | stream "$1" $2 $3 "R G B"
}

# figures PAGE: each row of the table as "NAME RELATIVE PSNR FLIP NS",
# the data-v figures in the order of the columns, "-" for none
figures () {
	sed -n 's|^<tr data-pic="[0-9]*"><td>\([^<]*\)</td>\(.*\)</tr>$|\1\2|p' "$1" |
	sed -e 's|<td class="num" data-v="">[^<]*</td>| -|g' \
		-e 's|<td class="num" data-v="\([^"]*\)">[^<]*</td>| \1|g'
}

# png PAGE ID FILE: the PNG of the page's image ID, decoded
png () {
	sed -n "s|.*<img id=\"$2\" [^>]*src=\"data:image/png;base64,\([^\"]*\)\".*|\1|p" "$1" |
	base64 -d >"$3" &&
	test -s "$3"
}

test_expect_success 'set up a truth and three modes, linear' '
	picture truth.rfl 40 30 "r = 0.2 + x / 20; g = 0.1 + y / 30; b = 0.3 + hh" &&
	picture bright.rfl 40 30 "r = 0.45 + x / 20; g = 0.35 + y / 30; b = 0.55 + hh" &&
	picture noisy.rfl 40 30 "r = 0.2 + x / 20 + 0.2 * hh; g = 0.1 + y / 30; b = 0.3 + hh * 0.5" &&
	picture flat.rfl 40 30 "r = 0.9; g = 0.6; b = 0.8"
'

test_expect_success 'a page of three modes: every row, in the order given' '
	reflect-report -o page.html --title="a <test>" --time=noisy=2.5 \
		--caption=flat="the mean & nothing else" truth.rfl bright=bright.rfl \
		noisy=noisy.rfl flat=flat.rfl 2>err &&
	test ! -s err &&
	figures page.html >rows &&
	cut -d" " -f1 rows >names &&
	printf "%s\n" bright noisy flat >expect &&
	diff -u expect names &&
	test_grep "<title>a &lt;test&gt;</title>" page.html &&
	test_grep "the mean &amp; nothing else" page.html &&
	test_grep "FLIP is HDR-FLIP" page.html
'

test_expect_success 'the table holds reflect-compare'"'"'s relative RMSE, PSNR and FLIP' '
	for m in bright noisy flat
	do
		test_expect_code 3 reflect-compare -fa $m.rfl truth.rfl >diff.out &&
		test_expect_code 3 reflect-compare --metric=flip -fa $m.rfl truth.rfl >flip.out &&
		echo "$m $(cut -d" " -f2,3 diff.out) $(cut -d" " -f1 flip.out)" >want &&
		grep "^$m " rows | cut -d" " -f1-4 >have &&
		test_cmp_numbers want have 1e-6 || return 1
	done &&
	# the figures mean something: 0.25 brighter everywhere is a PSNR of
	# 20 log10(1 / 0.25) = 12.0412 dB, and the flat colour is the worst FLIP
	grep "^bright " rows | cut -d" " -f3 >have &&
	echo 12.0412 >want &&
	test_cmp_numbers want have 1e-4 &&
	sort -k4 -g rows | tail -n 1 | cut -d" " -f1 >worst &&
	echo flat >want &&
	diff -u want worst
'

test_expect_success 'the time is the given one, and none where none was given' '
	cut -d" " -f1,5 rows >have &&
	printf "%s\n" "bright -" "noisy 2.5" "flat -" >want &&
	diff -u want have
'

test_expect_success 'the page names nothing outside itself' '
	! grep -i "https\?:" page.html &&
	! grep -i "<link\|@import\|url(" page.html &&
	grep -o " src=\"[a-z]*:" page.html | sort -u >schemes &&
	echo " src=\"data:" >want &&
	diff -u want schemes
'

test_expect_success 'every picture at 8 exposures, every mode a map: 35 PNG files' '
	grep -c "<img id=\"shot-[0-3]-[0-7]\" " page.html >n &&
	echo 32 >want &&
	diff -u want n &&
	grep -c "<img id=\"heat-[1-3]\" " page.html >n &&
	echo 3 >want &&
	diff -u want n
'

test_expect_success 'the pictures are reflect-export'"'"'s at each exposure' '
	png page.html shot-0-4 truth0.png &&
	reflect-export -o truth0-export.png truth.rfl &&
	reflect-compare -fa truth0.png truth0-export.png | cut -d" " -f1,4 >got &&
	echo "0 0" >want &&
	test_cmp_numbers want got 0 &&
	png page.html shot-2-5 noisy1.png &&
	reflect-export -e 1 -o noisy1-export.png noisy.rfl &&
	reflect-compare -fa noisy1.png noisy1-export.png | cut -d" " -f1,4 >got &&
	test_cmp_numbers want got 0 &&
	png page.html shot-2-0 noisy-4.png &&
	reflect-export -e -4 -o noisy-4-export.png noisy.rfl &&
	reflect-compare -fa noisy-4.png noisy-4-export.png | cut -d" " -f1,4 >got &&
	test_cmp_numbers want got 0 &&
	# and they differ from one exposure to the next
	test_expect_code 3 reflect-compare -fa noisy1.png noisy-4.png >/dev/null
'

test_expect_success '--stops=LO,HI: those exposures alone, the viewer at 0 or the nearest' '
	reflect-report --stops=-2,0 --time=noisy=2.5 -o stops.html truth.rfl bright=bright.rfl noisy=noisy.rfl \
		flat=flat.rfl &&
	grep -c "<img id=\"shot-[0-3]-[0-2]\" " stops.html >n &&
	grep -c "<img id=\"shot-" stops.html >all &&
	echo 12 >want &&
	diff -u want n &&
	diff -u want all &&
	test_grep "\"stops\": \[-2, -1, 0\], \"stop0\": 2," stops.html &&
	test_grep "id=\"exposure\" min=\"0\" max=\"2\" step=\"1\" value=\"2\"" stops.html &&
	png stops.html shot-2-0 noisy-2.png &&
	reflect-export -e -2 -o noisy-2-export.png noisy.rfl &&
	reflect-compare -fa noisy-2.png noisy-2-export.png | cut -d" " -f1,4 >got &&
	echo "0 0" >want &&
	test_cmp_numbers want got 0 &&
	png stops.html shot-0-2 truth0s.png &&
	reflect-compare -fa truth0s.png truth0-export.png | cut -d" " -f1,4 >got &&
	test_cmp_numbers want got 0 &&
	# the figures do not hang on the exposures shown
	figures stops.html >srows &&
	diff -u rows srows &&
	# all above 0: the viewer starts at the lowest, all below at the highest
	reflect-report --stops=1,3 truth.rfl noisy=noisy.rfl >up.html &&
	test_grep "\"stops\": \[1, 2, 3\], \"stop0\": 0," up.html &&
	png up.html shot-0-0 truth1.png &&
	reflect-export -e 1 -o truth1-export.png truth.rfl &&
	reflect-compare -fa truth1.png truth1-export.png | cut -d" " -f1,4 >got &&
	test_cmp_numbers want got 0 &&
	reflect-report --stops=-3,-2 truth.rfl noisy=noisy.rfl >down.html &&
	test_grep "\"stops\": \[-3, -2\], \"stop0\": 1," down.html &&
	reflect-report --stops=-16,-1 truth.rfl noisy=noisy.rfl >wide.html &&
	test $(grep -c "<img id=\"shot-" wide.html) = 32
'

test_expect_success '--stops refuses what is not two whole stops in order, at most 16' '
	for s in 1 2,1 -17,0 0,17 -8,8 a,b 1,2x ""
	do
		test_expect_code 1 reflect-report --stops="$s" truth.rfl noisy=noisy.rfl \
			>out 2>err &&
		echo "reflect-report: --stops: ${SQ}$s${SQ} is not LO,HI: whole stops from -16 to 16, LO no more than HI, at most 16 of them (e.g. --stops=-2,1)" >want &&
		diff -u want err &&
		test_line_count 0 out || return 1
	done
'

test_expect_success 'the maps are reflect-compare --metric=flip -o'"'"'s' '
	png page.html heat-2 heat.png &&
	test_expect_code 3 reflect-compare --metric=flip -o heat-compare.png noisy.rfl \
		truth.rfl >/dev/null &&
	reflect-compare -fa heat.png heat-compare.png | cut -d" " -f1,4 >got &&
	echo "0 0" >want &&
	test_cmp_numbers want got 0
'

test_expect_success 'display pictures: LDR-FLIP, one exposure, reflect-compare'"'"'s figures' '
	reflect-export -o truth.png truth.rfl &&
	reflect-export -o noisy.png noisy.rfl &&
	reflect-report truth.png noisy=noisy.png >ldr.html &&
	test_grep "FLIP is LDR-FLIP" ldr.html &&
	grep -c "<img id=\"shot-" ldr.html >n &&
	echo 2 >want &&
	diff -u want n &&
	# exposures are for linear pictures: display ones are shown as they are
	reflect-report --stops=-2,1 truth.png noisy=noisy.png >ldr-stops.html &&
	diff -u ldr.html ldr-stops.html &&
	figures ldr.html | cut -d" " -f1-4 >have &&
	test_expect_code 3 reflect-compare -fa noisy.png truth.png >diff.out &&
	test_expect_code 3 reflect-compare --metric=flip -fa noisy.png truth.png >flip.out &&
	echo "noisy $(cut -d" " -f2,3 diff.out) $(cut -d" " -f1 flip.out)" >want &&
	test_cmp_numbers want have 1e-6
'

test_expect_success 'the truth against itself: 0, PSNR infinite, FLIP 0' '
	reflect-report truth.rfl same=truth.rfl >same.html &&
	figures same.html >have &&
	echo "same 0 Infinity 0 -" >want &&
	diff -u want have
'

test_expect_success 'a file that cannot be read: its name and why, exit 1, no page' '
	test_expect_code 1 reflect-report -o bad.html truth.rfl a=nope.rfl >out 2>err &&
	echo "reflect-report: cannot open ${SQ}nope.rfl${SQ}: No such file or directory" >want &&
	diff -u want err &&
	test ! -s out &&
	test ! -e bad.html &&
	test_expect_code 1 reflect-report nope.rfl a=truth.rfl 2>err &&
	diff -u want err
'

test_expect_success 'pictures of different sizes: both sizes and the fix' '
	picture small.rfl 20 30 "r = 1; g = 1; b = 1" &&
	test_expect_code 1 reflect-report truth.rfl small=small.rfl >out 2>err &&
	test ! -s out &&
	echo "reflect-report: ${SQ}small.rfl${SQ} is 20x30 and the truth ${SQ}truth.rfl${SQ} 40x30: render every mode at the truth${SQ}s size" >want &&
	diff -u want err
'

test_expect_success 'NaN in a mode or the truth: how many, where, the fix' '
	picture nan.rfl 40 30 "r = (x == 3 && y == 2) ? \"nan\" : 0.5; g = 0.5; b = (x == 5 && y == 7) ? \"inf\" : 0.5" &&
	test_expect_code 1 reflect-report truth.rfl nan=nan.rfl >out 2>err &&
	test ! -s out &&
	echo "reflect-report: ${SQ}nan.rfl${SQ} has 2 colour values that are not finite (NaN or infinite), the first at pixel 3, 2 in R: a report measures finite colours; render it again without them" >want &&
	diff -u want err &&
	test_expect_code 1 reflect-report nan.rfl truth=truth.rfl 2>err &&
	test_grep "^reflect-report: the truth ${SQ}nan.rfl${SQ} has 2 colour values" err
'

test_expect_success 'a mode without a name, named twice, or empty' '
	test_expect_code 1 reflect-report truth.rfl noisy.rfl 2>err &&
	echo "reflect-report: ${SQ}noisy.rfl${SQ} has no name: give each mode as NAME=FILE" >want &&
	diff -u want err &&
	test_expect_code 1 reflect-report truth.rfl a=noisy.rfl a=flat.rfl 2>err &&
	echo "reflect-report: two modes are named ${SQ}a${SQ} (${SQ}noisy.rfl${SQ} and ${SQ}flat.rfl${SQ}): give each a name of its own" >want &&
	diff -u want err &&
	test_expect_code 1 reflect-report truth.rfl =noisy.rfl 2>err &&
	echo "reflect-report: ${SQ}noisy.rfl${SQ} has no name: give each mode as NAME=FILE" >want &&
	diff -u want err
'

test_expect_success 'captions and times for no mode, times that are no number' '
	test_expect_code 1 reflect-report --caption=nope=x truth.rfl a=noisy.rfl 2>err &&
	echo "reflect-report: --caption: no mode is named ${SQ}nope${SQ} (name a mode as NAME=FILE)" >want &&
	diff -u want err &&
	test_expect_code 1 reflect-report --time=a truth.rfl a=noisy.rfl 2>err &&
	echo "reflect-report: --time: ${SQ}a${SQ} is not NAME=NS" >want &&
	diff -u want err &&
	test_expect_code 1 reflect-report --time=a=fast truth.rfl a=noisy.rfl 2>err &&
	test_grep "^reflect-report: .*time.*fast" err &&
	test_line_count 1 err
'

test_expect_success 'a linear truth and a display mode: both named, the fix' '
	test_expect_code 1 reflect-report truth.rfl noisy=noisy.png 2>err &&
	echo "reflect-report: ${SQ}noisy.png${SQ} is display sRGB and the truth ${SQ}truth.rfl${SQ} linear: give every picture as the truth is (reflect-export them all to EXR, or all to PNG)" >want &&
	diff -u want err
'

test_expect_success 'no colour in common: the channels the truth lacks' '
	awk "BEGIN { for (i = 0; i < 1200; i++) print 0.5 }" | stream grey.rfl 40 30 "Y" &&
	test_expect_code 1 reflect-report truth.rfl grey=grey.rfl 2>err &&
	test_grep "^reflect-report: ${SQ}grey.rfl${SQ} has no colour the truth ${SQ}truth.rfl${SQ} has" err &&
	test_expect_code 1 reflect-report grey.rfl a=truth.rfl 2>err &&
	test_grep "^reflect-report: the truth ${SQ}grey.rfl${SQ} has no colour" err
'

test_expect_success 'no mode at all, or no truth: the usage' '
	test_expect_code 1 reflect-report truth.rfl 2>err &&
	test_grep "^usage: reflect-report " err &&
	test_expect_code 1 reflect-report 2>err &&
	test_grep "^usage: reflect-report " err
'

test_expect_success '--help on stdout; an unknown option: the usage, exit 1' '
	reflect-report --help >out 2>err &&
	test ! -s err &&
	test_grep "^usage: reflect-report " out &&
	test_expect_code 1 reflect-report --nope truth.rfl a=noisy.rfl >out 2>err &&
	test ! -s out &&
	test_grep "^usage: reflect-report " err
'

test_expect_success 'a page that cannot be written: the reason, exit 2' '
	test_expect_code 2 reflect-report -o nodir/page.html truth.rfl a=noisy.rfl 2>err &&
	echo "reflect-report: cannot write ${SQ}nodir/page.html${SQ}: No such file or directory" >want &&
	diff -u want err
'

test_expect_success 'the command line is checked before a picture is read' '
	test_expect_code 1 reflect-report nope.rfl a=nope.rfl b 2>err &&
	echo "reflect-report: ${SQ}b${SQ} has no name: give each mode as NAME=FILE" >want &&
	diff -u want err &&
	test_expect_code 1 reflect-report --time=a=fast nope.rfl a=nope.rfl 2>err &&
	test_grep "fast" err
'

if test -w /dev/full
then
	test_expect_success 'a full disk: a system error, exit 2' '
		test_expect_code 2 reflect-report truth.rfl a=noisy.rfl >/dev/full 2>err &&
		test_grep "^reflect-report: " err
	'
else
	test_skip 'a full disk: a system error, exit 2' 'no /dev/full'
fi

test_done
