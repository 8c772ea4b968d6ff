#!/bin/sh
test_description='a size past the limits of reflect-stream(5): refused before anything is written'
. "$srcdir/tests/lib.sh"

# reflect-gbuffer -x 100000 -y 100000 began writing 920 GB.  Every tool
# that makes a frame of a size it is given refuses more than 2^16 pixels
# a side or 2^28 pixels, naming the option and the limit, and writes
# nothing.

# refused TOOL ARGS...: status 1 within 20 s, one line naming the
# limit, nothing on standard output.
refused () {
	test_expect_code 1 timeout 20 "$@" >out 2>err </dev/null &&
	test_one_line_message "$1" err &&
	test_grep "limit of\|out of range \[1, 65536\]" err &&
	test ! -s out
}

test_expect_success 'reflect-gbuffer' '
	refused reflect-gbuffer -x 100000 -y 100000 &&
	test_grep "option -x: 100000 is out of range \[1, 65536\]" err &&
	refused reflect-gbuffer -x 65536 -y 65536 &&
	test_grep "^reflect-gbuffer: -x -y: a frame of 65536 x 65536 pixels is over the limit of 268435456 (2^28) pixels" err &&
	refused reflect-gbuffer -x 16384 -y 16384 --supersample=2 &&
	test_grep "^reflect-gbuffer: -x -y --supersample: a frame of 32768 x 32768 pixels" err &&
	reflect-gbuffer -x 65536 -y 1 -c mask | reflect-info >info &&
	test_grep "NCOLS=65536" info
'

test_expect_success 'reflect-trace' '
	refused reflect-trace -x 100000 -y 100000 &&
	test_grep "option -x: 100000 is out of range" err &&
	refused reflect-trace -x 20000 -y 20000 &&
	test_grep "^reflect-trace: -x -y: a frame of 20000 x 20000 pixels is over the limit of 268435456" err
'

test_expect_success 'reflect-capture -n' '
	refused reflect-capture -n 8192 &&
	test_grep "^reflect-capture: -n (a frame of N x 6N): a frame of 8192 x 49152 pixels is over the limit of 268435456" err &&
	refused reflect-capture -n 6689 -o big.exr &&
	test ! -e big.exr
'

test_expect_success 'reflect-prefilter --size' '
	refused reflect-prefilter --size=8192 -o big.ktx &&
	test_grep "^reflect-prefilter: --size (a frame of N x 6N): a frame of 8192 x 49152 pixels is over the limit" err &&
	test ! -e big.ktx
'

test_expect_success 'headerless input' '
	refused reflect-info -H -x 100000 -y 1 -c 1 &&
	test_grep "option -x: 100000 is out of range \[1, 65536\]" err &&
	refused reflect-export -o big.png -H -x 65536 -y 65536 -c 3 /dev/null &&
	test_grep "^reflect-export: -H -x -y: a frame of 65536 x 65536 pixels is over the limit" err &&
	test ! -e big.png
'

test_expect_success 'reflect-import: an image wider than a frame' '
	reflect-gbuffer -x 32768 -y 2 -c mask >wide1.rfl &&
	reflect-export -c mask -o wide1.exr wide1.rfl &&
	reflect-import wide1.exr | reflect-info >info &&
	test_grep "NCOLS=32768" info &&
	"$builddir/tests/imgdump" wide1.exr >/dev/null &&
	awk "BEGIN { printf \"P5\n70000 1\n255\n\"; for (i = 0; i < 70000; i++) printf \"%c\", 7 }" >wide.pgm &&
	refused reflect-import wide.pgm &&
	test_grep "^reflect-import: ${SQ:-}.*wide.pgm.*: a frame of 70000 x 1 pixels is over the limit of 65536 pixels a side" err
'

test_expect_success 'reflect-montage: a grid past the limit' '
	reflect-gbuffer -x 9000 -y 4 -c mask >cell.rfl &&
	refused reflect-montage --columns=8 -o m.png A=cell.rfl:mask B=cell.rfl:mask \
		C=cell.rfl:mask D=cell.rfl:mask E=cell.rfl:mask F=cell.rfl:mask \
		G=cell.rfl:mask H=cell.rfl:mask &&
	test_grep "^reflect-montage: the montage (fewer a row: --columns): a frame of .* over the limit of 65536 pixels a side" err &&
	test ! -e m.png &&
	reflect-montage --columns=4 -o m.png A=cell.rfl:mask B=cell.rfl:mask \
		C=cell.rfl:mask D=cell.rfl:mask &&
	test -s m.png
'

test_done
