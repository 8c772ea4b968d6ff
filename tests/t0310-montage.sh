#!/bin/sh
test_description='reflect-montage: a labelled grid of images and stream channels'
. "$srcdir/tests/lib.sh"

imgdump="$builddir/tests/imgdump"

# A 4x2 stream: R G B, a distance d from 0 to 7 along the pixels, and a
# normal (X Y Z) of -1, 0 or 1.
test_expect_success 'setup: a small stream with known values' '
	awk "BEGIN { print \"#?REFLECT1\"; print \"NCOLS=4\"; print \"NROWS=2\"
		print \"NCOMP=7\"; print \"CHANNELS=R G B d N.X N.Y N.Z\"; print \"FORMAT=ascii\"
		print \"\"
		for (i = 0; i < 8; i++) print 0.25, 0.5, 1, i, -1, 0, 1 }" >in.txt
'

# Two cells a row of 4x2, a rule of 2 pixels: 10 x 2.  The colour cell
# is what reflect-export writes (8-bit, sRGB); the vector cell maps
# -1 0 1 to 0 0.5 1 (128 in 8 bits: round(0.5 x 255)).
test_expect_success 'colour as reflect-export encodes it, vectors to 0..1' '
	reflect-montage --label-scale=1 -o m.png c=in.txt v=in.txt:N.X,N.Y,N.Z &&
	"$imgdump" -8 m.png >dump &&
	head -n 1 dump >size &&
	echo "10 2 3" >expect &&
	cmp expect size &&
	reflect-export -o e.png in.txt &&
	# the first row: the colour cell (lines 3 to 6), the rule, the vectors
	"$imgdump" -8 e.png | sed -n 3p >want &&
	sed -n 3p dump >got &&
	cmp want got &&
	sed -n 7p dump >rule &&
	echo "0 0 0" >expect &&
	cmp expect rule &&
	sed -n 9p dump >vec &&
	echo "0 128 255" >expect &&
	cmp expect vec
'

# False colour over the channel's range, 0 to 7: the first pixel is the
# ramp's start (0.05 0.03 0.25: 13 8 64), the last its end (0.98 0.95
# 0.35: 250 242 89); with range=0,14 the last is halfway (0.75 0.2 0.45).
test_expect_success 'a scalar in false colour over its range, or the one given' '
	reflect-montage --label-scale=1 -o f.png d=in.txt:d &&
	"$imgdump" -8 f.png | sed 1,2d >px &&
	sed -n 1p px >first && echo "13 8 64" >expect && cmp expect first &&
	sed -n 8p px >last && echo "250 242 89" >expect && cmp expect last &&
	reflect-montage --label-scale=1 -o r.png d=in.txt:d:range=0,14 &&
	"$imgdump" -8 r.png | sed 1,2d | sed -n 8p >half &&
	echo "191 51 115" >expect &&
	cmp expect half
'

test_expect_success 'a grid of rows, images and streams, a bar under false colour' '
	reflect-gbuffer -x 64 -y 36 | reflect-project >g.rfl &&
	reflect-export -c N -o n.exr g.rfl &&
	reflect-montage --columns=2 -o grid.png a=g.rfl:hit.dist b=n.exr:N.X,N.Y,N.Z \
		c=g.rfl:roughness &&
	"$imgdump" grid.png | head -n 1 >size &&
	echo "130 74 3" >expect &&
	cmp expect size
'

# A supersampled stream is drawn at its picture's size, resolved as
# reflect-export resolves it: the cell of the stream is the cell of
# the exported image.
test_expect_success 'a SUPERSAMPLE stream is drawn resolved' '
	reflect-gbuffer --supersample=2 -x 12 -y 8 | reflect-project |
		reflect-shade -m hdrp --final 2>/dev/null >ss.rfl &&
	reflect-export --depth=float -o ss.exr ss.rfl &&
	reflect-montage --label-scale=1 -o from-stream.png s=ss.rfl &&
	reflect-montage --label-scale=1 -o from-image.png s=ss.exr &&
	"$imgdump" -8 from-stream.png >got &&
	head -n 1 got >size &&
	echo "12 8 3" >expect &&
	cmp expect size &&
	"$imgdump" -8 from-image.png >want &&
	cmp want got
'

test_expect_success 'bad cells are refused with the fix' '
	test_expect_code 1 reflect-montage -o x.png nolabel 2>err &&
	test_grep "is not LABEL=FILE" err &&
	test_expect_code 1 reflect-montage -o x.png a=in.txt:nothere 2>err &&
	test_grep "has no channel .nothere." err &&
	test_expect_code 1 reflect-montage -o x.png a=in.txt:d:colour 2>err &&
	test_grep "a colour cell takes 3 channels, not 1" err &&
	test_expect_code 1 reflect-montage -o x.png a=in.txt:d:range=3,1 2>err &&
	test_grep "range=3,1 is empty" err &&
	test_expect_code 1 reflect-montage -o x.png a=missing.rfl 2>err &&
	test_grep "cannot open .missing.rfl." err
'

test_done
