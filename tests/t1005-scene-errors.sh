#!/bin/sh
test_description='bad scene files: each error names file:line:column and what was expected'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"

test_expect_success 'unknown keyword' '
	bad_scene "3:1: unknown keyword .spehre. (expected name, camera, probe, room, sphere, box, rect, mesh, sky, pattern, wall or window)$" <<-\EOF
	probe box -3 0 -2 3 3 2
	# a typo follows
	spehre center 0 1 0 radius 1
	EOF
'

test_expect_success 'unknown attribute' '
	bad_scene "2:24: unknown sphere attribute .radus. (expected center, radius or a material" <<-\EOF
	probe box -3 0 -2 3 3 2
	sphere center 0 1 0    radus 1
	EOF
'

test_expect_success 'missing value' '
	bad_scene "2:27: expected a number for .radius., found the end of the line$" <<-\EOF
	probe box -3 0 -2 3 3 2
	sphere center 0 1 0 radius
	EOF
'

test_expect_success 'missing value before the next attribute' '
	bad_scene "2:19: expected a number for .center., found .radius.$" <<-\EOF
	probe box -3 0 -2 3 3 2
	sphere center 0 1 radius 1
	EOF
'

test_expect_success 'non-numeric value' '
	bad_scene "1:21: expected a number for .box., found .three.$" <<-\EOF
	probe box -3 0 -2 3 three 2
	EOF
'

test_expect_success 'not a finite number' '
	bad_scene "2:15: expected a number for .center., found .nan.$" <<-\EOF
	probe box -3 0 -2 3 3 2
	sphere center nan 1 0 radius 1
	EOF
'

test_expect_success 'negative radius' '
	bad_scene "2:28: expected a positive radius, found -0.5$" <<-\EOF
	probe box -3 0 -2 3 3 2
	sphere center 0 1 0 radius -0.5
	EOF
'

test_expect_success 'empty box' '
	bad_scene "2:5: expected min < max on every axis, the box is empty on Y (min 2, max 2)$" <<-\EOF
	probe box -3 0 -2 3 3 2
	box min 0 2 0 max 1 2 1
	EOF
'

test_expect_success 'empty probe box' '
	bad_scene "1:7: expected min < max on every axis, the box is empty on X (min 3, max -3)$" <<-\EOF
	probe box 3 0 -2 -3 3 2
	EOF
'

test_expect_success 'probe outside its own box' '
	bad_scene "1:7: expected the probe.s centre inside its box, (0 1.5 5) is outside on Z \[-2, 2\]$" <<-\EOF
	probe center 0 1.5 5 box -3 0 -2 3 3 2
	EOF
'

test_expect_success 'no probe at all' '
	bad_scene "3:1: expected a .probe. line" <<-\EOF
	# only a sphere
	sphere center 0 1 0 radius 1
	EOF
'

test_expect_success 'value out of range' '
	bad_scene "2:39: expected .metallic. in \[0, 1\], found 1.5$" <<-\EOF
	probe box -3 0 -2 3 3 2
	sphere center 0 1 0 radius 1 metallic 1.5
	EOF
'

test_expect_success 'degenerate camera' '
	bad_scene "2:1: camera: expected an up vector not parallel to the view direction$" <<-\EOF
	probe box -3 0 -2 3 3 2
	camera position 0 1 0 target 0 0 0 up 0 1 0
	EOF
'

test_expect_success 'an error on a continued line names that line' '
	bad_scene "3:13: expected on or off for .projection., found .maybe.$" <<-\EOF
	probe box -3 0 -2 3 3 2 \
	      blend 1 \
	 projection maybe
	EOF
'

test_expect_success 'missing normal map image' '
	bad_scene "2:46: cannot open .bad/none.png.: " <<-\EOF
	probe box -3 0 -2 3 3 2
	sphere center 0 1 0 radius 1 normalmap image bad/none.png
	EOF
'

test_expect_success 'a scene file that does not exist' '
	test_expect_code 1 reflect-gbuffer nowhere.scene 2>err &&
	test_one_line_message reflect-gbuffer err &&
	test_grep "^reflect-gbuffer: cannot open .nowhere.scene.: No such file or directory$" err
'

test_expect_success 'the name in messages is the one given, from stdin too' '
	printf "probe box 0 0 0 1 1 1\nball\n" >s &&
	test_expect_code 1 reflect-gbuffer - <s 2>err &&
	test_grep "^reflect-gbuffer: <stdin>:2:1: unknown keyword .ball." err
'

