#!/bin/sh
test_description='KTX 1 and KTX 2 cube chains: read as other tools write them, written by reflect-prefilter, refused by name'
. "$srcdir/tests/lib.sh"

SQ="'"
mkktx="$builddir/tests/mkktx"
HINT1="is not supported; convert with ktx extract/toktx to an uncompressed format"
HINT2="is not supported; convert with ktx extract/toktx to an uncompressed or zstd format"

# header values of the frames of an ascii chain, one line per frame
frame_keys () {
	awk -v key="$1" 'index($0, key "=") == 1 { sub(key "=", ""); print }' "$2"
}

# the data lines of every frame of an ascii stream
data () {
	awk '/^#\?REFLECT1/ { d = 0; next } d { print; next } /^$/ { d = 1 }' "$1"
}

# level and red value of every texel whose green is 1: mkktx's labels
labels () {
	awk '/^#\?REFLECT1/ { k++ } NF == 3 && $2 == 1 { print k - 1, $1 }' "$1" | sort -u
}

# refused FILE TOOL...: exit 1 and one line on stderr, in err
refused () {
	test_expect_code 1 "$@" >out 2>err &&
	test ! -s out &&
	test_one_line_message "$1" err
}

test_expect_success 'set up: a chain as a stream and a frame to shade' '
	reflect-prefilter --size=16 -s 4 -fa >chain.txt &&
	reflect-prefilter --size=16 -s 4 -o chain.rfl &&
	reflect-gbuffer -x 8 -y 6 | reflect-project >frame.rfl
'

test_expect_success 'reflect-prefilter -o x.ktx / x.ktx2: the version by the suffix' '
	reflect-prefilter --size=16 -s 4 -o c.ktx &&
	reflect-prefilter --size=16 -s 4 -o c.ktx2 &&
	reflect-prefilter --size=16 -s 4 --ktx-texel=float -o f.ktx &&
	reflect-prefilter --size=16 -s 4 --ktx-texel=float -o f.ktx2 &&
	printf "\253KTX 11\273\r\n\032\n" >expect &&
	head -c 12 c.ktx >got && cmp expect got &&
	printf "\253KTX 20\273\r\n\032\n" >expect &&
	head -c 12 c.ktx2 >got && cmp expect got
'

test_expect_success 'a float KTX reads back as the stream chain, texel for texel, keys and all' '
	for f in f.ktx f.ktx2
	do
		reflect-prefilter -fa $f >back.txt 2>log &&
		test_grep "already a prefiltered chain of 5 levels" log &&
		data chain.txt >a && data back.txt >b && cmp a b &&
		for key in LEVEL NCOLS MAPPING STEPS SAMPLES PREFILTER BASE IRRADIANCE_SH9
		do
			test "$(frame_keys $key chain.txt)" = "$(frame_keys $key back.txt)" ||
			return 1
		done || return 1
	done
'

# The room's brightest texels are near 18, where half floats step by
# 2^-6: a rounding moves a value by 0.008 at most.
test_expect_success 'half KTX 1 and KTX 2 read back alike, within half-float rounding' '
	reflect-prefilter -fa c.ktx >h1.txt 2>/dev/null &&
	reflect-prefilter -fa c.ktx2 >h2.txt 2>/dev/null &&
	data h1.txt >a && data h2.txt >b && cmp a b &&
	data chain.txt >a && test_cmp_numbers a b 0.008
'

test_expect_success 'reflect-shade --env=x.ktx --prefiltered: the stream chain'"'"'s pixels' '
	reflect-shade -h -f a --env=chain.rfl frame.rfl >want &&
	reflect-shade -h -f a --env=f.ktx2 --prefiltered frame.rfl >got &&
	cmp want got &&
	reflect-shade -h -f a --env=f.ktx frame.rfl >got &&
	cmp want got &&
	reflect-shade -h -f a --env=c.ktx2 --prefiltered frame.rfl >got &&
	test_cmp_numbers want got 0.01 &&
	reflect-shade -h -f a --final --env=chain.rfl frame.rfl >want &&
	reflect-shade -h -f a --final --env=f.ktx2 frame.rfl >got &&
	cmp want got
