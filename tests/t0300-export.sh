#!/bin/sh
test_description='reflect-export writes EXR, PNG, TIFF and JPEG with the values asked for'
. "$srcdir/tests/lib.sh"

imgdump="$builddir/tests/imgdump"

# Three pixels, one row.  Every 8-bit value expected below is worked out by
# hand: v -> v * 2^stops -> clamp to [0, 1] -> sRGB (12.92 v below 0.0031308,
# else 1.055 v^(1/2.4) - 0.055) -> round(255 v).
test_expect_success 'setup: a small ascii stream with known values' '
	cat >in.txt <<-\EOF &&
	#?REFLECT1
	NCOLS=3
	NROWS=1
	NCOMP=8
	CHANNELS=R G B A spec.R spec.G spec.B mask
	FORMAT=ascii

	0.25	0.0015	0.09	1	0.5	1	2	1
	0.6	-1	nan	1	0.125	0.25	0.75	0
	0.125	0.02	4	1	3	-2	0.1	1
	EOF
	reflect-info in.txt >/dev/null
'

test_expect_success 'exr: R G B by default, float values and names kept' '
	reflect-export -o a.exr in.txt &&
	"$imgdump" a.exr >dump &&
	cat >expect <<-\EOF &&
	3 1 3
	R G B
	0.25 0.0015 0.09
	0.6 -1 nan
	0.125 0.02 4
	EOF
	test_cmp_numbers expect dump 1e-7
'

test_expect_success 'exr: -c spec names the layer, the names are kept' '
	reflect-export -c spec -o spec.exr in.txt &&
	"$imgdump" spec.exr >dump &&
	cat >expect <<-\EOF &&
	3 1 3
	spec.R spec.G spec.B
	0.5 1 2
	0.125 0.25 0.75
	3 -2 0.1
	EOF
	test_cmp_numbers expect dump 1e-7
'

test_expect_success 'exr: -e 1 doubles the values and does not clamp them' '
	reflect-export -e 1 -c spec -o bright.exr in.txt &&
	"$imgdump" bright.exr >dump &&
	cat >expect <<-\EOF &&
	3 1 3
	spec.R spec.G spec.B
	1 2 4
	0.25 0.5 1.5
	6 -4 0.2
	EOF
	test_cmp_numbers expect dump 1e-6
'

test_expect_success 'exr: --half stores half floats (0.1 becomes 1638/16384)' '
	reflect-export --half -c spec -o half.exr in.txt &&
	"$imgdump" half.exr >dump &&
	cat >expect <<-\EOF &&
	3 1 3
	spec.R spec.G spec.B
	0.5 1 2
	0.125 0.25 0.75
	3 -2 0.0999755859375
	EOF
	test_cmp_numbers expect dump 1e-9 &&
	reflect-export --depth=half -c spec -o half2.exr in.txt &&
	"$imgdump" half2.exr >dump2 &&
	test_cmp_numbers expect dump2 1e-9
'

test_expect_success 'exr: -c all writes every channel, a list picks some' '
	reflect-export -c all -o all.exr in.txt &&
	"$imgdump" all.exr >dump &&
	sed -n 1p dump >size &&
	echo "3 1 8" >expect &&
	test_cmp_numbers expect size &&
	sed -n 2p dump | tr " " "\n" | sort >names &&
	printf "%s\n" A B G R mask spec.B spec.G spec.R >expect &&
	cmp expect names &&
	reflect-export -c mask,spec.G -o two.exr in.txt &&
	"$imgdump" two.exr >dump &&
	sed -n 2p dump >names &&
	test_grep "^mask spec.G$" names
'

test_expect_success 'png: exposure and sRGB, 8-bit values by hand' '
	# R: 0.25 0.6 0.125 x2 = 0.5 1.2 0.25 -> 0.7354 1 0.5371 -> 188 255 137
	# G: 0.0015 -1 0.02 x2 = 0.003 -2 0.04 -> 0.03876 0 0.2209 -> 10 0 56
	# B: 0.09 NaN 4 x2 = 0.18 NaN 8 -> 0.4614 0 1 -> 118 0 255
	reflect-export -e 1 -o a.png in.txt &&
	"$imgdump" -8 a.png >dump &&
	cat >expect <<-\EOF &&
	3 1 3
	R G B
	188 10 118
	255 0 0
	137 56 255
	EOF
	test_cmp_numbers expect dump 0
