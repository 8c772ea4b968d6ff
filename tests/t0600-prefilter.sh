#!/bin/sh
test_description='reflect-prefilter: inputs in every layout, chains out, bad input'
. "$srcdir/tests/lib.sh"

SQ="'"

# header values of the frames of an ascii chain, one line per frame
frame_keys () {
	awk -v key="$1" 'index($0, key "=") == 1 { sub(key "=", ""); print }' "$2"
}

# a constant-colour image: constant_image FILE W H R G B
constant_image () {
	awk -v w="$2" -v h="$3" -v r="$4" -v g="$5" -v b="$6" 'BEGIN {
		printf "#?REFLECT1\nNCOLS=%d\nNROWS=%d\nNCOMP=3\nCHANNELS=R G B\nFORMAT=ascii\n\n", w, h
		for (i = 0; i < w * h; i++) printf "%s\t%s\t%s\n", r, g, b
	}' | reflect-export -c all -o "$1"
}

# level 0 texels of an ascii chain (data lines of the first frame)
level0 () {
	awk 'BEGIN { f = 0 } /^#\?REFLECT1/ { f++; d = 0; next } f == 1 && d { print } f == 1 && /^$/ { d = 1 }' "$1"
}

test_expect_success 'default chain: levels, mapping and steps in the headers' '
	reflect-prefilter --size=16 -fa >chain.txt &&
	test "$(frame_keys LEVEL chain.txt | tr "\n" " ")" = "0 1 2 3 4 " &&
	test "$(frame_keys LEVELS chain.txt | sort -u)" = 5 &&
	test "$(frame_keys NCOLS chain.txt | tr "\n" " ")" = "16 8 4 2 1 " &&
	test "$(frame_keys MAPPING chain.txt | sort -u)" = unity &&
	test "$(frame_keys STEPS chain.txt | sort -u)" = 4 &&
	test "$(frame_keys SAMPLES chain.txt | sort -u)" = 64 &&
	test "$(frame_keys BASE chain.txt | sort -u)" = copied &&
	test "$(frame_keys PREFILTER chain.txt | sort -u)" = ggx
'

test_expect_success 'a 256 cube makes the 7 levels of Unity, 256 to 4' '
	reflect-prefilter -s 1 -fa -h >/dev/null &&
	reflect-prefilter -s 1 >big.rfl &&
	test "$(reflect-info big.rfl | grep -c "^frame")" = 7 &&
	reflect-info big.rfl | grep "NCOLS=4$"
'

test_expect_success '--min-size and --levels choose the chain' '
	reflect-prefilter --size=16 --min-size=4 -fa >min.txt &&
	test "$(frame_keys NCOLS min.txt | tr "\n" " ")" = "16 8 4 " &&
	test "$(frame_keys STEPS min.txt | sort -u)" = 2 &&
	reflect-prefilter --size=16 --levels=2 --steps=6 --mapping=linear -fa >lev.txt &&
	test "$(frame_keys NCOLS lev.txt | tr "\n" " ")" = "16 8 " &&
	test "$(frame_keys STEPS lev.txt | sort -u)" = 6 &&
	test "$(frame_keys MAPPING lev.txt | sort -u)" = linear
'

test_expect_success 'the same bytes with one thread and with two' '
	reflect-prefilter --size=16 -h -j 1 >j1.rfl &&
	reflect-prefilter --size=16 -h -j 2 >j2.rfl &&
	cmp j1.rfl j2.rfl
'

for layout in cube vcross hcross
do
	test_expect_success "a $layout image reads back texel for texel" '
		reflect-prefilter --size=16 --plain --levels=2 --dump=$layout 2>log &&
		test_grep "wrote .level0-$layout.exr." log &&
		reflect-prefilter --plain --levels=2 -fa level0-$layout.exr >back.txt &&
		reflect-prefilter --size=16 --plain --levels=2 -fa >orig.txt &&
		level0 back.txt >back0 && level0 orig.txt >orig0 &&
		test_line_count 1536 back0 &&
		test_cmp_numbers orig0 back0 0.02
	'
done

test_expect_success 'a lat-long image is recognised and resampled' '
	reflect-prefilter --size=16 --plain --levels=2 --dump=latlong 2>log &&
	reflect-prefilter -v --size=16 --plain --levels=2 -fa level0-latlong.exr >ll.txt 2>log &&
	test_grep "2 levels of 16..8 texels" log &&
	level0 ll.txt >ll0 &&
	test_line_count 1536 ll0