'

test_expect_success '--irradiance=x.ktx2: the diffuse light as a KTX cube too' '
	reflect-prefilter --size=16 -s 4 --irradiance=irr.ktx2 -o /dev/null &&
	printf "\253KTX 20\273\r\n\032\n" >expect &&
	head -c 12 irr.ktx2 >got && cmp expect got &&
	reflect-prefilter --prefiltered -fa irr.ktx2 >irr.txt 2>/dev/null &&
	test "$(frame_keys NCOLS irr.txt)" = 32
'

test_expect_success 'a float KTX chain written again is the same file' '
	reflect-prefilter --ktx-texel=float f.ktx2 -o again.ktx2 2>/dev/null &&
	cmp f.ktx2 again.ktx2 &&
	reflect-prefilter --ktx-texel=float f.ktx -o again.ktx 2>/dev/null &&
	cmp f.ktx again.ktx
'

if "$mkktx" probe.ktx2 ktx2-zstd 4 1
then
	test_expect_success '--zstd: Zstandard levels, the same texels as plain ones' '
		reflect-prefilter --size=16 -s 4 --zstd=19 -o z.ktx2 &&
		reflect-prefilter --size=16 -s 4 --zstd -o z3.ktx2 &&
		test $(wc -c <z.ktx2) -lt $(wc -c <c.ktx2) &&
		reflect-prefilter -fa z.ktx2 >z.txt 2>/dev/null &&
		reflect-prefilter -fa z3.ktx2 >z3.txt 2>/dev/null &&
		data z.txt >a && data z3.txt >b && cmp a b &&
		data h2.txt >b && cmp a b &&
		reflect-prefilter --size=16 -s 4 --zstd -o z.ktx2 --irradiance=irr.ktx &&
		printf "\253KTX 11\273\r\n\032\n" >expect &&
		head -c 12 irr.ktx >got && cmp expect got &&
		refused reflect-prefilter --size=16 --zstd -o z.ktx &&
		test_grep "^reflect-prefilter: --zstd: no KTX 2 file to write (-o or --irradiance ending in .ktx2)$" err &&
		test ! -e z.ktx
	'

	test_expect_success 'a hand-made Zstandard KTX 2 is read' '
		"$mkktx" hz.ktx2 ktx2-zstd 8 3 &&
		reflect-prefilter --prefiltered -fa hz.ktx2 >hz.txt 2>/dev/null &&
		labels hz.txt >faces &&
		printf "0 0\n0 1\n0 2\n0 3\n0 4\n0 5\n1 10\n1 11\n1 12\n1 13\n1 14\n1 15\n2 20\n2 21\n2 22\n2 23\n2 24\n2 25\n" >expect &&
		test_cmp_numbers expect faces 0
	'
else
	test_expect_success 'without libzstd, --zstd and Zstandard files are refused naming it' '
		refused reflect-prefilter --size=16 --zstd -o z.ktx2 &&
		test_grep "needs libzstd, which this reflect was built without" err
	'
fi

# cmgen's R11F_G11F_B10F KTX 1, glTF-IBL-Sampler's RGBA16F KTX 2, and the
# rest: face f at level k holds (f + 10 k, 1, 2), exactly in each.
for kind in ktx1-rgba32f ktx1-rgba16f ktx1-rgb9e5 ktx1-r11g11b10 \
	ktx2-rgba32f ktx2-rgba16f ktx2-rgb9e5 ktx2-b10g11r11
do
	case $kind in
	ktx1-*) f=cube.ktx ;;
	*) f=cube.ktx2 ;;
	esac
	test_expect_success "a hand-made $kind cube: a chain with --prefiltered, else raw" '
		"$mkktx" '$f' '$kind' 8 3 &&
		reflect-prefilter --prefiltered -fa '$f' >k.txt 2>log &&
		test_grep "already a prefiltered chain of 3 levels" log &&
		test "$(frame_keys NCOLS k.txt | tr "\n" " ")" = "8 4 2 " &&
		labels k.txt >faces &&
		printf "0 0\n0 1\n0 2\n0 3\n0 4\n0 5\n1 10\n1 11\n1 12\n1 13\n1 14\n1 15\n2 20\n2 21\n2 22\n2 23\n2 24\n2 25\n" >expect &&
		test_cmp_numbers expect faces 0 &&
		reflect-prefilter -fa --levels=2 -s 1 '$f' >raw.txt 2>log &&
		! grep already log &&
		test "$(frame_keys NCOLS raw.txt | tr "\n" " ")" = "8 4 " &&
		test "$(frame_keys PREFILTER raw.txt | sort -u)" = ggx
	'
