#!/bin/sh
test_description='--frames=A-B and --frame=K: the full run'"'"'s frames at those indices, pixel for pixel'
. "$srcdir/tests/lib.sh"

# frames FILE FIRST COUNT BYTES: COUNT frames of BYTES each from a
# headerless stream, starting at frame FIRST.
frames () {
	tail -c +$(($2 * $4 + 1)) "$1" | head -c $(($3 * $4))
}

# The FRAME and CAMERA keys of every frame of an ascii stream.
keys () {
	grep -E "^(FRAME|CAMERA)=" "$1"
}

# Bytes of a headerless frame: 24 x 16 G-buffer pixels of 20 floats,
# 16 x 8 traced ones of 5.
gbytes=$((24 * 16 * 20 * 4))
tbytes=$((16 * 8 * 5 * 4))

test_expect_success 'setup' '
	cat >s.scene <<-\EOF
	probe center 0 1.5 0 box -3 0 -2 3 3 2
	camera position 0 1.6 2 target 0 1 0 fov 50
	sphere center 0 1 0 radius 0.5 roughness 0.2
	EOF
'

test_expect_success 'gbuffer --frames=2-4 of an orbit: frames 2-4 of the whole run' '
	reflect-gbuffer -x 24 -y 16 -n 6 --orbit=90 -h s.scene >all &&
	test $(wc -c <all) -eq $((6 * gbytes)) &&
	reflect-gbuffer -x 24 -y 16 -n 6 --orbit=90 --frames=2-4 -h s.scene >part &&
	test $(wc -c <part) -eq $((3 * gbytes)) &&
	frames all 2 3 $gbytes >expect &&
	cmp expect part &&
	frames all 1 1 $gbytes >before &&
	! cmp -s before part
'

test_expect_success 'their headers: the whole run'"'"'s FRAME and CAMERA keys' '
	reflect-gbuffer -x 2 -y 2 -n 6 --orbit=90 -fa s.scene >all.txt &&
	reflect-gbuffer -x 2 -y 2 -n 6 --orbit=90 --frames=2-4 -fa s.scene >part.txt &&
	keys all.txt | sed -n 5,10p >expect &&
	keys part.txt >actual &&
	test_line_count 6 actual &&
	cmp expect actual &&
	grep -q "^FRAME=2$" actual
'

test_expect_success 'gbuffer --frame=K along a line path, the last and the first' '
	reflect-gbuffer -x 24 -y 16 -n 5 --path=line:1,1.6,3 -h s.scene >all &&
	reflect-gbuffer -x 24 -y 16 -n 5 --path=line:1,1.6,3 --frame=4 -h s.scene >last &&
	frames all 4 1 $gbytes >expect &&
	cmp expect last &&
	reflect-gbuffer -x 24 -y 16 -n 5 --path=line:1,1.6,3 --frame=0 -h s.scene >first &&
	frames all 0 1 $gbytes >expect &&
	cmp expect first
'

test_expect_success 'trace -n 4 --orbit: frame 0 is the single frame, --frames=1-2 the middle' '
	reflect-trace -x 16 -y 8 --samples=4 -h s.scene >one &&
	reflect-trace -x 16 -y 8 --samples=4 -n 4 --orbit=60 -h s.scene >all &&
	test $(wc -c <all) -eq $((4 * tbytes)) &&
	frames all 0 1 $tbytes >first &&
	cmp one first &&
	reflect-trace -x 16 -y 8 --samples=4 -n 4 --orbit=60 --frames=1-2 -h s.scene >part &&
	frames all 1 2 $tbytes >expect &&
	cmp expect part &&
	! cmp -s first part
'

test_expect_success 'trace frames carry the whole run'"'"'s keys' '
	reflect-trace -x 2 -y 2 --samples=1 -n 4 --orbit=60 -fa s.scene >all.txt &&
	reflect-trace -x 2 -y 2 --samples=1 -n 4 --orbit=60 --frame=3 -fa s.scene >part.txt &&
	keys all.txt | sed -n 7,8p >expect &&
	keys part.txt >actual &&
	cmp expect actual &&
	grep -q "^TRACE_SAMPLES=1$" part.txt
'

# The animated mode draws its rays from FRAME, so the frames of a range
# shade as the whole run'"'"'s do.
test_expect_success 'raytraced:animate=1 over a range: the whole run'"'"'s frames' '
	reflect-prefilter --size=16 -o room.rfl 2>/dev/null &&
	reflect-gbuffer -x 24 -y 16 -n 4 --orbit=30 s.scene | reflect-project |
	reflect-shade -h -m raytraced:samples=1:animate=1:pattern=white --env=room.rfl >all &&
	reflect-gbuffer -x 24 -y 16 -n 4 --orbit=30 --frames=2-3 s.scene | reflect-project |
	reflect-shade -h -m raytraced:samples=1:animate=1:pattern=white --env=room.rfl >part &&
	test $(wc -c <all) -eq $((2 * $(wc -c <part))) &&
	frames all 1 1 $(($(wc -c <part) / 2)) >before &&
	tail -c $(wc -c <part) all >expect &&
	cmp expect part &&
	! cmp -s before expect
'

test_expect_success 'ranges outside the run, backwards or malformed: refused' '
	for args in "-n 6 --frames=4-6" "--frame=1" "-n 3 --frames=2-1" "--frames=3" \
		"--frames=a-b" "--frames=1-" "--frame=-1" "--frames=0-1000000000"
	do
		test_expect_code 1 reflect-gbuffer -x 2 -y 2 $args s.scene >out 2>err &&
		test_one_line_message reflect-gbuffer err &&
		test ! -s out &&
		test_expect_code 1 reflect-trace -x 2 -y 2 $args s.scene >out 2>err &&
		test_one_line_message reflect-trace err &&
		test ! -s out || return 1
	done &&
	test_expect_code 1 reflect-gbuffer -x 2 -y 2 -n 6 --frames=4-6 s.scene 2>err >/dev/null &&
	test_grep "^reflect-gbuffer: --frames=4-6: past the full run.s last frame, 5 (-n 6 makes frames 0-5; give -n the full run.s count)$" err &&
	test_expect_code 1 reflect-trace -x 2 -y 2 -n 3 --frames=2-1 s.scene 2>err >/dev/null &&
	test_grep "^reflect-trace: --frames=2-1: the range runs backwards (A-B with A <= B)$" err
'

test_done