'

test_expect_success 'png: --srgb=off quantises linear values' '
	# 0.25 0.0015 0.09 -> 63.75 0.38 22.95; 0.6 -> 153; 0.125 0.02 -> 31.9 5.1
	reflect-export --srgb=off -o lin.png in.txt &&
	"$imgdump" -8 lin.png >dump &&
	cat >expect <<-\EOF &&
	3 1 3
	R G B
	64 0 23
	153 0 0
	32 5 255
	EOF
	test_cmp_numbers expect dump 0
'

test_expect_success 'png: --tone=filmic maps x to x(2.51x+0.03)/(x(2.43x+0.59)+0.14)' '
	# spec 0.5 1 2 -> 0.6163 0.8038 0.9149 -> 157 205 233
	#      0.125 0.25 0.75 -> 0.1707 0.3741 0.7358 -> 44 95 188
	#      3 -2 0.1 -> 0.9537 0 0.1258 -> 243 0 32
	reflect-export --tone=filmic --srgb=off -c spec -o filmic.png in.txt &&
	"$imgdump" -8 filmic.png >dump &&
	cat >expect <<-\EOF &&
	3 1 3
	R G B
	157 205 233
	44 95 188
	243 0 32
	EOF
	test_cmp_numbers expect dump 0
'

test_expect_success 'png: R G B A straight alpha (colour divided by A, then sRGB)' '
	cat >rgba.txt <<-\EOF &&
	#?REFLECT1
	NCOLS=1
	NROWS=1
	NCOMP=4
	CHANNELS=R G B A
	FORMAT=ascii

	0.125	0.05	0.3	0.25
	EOF
	# /0.25: 0.5 0.2 1.2 -> sRGB 0.7354 0.4845 1 -> 188 124 255; A 63.75 -> 64
	reflect-export -c R,G,B,A -o rgba.png rgba.txt &&
	"$imgdump" -8 rgba.png >dump &&
	cat >expect <<-\EOF &&
	1 1 4
	R G B A
	188 124 255 64
	EOF
	test_cmp_numbers expect dump 0
'

test_expect_success 'png: --depth=16 and one grey channel' '
	# 0.25 0.6 0.125 x 65535 = 16383.75 39321.0 8191.875
	reflect-export --depth=16 --srgb=off -c R -o grey16.png in.txt &&
	"$imgdump" -16 grey16.png >dump &&
	cat >expect <<-\EOF &&
	3 1 1
	Y
	16384
	39321
	8192
	EOF
	sed 2d dump >values && sed 2d expect >want &&
	test_cmp_numbers want values 0
'

test_expect_success 'tiff: 8-bit by default, float with --depth=float' '
	reflect-export -e 1 -o a.tif in.txt &&
	"$imgdump" -8 a.tif >dump &&
	sed 1,2d dump >values &&
	cat >expect <<-\EOF &&
	188 10 118
	255 0 0
	137 56 255
	EOF
	test_cmp_numbers expect values 0 &&
	reflect-export --depth=float -c spec -o f.tif in.txt &&
	"$imgdump" f.tif >dump &&
	sed 1,2d dump >values &&
	cat >expect <<-\EOF &&
	0.5 1 2
	0.125 0.25 0.75
	3 -2 0.1
	EOF
	test_cmp_numbers expect values 1e-7
'

test_expect_success 'jpeg: writes 3 channels of the right size' '
	reflect-export -o a.jpg in.txt &&
	"$imgdump" -8 a.jpg >dump &&
	sed -n 1p dump >size &&
	echo "3 1 3" >expect &&
	test_cmp_numbers expect size 0
'

test_expect_success 'a missing channel is named, exit 1' '
	test_expect_code 1 reflect-export -c spec,foo -o x.exr in.txt 2>err &&
	test_one_line_message reflect-export err &&
	test_grep "input has no channel .foo." err &&
	test_expect_code 1 reflect-export -c albedo -o x.exr in.txt 2>err &&
	test_one_line_message reflect-export err &&
	test_grep "no channel .albedo. (nor albedo.R albedo.G albedo.B or albedo.X albedo.Y albedo.Z)" err &&
	! test -e x.exr