done

test_expect_success 'unsupported kinds are refused, naming the file, the format and the fix' '
	while read kind ext message
	do
		"$mkktx" bad.$ext $kind 4 1 &&
		refused reflect-prefilter --prefiltered bad.$ext &&
		test_grep "^reflect-prefilter: ${SQ}bad.$ext${SQ}: $message" err &&
		refused reflect-shade --env=bad.$ext --prefiltered frame.rfl &&
		test_grep "^reflect-shade: ${SQ}bad.$ext${SQ}: $message" err || return 1
	done <<-EOF
	ktx1-bc6h ktx glInternalFormat 0x8e8f (BC6H, block-compressed) $HINT1
	ktx1-etc1 ktx glInternalFormat 0x8d64 (ETC1, block-compressed) $HINT1
	ktx2-bc6h ktx2 vkFormat 143 (BC6H, block-compressed) $HINT2
	ktx2-bc7 ktx2 vkFormat 145 (BC7, block-compressed) $HINT2
	ktx2-astc ktx2 vkFormat 157 (ASTC, block-compressed) $HINT2
	ktx2-etc2 ktx2 vkFormat 147 (ETC2, block-compressed) $HINT2
	ktx2-basislz ktx2 BasisLZ supercompression $HINT2
	ktx2-uastc ktx2 Basis Universal UASTC $HINT2
	ktx2-zlib ktx2 ZLIB supercompression $HINT2
	ktx2-array ktx2 an array of 2 cubes; reflect reads one cube
	ktx2-3d ktx2 not a cube map (a 3D texture)
	ktx2-2d ktx2 not a cube map (a 2D texture)
	EOF
'

# ktx1-rgba16f of 4 texels, 3 levels: 64 bytes of header, then per
# level an imageSize and six faces of 128, 32 and 8 bytes (1084 in all).
# ktx2-rgba16f: 80 bytes of header, 3 index entries and a DFD of 28, then
# the levels smallest first, 8-byte aligned: level 0 from 424 to 1192.
test_expect_success 'truncated files are refused at every length, saying what is missing' '
	"$mkktx" whole.ktx ktx1-rgba16f 4 3 &&
	test $(wc -c <whole.ktx) -eq 1084 &&
	while read length message
	do
		head -c $length whole.ktx >cut.ktx &&
		refused reflect-prefilter --prefiltered cut.ktx &&
		test_grep "${SQ}cut.ktx${SQ}: $message" err || return 1
	done <<-EOF &&
	0 not a KTX file (no KTX 11 or KTX 20 identifier)
	11 not a KTX file (no KTX 11 or KTX 20 identifier)
	40 truncated: the KTX header needs 24 more bytes
	66 truncated: level 0${SQ}s imageSize needs 2 more bytes
	500 truncated: level 0 of face -Y needs 80 more bytes
	850 truncated: level 1 of face +X needs 22 more bytes
	1083 truncated: level 2 of face -Z needs 1 more bytes
	EOF
	"$mkktx" whole.ktx2 ktx2-rgba16f 4 3 &&
	test $(wc -c <whole.ktx2) -eq 1192 &&
	while read length message
	do
		head -c $length whole.ktx2 >cut.ktx2 &&
		refused reflect-prefilter --prefiltered cut.ktx2 &&
		test_grep "${SQ}cut.ktx2${SQ}: $message" err || return 1
	done <<-EOF
	79 truncated: the KTX 2 header needs 1 more bytes
	100 truncated: the level index needs 52 more bytes
	1000 truncated: level 0 needs 192 more bytes
	EOF
'