'

test_expect_success 'six face files by %d and by %s' '
	for f in 0 1 2 3 4 5
	do
		constant_image face$f.exr 4 4 $f 1 2 || return 1
	done &&
	reflect-prefilter --plain --levels=2 -fa "face%d.exr" >six.txt &&
	level0 six.txt | awk "{ print \$1 }" | uniq -c | awk "{ print \$1, \$2 }" >counts &&
	printf "16 0\n16 1\n16 2\n16 3\n16 4\n16 5\n" >expect &&
	test_cmp_numbers expect counts 0 &&
	i=0 &&
	for f in px nx py ny pz nz
	do
		cp face$i.exr side-$f.exr && i=$((i + 1)) || return 1
	done &&
	reflect-prefilter --plain --levels=2 -fa "side-%s.exr" >six2.txt &&
	level0 six2.txt >a && level0 six.txt >b && cmp a b
'

test_expect_success 'a MIP-mapped EXR cube round-trips and is recognised' '
	reflect-prefilter --size=16 --mapping=exact -o probe.exr &&
	reflect-prefilter -fa probe.exr >again.txt 2>log &&
	test_grep "already a prefiltered chain of 5 levels" log &&
	test "$(frame_keys MAPPING again.txt | sort -u)" = exact &&
	test "$(frame_keys NCOLS again.txt | tr "\n" " ")" = "16 8 4 2 1 " &&
	reflect-prefilter --size=16 --mapping=exact -fa >direct.txt &&
	level0 direct.txt >d0 && level0 again.txt >a0 &&
	test_cmp_numbers d0 a0 0.02
'

test_expect_success 'a MIP-mapped EXR chain is the same bytes run after run' '
	reflect-prefilter --size=16 -o first.exr &&
	sleep 1 &&
	reflect-prefilter --size=16 -o second.exr &&
	cmp first.exr second.exr &&
	SOURCE_DATE_EPOCH=86400 reflect-prefilter --size=16 -o dated.exr &&
	! cmp -s first.exr dated.exr
'

# A MIP-mapped file is written beside its path and renamed over it, as
# every image: what fails leaves the old file and no temporary one, and
# the messages name the path, not the temporary file.
test_expect_success 'a MIP-mapped chain replaces its file whole, or not at all' '
	mkdir mip &&
	echo keep >mip/old.tif &&
	test_expect_code 1 reflect-prefilter --size=16 -o mip/old.tif 2>err &&
	test_grep "cannot write .mip/old.tif.: this file type holds no MIP levels" err &&
	test "$(cat mip/old.tif)" = keep &&
	reflect-prefilter --size=16 -o mip/p.exr &&
	chmod 640 mip/p.exr &&
	reflect-prefilter --size=8 -o mip/p.exr &&
	test "$(stat -c %a mip/p.exr)" = 640 &&
	ls -a mip >names &&
	printf ".\n..\nold.tif\np.exr\n" >expect &&
	diff -u expect names
'

test_expect_success 'a chain as one file per level (--prefiltered, %d numbers levels)' '
	mkdir levels && (
		cd levels &&
		reflect-prefilter --size=16 --dump=hcross 2>/dev/null &&
		reflect-prefilter --size=16 -fa >../direct16.txt &&
		reflect-prefilter --prefiltered -fa "level%d-hcross.exr" >../files16.txt 2>../log
	) &&
	test_grep "already a prefiltered chain of 5 levels" log &&
	test "$(frame_keys NCOLS files16.txt | tr "\n" " ")" = "16 8 4 2 1 " &&
	sed -n "/^$/,\$p" direct16.txt | grep -v "^#\|=\|^$\|^reflect" >d &&
	sed -n "/^$/,\$p" files16.txt | grep -v "^#\|=\|^$\|^reflect" >f &&
	test_cmp_numbers d f 0.02 &&
	cp levels/level0-hcross.exr bad0.exr && cp levels/level2-hcross.exr bad1.exr &&
	test_expect_code 1 reflect-prefilter --prefiltered "bad%d.exr" 2>err &&
	test_grep "level 1 has faces of 4 texels, not half the 16 of level 0" err
'