'

test_expect_success 'no R G B and no spec: asks for -c' '
	cat >p.txt <<-\EOF &&
	#?REFLECT1
	NCOLS=1
	NROWS=1
	NCOMP=3
	CHANNELS=P.X P.Y P.Z
	FORMAT=ascii

	1	2	3
	EOF
	test_expect_code 1 reflect-export -o x.exr p.txt 2>err &&
	test_one_line_message reflect-export err &&
	test_grep "choose channels with -c" err &&
	reflect-export -c P -o p.exr p.txt &&
	"$imgdump" p.exr >dump &&
	test_grep "^P.X P.Y P.Z$" dump
'

test_expect_success 'an unknown extension is refused before reading' '
	test_expect_code 1 reflect-export -o a.xyz </dev/null 2>err &&
	test_one_line_message reflect-export err &&
	test_grep "^reflect-export: cannot write .a.xyz.: unknown image type" err &&
	test_expect_code 1 reflect-export -o noext in.txt 2>err &&
	test_grep "cannot write .noext.: unknown image type" err &&
	! test -e a.xyz
'

test_expect_success 'an unwritable path gives the system reason, exit 2' '
	test_expect_code 2 reflect-export -o no/such/dir/a.png in.txt 2>err &&
	test_one_line_message reflect-export err &&
	test_grep "^reflect-export: cannot write .no/such/dir/a.png.: No such file or directory$" err &&
	test_expect_code 2 reflect-export -o no/such/dir/a.exr in.txt 2>err &&
	test_grep "cannot write .no/such/dir/a.exr.: No such file or directory$" err
'

if test -c /dev/full
then
	test_expect_success 'a full disk is an error, exit 2' '
		ln -s /dev/full full.png &&
		test_expect_code 2 reflect-export -o full.png in.txt 2>err &&
		test_one_line_message reflect-export err &&
		test_grep "cannot write .full.png.: No space left on device$" err &&
		ln -s /dev/full full.jpg &&
		test_expect_code 2 reflect-export -o full.jpg in.txt 2>err &&
		test_one_line_message reflect-export err &&
		ln -s /dev/full full.exr &&
		test_expect_code 2 reflect-export -o full.exr in.txt 2>err &&
		test_one_line_message reflect-export err
	'
else
	test_skip 'a full disk is an error, exit 2' 'no /dev/full'
fi

test_expect_success 'channel counts and depths a format cannot take' '
	test_expect_code 1 reflect-export -c all -o x.png in.txt 2>err &&
	test_one_line_message reflect-export err &&
	test_grep "cannot write 8 channels to .x.png.: 8-bit .png files take 1, 3 or 4 channels" err &&
	test_expect_code 1 reflect-export -c R,G,B,A -o x.jpg in.txt 2>err &&
	test_grep "8-bit .jpg files take 1 or 3 channels" err &&
	test_expect_code 1 reflect-export --depth=16 -o x.jpg in.txt 2>err &&
	test_grep "a .jpg file does not store 16-bit pixels" err &&
	test_expect_code 1 reflect-export --depth=8 -o x.exr in.txt 2>err &&
	test_grep "a .exr file does not store 8-bit pixels" err &&
	test_expect_code 1 reflect-export -c R,G,B,A -o x.hdr in.txt 2>err &&
	test_grep ".hdr files take 3 channels" err &&
	! test -e x.png && ! test -e x.jpg && ! test -e x.exr && ! test -e x.hdr
'

test_expect_success 'one channel three times: grey in png, refused in exr' '
	reflect-export -c mask,mask,mask --srgb=off -o mask.png in.txt &&
	"$imgdump" -8 mask.png >dump &&
	sed 1,2d dump >values &&
	printf "255 255 255\n0 0 0\n255 255 255\n" >expect &&
	test_cmp_numbers expect values 0 &&
	test_expect_code 1 reflect-export -c mask,mask -o x.exr in.txt 2>err &&
	test_grep "channel .mask. is chosen twice" err