# A header may claim any size, and a sparse file backs the claim with no
# disk: 4096-texel faces in a 1.6 GB file that holds 2 KB, whose cube is
# over the memory limit; 16384-texel faces whose level holds 1536 bytes;
# offsets near 2^63.  Each is refused before anything is allocated.
test_expect_success 'absurd sizes are refused before any allocation' '
	"$mkktx" sparse.ktx2 ktx2-rgba32f 4 1 &&
	printf "\000\020\000\000\000\020\000\000" |
	dd of=sparse.ktx2 bs=1 seek=20 conv=notrunc 2>/dev/null &&
	printf "\000\000\000\140\000\000\000\000\000\000\000\140" |
	dd of=sparse.ktx2 bs=1 seek=88 conv=notrunc 2>/dev/null &&
	truncate -s $((144 + 6 * 4096 * 4096 * 16)) sparse.ktx2 &&
	test_expect_code 1 timeout 20 reflect-prefilter --prefiltered sparse.ktx2 >/dev/null 2>err &&
	test_one_line_message reflect-prefilter err &&
	test_grep "${SQ}sparse.ktx2${SQ}: a cube of 4096-texel faces takes 1153.1 MB, over the limit of 1024 MB" err &&
	"$mkktx" huge.ktx2 ktx2-rgba32f 4 1 &&
	printf "\000\100\000\000\000\100\000\000" |
	dd of=huge.ktx2 bs=1 seek=20 conv=notrunc 2>/dev/null &&
	printf "\017" | dd of=huge.ktx2 bs=1 seek=40 conv=notrunc 2>/dev/null &&
	refused reflect-prefilter --prefiltered huge.ktx2 &&
	test_grep "${SQ}huge.ktx2${SQ}: level 0 holds 1536 bytes; six faces of 268435456 R32G32B32A32_SFLOAT texels take 25769803776" err &&
	"$mkktx" far.ktx2 ktx2-rgba32f 4 1 &&
	printf "\377\377\377\377\377\377\377\177" |
	dd of=far.ktx2 bs=1 seek=80 conv=notrunc 2>/dev/null &&
	refused reflect-prefilter --prefiltered far.ktx2 &&
	test_grep "${SQ}far.ktx2${SQ}: truncated: level 0 needs" err &&
	"$mkktx" wide.ktx ktx1-rgba32f 4 1 &&
	printf "\000\000\001\000" | dd of=wide.ktx bs=1 seek=36 conv=notrunc 2>/dev/null &&
	printf "\000\000\001\000" | dd of=wide.ktx bs=1 seek=40 conv=notrunc 2>/dev/null &&
	refused reflect-prefilter --prefiltered wide.ktx &&
	test_grep "${SQ}wide.ktx${SQ}: cube faces of 65536 texels (1 to 16384 are read)" err &&
	printf "\000\000\000\000" | dd of=wide.ktx bs=1 seek=40 conv=notrunc 2>/dev/null &&
	refused reflect-prefilter --prefiltered wide.ktx &&
	test_grep "${SQ}wide.ktx${SQ}: cube faces of 65536x0 are not square" err
'

test_expect_success '--ktx-texel takes half or float' '
	refused reflect-prefilter --ktx-texel=double -o x.ktx &&
	test_grep "ktx-texel: ${SQ}double${SQ} is not half or float" err &&
	test ! -e x.ktx
'

test_expect_success 'a failed write leaves the old file as it was' '
	cp c.ktx2 keep.ktx2 &&
	mkdir ro && cp c.ktx2 ro/x.ktx2 && chmod a-w ro &&
	if test "$(id -u)" -ne 0
	then
		test_expect_code 2 reflect-prefilter --size=8 -o ro/x.ktx2 2>err &&
		test_grep "cannot write ${SQ}ro/x.ktx2${SQ}" err
	fi &&
	chmod u+w ro &&
	cmp keep.ktx2 ro/x.ktx2 &&
	test_expect_code 2 reflect-prefilter --size=8 -o /dev/full/x.ktx2 2>err &&
	test_grep "cannot write ${SQ}/dev/full/x.ktx2${SQ}" err
'

test_done