test_expect_success 'a DDS cube with mips: a chain with --prefiltered, else raw' '
	"$builddir/tests/mkdds" cube.dds 8 3 &&
	reflect-prefilter --prefiltered -fa cube.dds >dds.txt 2>log &&
	test_grep "already a prefiltered chain of 3 levels" log &&
	test "$(frame_keys NCOLS dds.txt | tr "\n" " ")" = "8 4 2 " &&
	awk "/^#\?REFLECT1/ { k++ } NF == 3 && \$2 == 1 { print k - 1, \$1 }" dds.txt | sort -u >faces &&
	printf "0 0\n0 1\n0 2\n0 3\n0 4\n0 5\n1 10\n1 11\n1 12\n1 13\n1 14\n1 15\n2 20\n2 21\n2 22\n2 23\n2 24\n2 25\n" >expect &&
	test_cmp_numbers expect faces 0 &&
	reflect-prefilter -fa --levels=2 cube.dds >raw.txt &&
	test "$(frame_keys NCOLS raw.txt | tr "\n" " ")" = "8 4 " &&
	test "$(frame_keys PREFILTER raw.txt | sort -u)" = ggx
'

# A DDS header may claim any size, and a sparse file backs the claim with
# no disk at all: 4096-texel faces in a 1.6 GB file that holds 4 KB.  The
# cube it would need, 6 faces of (4096 + 2)^2 bordered RGB float texels,
# 1153.1 MB, is over the memory limit, so nothing is allocated; before,
# reflect-shade took 2.8 GB for such a file.
test_expect_success 'a sparse DDS is refused at the cube limit, before any allocation' '
	"$builddir/tests/mkdds" sparse.dds 8 1 &&
	printf "\000\020\000\000\000\020\000\000" |
	dd of=sparse.dds bs=1 seek=12 conv=notrunc 2>/dev/null &&
	truncate -s $((128 + 4096 * 4096 * 6 * 16)) sparse.dds &&
	test_expect_code 1 timeout 20 reflect-prefilter --prefiltered sparse.dds >/dev/null 2>err &&
	test_one_line_message reflect-prefilter err &&
	test_grep "${SQ}sparse.dds${SQ}: a cube of 4096-texel faces takes 1153.1 MB, over the limit of 1024 MB (REFLECT_MAX_CUBE_MB raises it)" err &&
	reflect-gbuffer -x 4 -y 4 | reflect-project >frame.rfl &&
	test_expect_code 1 timeout 20 reflect-shade --env=sparse.dds --prefiltered frame.rfl >/dev/null 2>err &&
	test_grep "over the limit of 1024 MB" err
'

# The embedded room's raw cube at 256: 6 x 258^2 x 12 bytes = 4.6 MB.
test_expect_success 'REFLECT_MAX_CUBE_MB sets the limit' '
	REFLECT_MAX_CUBE_MB=1 test_expect_code 1 reflect-prefilter --size=256 >/dev/null 2>err &&
	test_grep "a cube of 256-texel faces takes 4.6 MB, over the limit of 1 MB" err &&
	REFLECT_MAX_CUBE_MB=1 reflect-prefilter --size=64 >/dev/null
'

test_expect_success 'NaN and Inf texels are refused, or zeroed with --nonfinite=zero' '
	awk "BEGIN {
		printf \"#?REFLECT1\nNCOLS=2\nNROWS=12\nNCOMP=3\nCHANNELS=R G B\nFORMAT=ascii\n\n\"
		for (i = 0; i < 24; i++) printf \"%s\t1\t1\n\", (i == 5 ? \"nan\" : (i == 9 ? \"inf\" : \"0.5\"))
	}" >nan.txt &&
	reflect-export -c all -o nan.exr nan.txt &&
	for opt in "" -S --nonfinite=error
	do
		test_expect_code 1 reflect-prefilter $opt --plain --levels=2 nan.exr >/dev/null 2>err &&
		test_one_line_message reflect-prefilter err &&
		test_grep "^reflect-prefilter: ${SQ}nan.exr${SQ}: pixel (1, 2): R is nan (2 such values in all; --nonfinite=zero replaces them with 0)$" err || return 1
	done &&
	reflect-prefilter --nonfinite=zero --plain --levels=2 -fa nan.exr >out.txt 2>err &&
	test_grep "replaced 2 NaN, infinite or out-of-range texel values with 0" err &&
	level0 out.txt >data && test_line_count 24 data && ! grep -E "nan|inf" data &&
	test_expect_code 1 reflect-prefilter --nonfinite=maybe nan.exr 2>err &&
	test_grep "^reflect-prefilter: --nonfinite: ${SQ}maybe${SQ} is not error or zero$" err