'

test_expect_success 'hdr: negative values become 0 (RGBE has no sign)' '
	reflect-export -c spec -o a.hdr in.txt &&
	"$imgdump" a.hdr >dump &&
	sed -n 5p dump >row &&
	# RGBE keeps 8 bits under the largest component: 0.1 next to 3 is
	# within 4/256 of it.
	echo "3 0 0.1" >expect &&
	test_cmp_numbers expect row 0.016
'

test_expect_success 'setup: a stream of two frames' '
	sed -e "/^[0-9]/s/[01]\$/0.5/" in.txt >in2.txt &&
	cat in.txt in2.txt >two.txt &&
	reflect-info two.txt >info &&
	test_grep "^frame 2:" info
'

test_expect_success 'several frames: %d numbers the files from 0' '
	reflect-export -c mask -o "m%d.exr" two.txt &&
	"$imgdump" m0.exr >dump0 && "$imgdump" m1.exr >dump1 &&
	printf "3 1 1\nmask\n1\n0\n1\n" >expect0 &&
	printf "3 1 1\nmask\n0.5\n0.5\n0.5\n" >expect1 &&
	test_cmp_numbers expect0 dump0 0 &&
	test_cmp_numbers expect1 dump1 0 &&
	! test -e m2.exr
'

test_expect_success 'several frames: %03d pads the number' '
	reflect-export -c mask --srgb=off -o "f%03d.png" two.txt &&
	test -f f000.png && test -f f001.png && ! test -e f002.png
'

test_expect_success 'a single frame with %d is numbered 0' '
	reflect-export -o "one%d.exr" in.txt &&
	test -f one0.exr
'

test_expect_success 'several frames without %d: error at the second, exit 1' '
	test_expect_code 1 reflect-export -c mask -o same.exr two.txt 2>err &&
	test_one_line_message reflect-export err &&
	test_grep "more than one frame: put %d in the output name" err &&
	test_expect_code 1 reflect-export -o "a%d%d.exr" in.txt 2>err &&
	test_grep "may hold one %d or %0Nd" err
'

# Headerless float data is in the host's byte order.
if test "$(printf '\001\000\000\000' | od -An -tu4 | tr -d ' ')" = 1
then
	raw='\000\000\300\077\000\000\000\300\000\000\200\076\000\000\000\101'
else
	raw='\077\300\000\000\300\000\000\000\076\200\000\000\101\000\000\000'
fi

test_expect_success 'headerless input: -c names the channels, all are written' '
	# 1.5 -2 | 0.25 8 as float32
	printf "$raw" >raw.bin &&
	reflect-export -H -x 2 -y 1 -c u,v -o raw.exr raw.bin &&
	"$imgdump" raw.exr >dump &&
	printf "2 1 2\nu v\n1.5 -2\n0.25 8\n" >expect &&
	test_cmp_numbers expect dump 0
'

test_expect_success 'bad input and bad options: one line, exit 1' '
	head -c 120 in.txt >short.txt &&
	test_expect_code 1 reflect-export -o t.exr short.txt 2>err &&
	test_one_line_message reflect-export err &&
	test_expect_code 1 reflect-export -e bright -o t.exr in.txt 2>err &&
	test_grep "^reflect-export: -e: .bright. is not an exposure" err &&
	test_expect_code 1 reflect-export --tone=aces -o t.exr in.txt 2>err &&
	test_grep "tone: .aces. is not none or filmic" err &&
	test_expect_code 1 reflect-export --depth=12 -o t.exr in.txt 2>err &&
	test_grep "depth: .12. is not 8, 16, half or float" err &&
	test_expect_code 1 reflect-export in.txt 2>err &&
	test_grep "^usage: reflect-export -o FILE" err
'

# "PIXEL NAME VALUE" a line, sorted: an image dump compared by channel
# name, whatever order the reader lists the channels in.
by_name () {
	awk 'NR == 2 { n = split($0, name) }
	NR > 2 { for (i = 1; i <= n; i++) print NR - 2, name[i], $i }' "$1" |
	sort -k1,1n -k2,2
}