# A camera inside an object is allowed (it sees the object from inside);
# -v says so, naming the object and its line.
test_expect_success 'camera inside an object: allowed, flagged with -v' '
	cat >inside.scene <<-\EOF &&
	probe box -3 0 -2 3 3 2
	box min -2 0 -1 max -1 3 1
	sphere center 0 1.5 0 radius 0.5
	camera position 0 1.6 0.1 target 1 1.5 0
	EOF
	reflect-gbuffer -x 2 -y 2 inside.scene >out 2>err &&
	test ! -s err &&
	reflect-gbuffer -v -x 2 -y 2 inside.scene >out 2>err &&
	test_one_line_message reflect-gbuffer err &&
	test_grep "frame 0: the camera at (0 1.6 0.1) is inside sphere 2 (inside.scene:3)$" err
'

test_expect_success 'camera outside the room: flagged with -v' '
	cat >outside.scene <<-\EOF &&
	probe box -3 0 -2 3 3 2
	camera position 0 1.6 9 target 0 1.5 0
	EOF
	reflect-gbuffer -v -x 2 -y 2 outside.scene >out 2>err &&
	test_grep "frame 0: the camera at (0 1.6 9) is outside the room" err
'

# A quoted word used to allocate the rest of the file: one 4 MB line of
# "" took some 40 s and gigabytes; now each is its own size.  The line is
# lexed whole before the statement is refused.
# Each quoted word once allocated the rest of the file: a 2 MB line of
# them took 2.8 GB and 10 s.  Memory is the measure (time is not, on a
# loaded machine under the sanitizers: 4 s there); address space limits
# do not mix with the sanitizers, whose run has none.
quotes_limit=1000000
grep -q fsanitize "$builddir/Makefile" && quotes_limit=unlimited
test_expect_success 'a scene of many quoted words is parsed in its own size' '
	{
		echo "probe box -1 -1 -1 1 1 1" &&
		printf "name \"a \\\\\"quoted\\\\\" name\"" &&
		awk "BEGIN { for (i = 0; i < 1400000; i++) printf \" \\\"\\\"\"; print \"\" }"
	} >quotes.scene &&
	test $(wc -c <quotes.scene) -gt 4000000 &&
	test_expect_code 1 sh -c "ulimit -v $quotes_limit && exec timeout 60 reflect-gbuffer -x 2 -y 2 quotes.scene" >out 2>err &&
	test_one_line_message reflect-gbuffer err &&
	test_grep "quotes.scene:2:26: expected the end of the line after the name" err
'

# What a scene puts in the stream's header (its name, a probe's env) must
# fit a header line and hold no control byte: refused at the scene's line,
# not later by the writer with no line to name.
test_expect_success 'header values too long or with control bytes name the line' '
	long=$(awk "BEGIN { for (i = 0; i < 2100; i++) printf \"a\" }") &&
	printf "probe box -1 -1 -1 1 1 1\nprobe box -1 -1 -1 1 1 1 env %s.exr\n" "$long" \
		>long.scene &&
	test_expect_code 1 reflect-gbuffer -x 1 -y 1 long.scene >out 2>err &&
	test ! -s out &&
	test_one_line_message reflect-gbuffer err &&
	test_grep "long.scene:2:30: expected an environment path of at most 2028 bytes, since the stream.s header carries it; it is 2104" err &&
	printf "probe box -1 -1 -1 1 1 1\nname \"a\033]0;x\"\n" >ctl.scene &&
	test_expect_code 1 reflect-gbuffer -x 1 -y 1 ctl.scene >out 2>err &&
	test_grep "ctl.scene:2:6: expected a name without control characters (byte 2 is 0x1b)" err &&
	printf "probe box -1 -1 -1 1 1 1 env \"a\001b.exr\"\n" >ctl2.scene &&
	test_expect_code 1 reflect-gbuffer -x 1 -y 1 ctl2.scene >out 2>err &&
	test_grep "ctl2.scene:1:30: expected an environment path without control characters (byte 2 is 0x01)" err &&
	name=$(awk "BEGIN { for (i = 0; i < 2100; i++) printf \"n\" }") &&
	printf "probe box -1 -1 -1 1 1 1\nname %s\n" "$name" >longname.scene &&
	test_expect_code 1 reflect-gbuffer -x 1 -y 1 longname.scene >out 2>err &&
	test_grep "longname.scene:2:6: expected a name of at most 2028 bytes" err
'

test_expect_success 'a long scene path in a capture names the probe line' '
	dir=$(awk "BEGIN { for (i = 0; i < 9; i++) printf \"%0250d/\", i }") &&
	mkdir -p "$dir" &&
	printf "probe box -1 -1 -1 1 1 1\nroom emission 1 1 1\n" >"$dir/x.scene" &&
	test_expect_code 1 reflect-gbuffer -x 1 -y 1 "$dir/x.scene" >out 2>err &&
	test ! -s out &&
	test_grep "x.scene:1:1: expected the capture of this scene (the probe names no env, and the scene emits) of at most 2028 bytes" err
'

test_done