'

# A stream was read as it was: its NaN went through the prefilter into
# every texel its lobes reached, and reflect-shade wrote NaN with exit 0
# (-S did not apply to it).  Face +Y, texel (3, 5) is NaN here; in the
# chain, texel (1, 0) of level 2 of face -Z is inf.
test_expect_success 'a stream environment with a NaN or Inf texel is refused, or repaired' '
	awk "BEGIN {
		printf \"#?REFLECT1\nNCOLS=8\nNROWS=48\nNCOMP=3\nCHANNELS=R G B\nENVMAP=CUBE\nFORMAT=ascii\n\n\"
		for (i = 0; i < 8 * 48; i++) printf \"%s\t1\t1\n\", (i == (2 * 8 + 5) * 8 + 3 ? \"nan\" : \"0.5\")
	}" >raw-nan.txt &&
	reflect-gbuffer -x 16 -y 9 | reflect-project >g.rfl &&
	for opt in "" -S
	do
		test_expect_code 1 reflect-prefilter $opt -s 4 raw-nan.txt >/dev/null 2>err &&
		test_one_line_message reflect-prefilter err &&
		test_grep "^reflect-prefilter: ${SQ}raw-nan.txt${SQ}: level 0, face +Y, texel (3, 5): R is nan (1 such value in all; --nonfinite=zero replaces them with 0)$" err || return 1
	done &&
	test_expect_code 1 reflect-shade -m hdrp --final --env=raw-nan.txt g.rfl >out.rfl 2>err &&
	test_grep "^reflect-shade: ${SQ}raw-nan.txt${SQ}: level 0, face +Y, texel (3, 5): R is nan" err &&
	sed "s/^PROBE_ENV=default$/PROBE_ENV=raw-nan.txt/" g.rfl >named.rfl &&
	test_expect_code 1 reflect-shade -m hdrp --final named.rfl >out.rfl 2>err &&
	test_grep "texel (3, 5): R is nan" err &&
	reflect-shade -m hdrp --final --nonfinite=zero --env=raw-nan.txt g.rfl >out.rfl 2>err &&
	test_grep "^reflect-shade: ${SQ}raw-nan.txt${SQ}: replaced 1 NaN, infinite or out-of-range texel values with 0$" err &&
	reflect-info -s out.rfl >stats &&
	awk "\$1 ~ /^(spec\.[RGB]|R|G|B)\$/ { n++; if (\$5 != 0 || \$6 != 0) bad = 1 }
		END { exit bad || n != 6 }" stats &&
	# a chain: level 2 of face -Z, its texel (1, 0)
	reflect-prefilter --size=8 -s 4 -fa >chain.txt &&
	awk "BEGIN { l = -1 } /^#\?REFLECT1/ { l++; d = 0 } d && l == 2 { if (++k == (5 * 2 + 0) * 2 + 1 + 1) \$2 = \"inf\" }
		{ print } /^\$/ { d = 1 }" chain.txt >chain-inf.txt &&
	test_expect_code 1 reflect-shade -m hdrp --env=chain-inf.txt g.rfl >out.rfl 2>err &&
	test_grep "${SQ}chain-inf.txt${SQ}: level 2, face -Z, texel (1, 0): G is inf" err &&
	# finite, but the sums of a few such texels are not: 3e38 in the
	# raw cube made inf in the chain prefiltered from it
	sed "s/^nan	/3e38	/" raw-nan.txt >raw-big.txt &&
	test_expect_code 1 reflect-shade -m hdrp --env=raw-big.txt g.rfl >out.rfl 2>err &&
	test_grep "${SQ}raw-big.txt${SQ}: level 0, face +Y, texel (3, 5): R is 3e+38, past a quarter of the float range (1 such value in all; --nonfinite=zero replaces them with 0)" err
'

# DDS, KTX and EXR readers made such values 0 with only a warning.
test_expect_success 'a DDS with a NaN texel is refused, naming its face and texel' '
	"$builddir/tests/mkdds" nan.dds 4 2 &&
	printf "\000\000\300\177" | dd of=nan.dds bs=1 seek=$((128 + 16 * (4 * 1 + 2))) conv=notrunc 2>/dev/null &&
	test_expect_code 1 reflect-prefilter --prefiltered nan.dds >/dev/null 2>err &&
	test_grep "^reflect-prefilter: ${SQ}nan.dds${SQ}: level 0, face +X, texel (2, 1): R is nan" err &&
	reflect-prefilter --prefiltered --nonfinite=zero -fa nan.dds >out.txt 2>err &&
	test_grep "replaced 1 NaN, infinite or out-of-range texel values with 0" err