test_expect_success 'png: 16-bit R G B, exposure and sRGB, values by hand' '
	# As the 8-bit test, x 65535: R 0.7354 1 0.5371 -> 48192 65535 35199
	# G 0.03876 0 0.2209 -> 2540 0 14478; B 0.4614 0 1 -> 30235 0 65535
	reflect-export -e 1 --depth=16 -o a16.png in.txt &&
	"$imgdump" -16 a16.png >dump &&
	cat >expect <<-\EOF &&
	3 1 3
	R G B
	48192 2540 30235
	65535 0 0
	35199 14478 65535
	EOF
	test_cmp_numbers expect dump 0
'

test_expect_success 'png: 16-bit R G B A, straight alpha, values by hand' '
	# /0.25: 0.5 0.2 1.2 -> sRGB 0.7354 0.4845 1 -> 48192 31754 65535;
	# A 0.25 x 65535 = 16383.75 -> 16384
	reflect-export --depth=16 -c R,G,B,A -o rgba16.png rgba.txt &&
	"$imgdump" -16 rgba16.png >dump &&
	cat >expect <<-\EOF &&
	1 1 4
	R G B A
	48192 31754 65535 16384
	EOF
	test_cmp_numbers expect dump 0
'

test_expect_success 'png: 8-bit grey, values by hand' '
	# spec.B 2 0.75 0.1 -> sRGB 1 0.8808 0.3492 -> 255 225 89
	reflect-export -c spec.B -o grey8.png in.txt &&
	"$imgdump" -8 grey8.png >dump &&
	sed 2d dump >values &&
	printf "3 1 1\n255\n225\n89\n" >expect &&
	test_cmp_numbers expect values 0
'

test_expect_success 'exr: every channel read back exactly by name, float and half' '
	# Float: the values as a float holds them.  Half: the nearest half
	# (0.0015 -> 0.0015001297, 0.1 -> 0.0999755859).
	reflect-export -c all -o exact.exr in.txt &&
	"$imgdump" exact.exr >dump &&
	by_name dump >got &&
	cat >want <<-\EOF &&
	3 1 8
	R G B A spec.R spec.G spec.B mask
	0.25 0.00150000001 0.0900000036 1 0.5 1 2 1
	0.600000024 -1 nan 1 0.125 0.25 0.75 0
	0.125 0.0199999996 4 1 3 -2 0.100000001 1
	EOF
	by_name want >expect &&
	test_cmp_numbers expect got 0 &&
	reflect-export -c all --half -o exacth.exr in.txt &&
	"$imgdump" exacth.exr >dump &&
	by_name dump >got &&
	cat >want <<-\EOF &&
	3 1 8
	R G B A spec.R spec.G spec.B mask
	0.25 0.0015001297 0.0900268555 1 0.5 1 2 1
	0.600097656 -1 nan 1 0.125 0.25 0.75 0
	0.125 0.0200042725 4 1 3 -2 0.0999755859 1
	EOF
	by_name want >expect &&
	test_cmp_numbers expect got 0
'

# 300 x 700 pixels of 8 channels: more rows than reflect-export reads in
# one block (4 MB: 436 rows), and not a whole number of OpenEXR chunks
# (16 rows) a block.  R G B are k/255 for an integer k; e0..e4 are
# multiples of 1/16 in [-64, 64), which a half holds exactly.  The values
# read back are printed as awk prints the expected ones: cmp compares.
test_expect_success 'setup: a 300x700 stream larger than one block' '
	awk "BEGIN {
		w = 300; h = 700
		print \"#?REFLECT1\"; print \"NCOLS=\" w; print \"NROWS=\" h
		print \"NCOMP=8\"; print \"CHANNELS=R G B e0 e1 e2 e3 e4\"
		print \"FORMAT=ascii\"; print \"\"
		for (y = 0; y < h; y++)
			for (x = 0; x < w; x++) {
				r = (x + 3 * y) % 256; g = (7 * x + y) % 256; b = (x * y) % 256
				e = \"\"
				for (c = 0; c < 5; c++)
					e = e sprintf(\" %.9g\", ((7 * x + 13 * y + 31 * c) % 2048) / 16 - 64)
				printf \"%.9g %.9g %.9g%s\n\", r / 255, g / 255, b / 255, e
				print r, g, b >\"big-rgb\"
				print r * 257, g * 257, b * 257 >\"big-rgb16\"
				print substr(e, 2) >\"big-e\"
			}
	}" >big.txt &&
	test_line_count 210007 big.txt &&
	test_line_count 210000 big-e