'

test_expect_success 'bad input: each a one-line message and exit 1' '
	test_expect_code 1 reflect-prefilter nope.exr 2>err &&
	test_grep "^reflect-prefilter: cannot open .nope.exr.: No such file or directory$" err &&
	test_expect_code 1 reflect-prefilter --layout=cube level0-latlong.exr 2>err &&
	test_one_line_message reflect-prefilter err &&
	test_grep "a cube image of faces N is N x 6N, not 64x32" err &&
	test_expect_code 1 reflect-prefilter --layout=strip x.exr 2>err &&
	test_grep "is not auto, latlong, cube, vcross, hcross, mirrorball or angular" err &&
	constant_image odd.exr 3 18 1 1 1 &&
	test_expect_code 1 reflect-prefilter odd.exr 2>err &&
	test_grep "odd size" err &&
	constant_image skew.exr 100 37 1 1 1 &&
	test_expect_code 1 reflect-prefilter skew.exr 2>err &&
	test_grep "cannot tell the layout of a 100x37 image" err &&
	constant_image big5.exr 8 8 1 1 1 &&
	cp face0.exr f-0.exr && cp face1.exr f-1.exr && cp face2.exr f-2.exr &&
	cp face3.exr f-3.exr && cp face4.exr f-4.exr && cp big5.exr f-5.exr &&
	test_expect_code 1 reflect-prefilter "f-%d.exr" 2>err &&
	test_grep "faces differ in size (8, not 4" err &&
	test_expect_code 1 reflect-prefilter -s 0 2>err &&
	test_grep "option -s: 0 is out of range" err &&
	test_expect_code 1 reflect-prefilter --levels=1 2>err &&
	test_expect_code 1 reflect-prefilter --steps=0 2>err &&
	test_grep "steps" err &&
	test_expect_code 1 reflect-prefilter --size=1 2>err &&
	test_grep "a chain of one level has nothing to convolve" err &&
	printf "not an image at all\n" >junk.exr &&
	test_expect_code 1 reflect-prefilter junk.exr 2>err &&
	test_one_line_message reflect-prefilter err &&
	test_grep "junk.exr" err
'

test_expect_success 'a stream cube on stdin is an environment' '
	reflect-prefilter --size=8 --plain --levels=2 >plain.rfl &&
	reflect-prefilter -fa - <plain.rfl >from-stdin.txt 2>log &&
	test_grep "already a plain chain of 2 levels" log &&
	test "$(frame_keys NCOLS from-stdin.txt | tr "\n" " ")" = "8 4 "
'

# Under a sky of one radiance E(n) = pi L: the cube holds L everywhere,
# to the discretisation of 32 texels a face.
test_expect_success '--irradiance: a 32-texel cube of E / pi, L under a uniform sky' '
	awk "BEGIN { printf \"#?REFLECT1\\nENVMAP=CUBE\\nLEVEL=0\\nLEVELS=1\\nPREFILTER=box\\n\"
		printf \"NCOLS=16\\nNROWS=96\\nNCOMP=3\\nCHANNELS=R G B\\nFORMAT=ascii\\n\\n\"
		for (j = 0; j < 6 * 16 * 16; j++) print 0.75, 0.5, 2 }" >flat.rfl &&
	reflect-prefilter --levels=2 --irradiance=irr.rfl -o chain.rfl flat.rfl 2>/dev/null &&
	reflect-info irr.rfl >info &&
	test_grep "^	NCOLS=32$" info && test_grep "^	NROWS=192$" info &&
	test_grep "^	LEVELS=1$" info &&
	reflect-info -s irr.rfl | awk "
		\$1 == \"R\" && (\$2 < 0.747 || \$3 > 0.753) { bad++ }
		\$1 == \"G\" && (\$2 < 0.498 || \$3 > 0.502) { bad++ }
		\$1 == \"B\" && (\$2 < 1.992 || \$3 > 2.008) { bad++ }
		END { exit bad > 0 }" &&
	reflect-prefilter --size=32 --levels=2 --irradiance=irr.exr -o /dev/null 2>/dev/null &&
	test -s irr.exr
'

test_done