'

test_expect_success 'png: 300x700, 8 and 16 bits, read back exactly' '
	reflect-export --srgb=off -o big.png big.txt &&
	"$imgdump" -8 big.png >dump &&
	sed -n 1p dump >size && echo "300 700 3" >expect &&
	test_cmp_numbers expect size 0 &&
	sed 1,2d dump >values &&
	cmp big-rgb values &&
	reflect-export --srgb=off --depth=16 -o big16.png big.txt &&
	"$imgdump" -16 big16.png >dump &&
	sed 1,2d dump >values &&
	cmp big-rgb16 values
'

test_expect_success 'exr: 300x700, float and half, read back exactly' '
	reflect-export -c e0,e1,e2,e3,e4 -o big.exr big.txt &&
	"$imgdump" big.exr >dump &&
	printf "300 700 5\ne0 e1 e2 e3 e4\n" >expect &&
	sed 2q dump >head &&
	cmp expect head &&
	sed 1,2d dump >values &&
	cmp big-e values &&
	reflect-export -c e0,e1,e2,e3,e4 --half -o bigh.exr big.txt &&
	"$imgdump" bigh.exr >dump &&
	sed 1,2d dump >values &&
	cmp big-e values
'

# The dynamic loader lists every library it loads under LD_DEBUG=files
# (glibc); a TIFF, written through OpenImageIO, shows that it does.
if LD_DEBUG=files reflect-info -V 2>&1 >/dev/null | grep "file=libreflect" >/dev/null
then
	test_expect_success 'png and exr are written without loading OpenImageIO' '
		LD_DEBUG=files reflect-export -o ld.tif in.txt 2>ld &&
		test_grep "libOpenImageIO" ld &&
		for args in "ld.png in.txt" "ld16.png --depth=16 in.txt" "ld.exr in.txt" \
			"ldh.exr --half in.txt" "ldbig.png --srgb=off big.txt"
		do
			set -- $args &&
			out=$1 && shift &&
			LD_DEBUG=files reflect-export -o $out "$@" 2>ld &&
			test -s $out &&
			! grep -e libOpenImageIO -e reflect-oiio ld || return 1
		done
	'
else
	test_skip 'png and exr are written without loading OpenImageIO' 'no LD_DEBUG'
fi

test_expect_success 'png and exr: a path that cannot be written, one line, exit 2' '
	test_expect_code 2 reflect-export -o /nonexistent/x.png in.txt 2>err &&
	test_one_line_message reflect-export err &&
	test_grep "^reflect-export: cannot write ./nonexistent/x.png.: No such file or directory$" err &&
	test_expect_code 2 reflect-export --half -o /nonexistent/x.exr in.txt 2>err &&
	test_one_line_message reflect-export err &&
	test_grep "^reflect-export: cannot write ./nonexistent/x.exr.: No such file or directory$" err &&
	mkdir dir.png dir.exr &&
	test_expect_code 2 reflect-export -o dir.png in.txt 2>err &&
	test_one_line_message reflect-export err &&
	test_grep "^reflect-export: cannot write .dir.png.: Is a directory$" err &&
	test_expect_code 2 reflect-export -o dir.exr in.txt 2>err &&
	test_one_line_message reflect-export err &&
	test_grep "^reflect-export: cannot write .dir.exr.: Is a directory$" err
'

if test -c /dev/full
then
	test_expect_success 'png and exr on a full disk: exit 2, No space left on device' '
		ln -s /dev/full full16.png && ln -s /dev/full fullh.exr &&
		ln -s /dev/full fullbig.png && ln -s /dev/full fullbig.exr &&
		for args in "full.png in.txt" "full16.png --depth=16 in.txt" \
			"full.exr in.txt" "fullh.exr --half in.txt" \
			"fullbig.png --srgb=off big.txt" "fullbig.exr -c e0,e1 big.txt"
		do
			set -- $args &&
			out=$1 && shift &&
			test_expect_code 2 reflect-export -o $out "$@" 2>err &&
			test_one_line_message reflect-export err &&
			test_grep "^reflect-export: cannot write .$out.: No space left on device$" err ||
			return 1
		done
	'
else
	test_skip 'png and exr on a full disk: exit 2, No space left on device' 'no /dev/full'
fi

# The image is written beside its path and renamed over it once whole:
# input that ends early leaves the old file as it was, and no temporary
# file behind (one per type: libpng, OpenEXR's core, OpenImageIO).
test_expect_success 'a failed export leaves the existing file as it was' '
	head -c $(($(wc -c <big.txt) / 2)) big.txt >half.txt &&
	for ext in png exr tif
	do
		reflect-export -o keep.$ext -c e0,e1,e2 big.txt &&
		cp keep.$ext before.$ext &&
		test_expect_code 1 reflect-export -o keep.$ext -c e0,e1,e2 half.txt 2>err &&
		test_grep "data ends" err &&
		cmp before.$ext keep.$ext &&
		test -z "$(ls -A | grep "^\.keep")" || return 1
	done
'

test_expect_success 'a replaced file keeps its mode; a new one gets the umask' '
	reflect-export -o mode.png in.txt &&
	chmod 640 mode.png &&
	reflect-export -e 1 -o mode.png in.txt &&
	test "$(stat -c %a mode.png)" = 640 &&
	(umask 027 && reflect-export -o new.png in.txt) &&
	test "$(stat -c %a new.png)" = 640 &&
	(umask 022 && reflect-export -o new2.png in.txt) &&
	test "$(stat -c %a new2.png)" = 644
'

test_expect_success 'a symbolic link is written through, not replaced' '
	reflect-export -o target.png in.txt &&
	ln -s target.png link.png &&
	reflect-export -e 1 -o link.png in.txt &&
	test -h link.png &&
	reflect-export -e 1 -o want.png in.txt &&
	cmp want.png target.png
'

# TIFF's DateTime tag held the time of writing; it is now fixed (the
# epoch, or SOURCE_DATE_EPOCH), so the same pixels make the same bytes.
test_expect_success 'tiff: the same pixels make the same bytes' '
	reflect-export -o t1.tif in.txt &&
	sleep 1 &&
	reflect-export -o t2.tif in.txt &&
	cmp t1.tif t2.tif &&
	SOURCE_DATE_EPOCH=86400 reflect-export -o t3.tif in.txt &&
	grep -a "1970:01:02 00:00:00" t3.tif >/dev/null &&
	grep -a "1970:01:01 00:00:00" t1.tif >/dev/null
'

test_expect_success '-o - writes the PNG to standard output, exr:- the EXR' '
	reflect-export -e 1 -o file.png in.txt &&
	reflect-export -e 1 -o - in.txt >piped.png &&
	cmp file.png piped.png &&
	reflect-export -o file.exr in.txt &&
	reflect-export -o exr:- in.txt | cat >piped.exr &&
	cmp file.exr piped.exr &&
	cat in.txt in.txt >two.txt &&
	test_expect_code 1 reflect-export -o - two.txt >/dev/null 2>err &&
	test_grep "standard output takes one image" err
'

# An image file wherever a stream is read: read as reflect-import reads
# it, its channels under their own names.
test_expect_success 'image files are streams to the stream tools' '
	reflect-info file.exr >info &&
	test_grep "NCOLS=3$" info &&
	test_grep "CHANNELS=R G B$" info &&
	reflect-export -o again.exr file.exr &&
	"$imgdump" file.exr >a &&
	"$imgdump" again.exr >b &&
	cmp a b &&
	reflect-info -s file.png >info &&
	test_grep "CHANNELS=R G B$" info &&
	# its values are display values already: no second encoding
	reflect-export -c R,G,B --srgb=off -o back.png file.png &&
	"$imgdump" -8 file.png >a &&
	"$imgdump" -8 back.png >b &&
	cmp a b
'

test_done
