#!/bin/sh
test_description='a plugin that prints, crashes or writes what its kind may not: never a wrong stream with exit 0'
. "$srcdir/tests/lib.sh"

P=$REFLECT_TEST_PLUGINS

test_expect_success 'setup: a G-buffer of 24 rows' '
	reflect-gbuffer -x 16 -y 24 | reflect-project >gbuf
'

test_expect_success 'a mode that prints to stdout leaves the stream as a quiet one' '
	reflect-project -fa -j 2 -m "$P/print_stdout.so:quiet=1" <gbuf >quiet 2>err &&
	echo "print_stdout: loaded" >expect &&
	diff -u expect err &&
	reflect-project -fa -j 2 -m "$P/print_stdout.so" <gbuf >out 2>err &&
	# the streams differ in the command line and mode recorded, only there
	grep -v "^reflect-project \|^PROJECTION=" quiet >quiet.body &&
	grep -v "^reflect-project \|^PROJECTION=" out >out.body &&
	test_line_count 401 out.body &&
	cmp quiet.body out.body &&
	test_grep "^print_stdout: loaded$" err &&
	test_grep "^print_stdout: create$" err &&
	test_grep "^print_stdout: row 23$" err &&
	test_grep "^print_stdout: raw$" err &&
	test_grep "^print_stdout: row 0$" err
'

test_expect_success 'the stream after a printing mode reads as one' '
	reflect-project -m "$P/print_stdout.so" <gbuf 2>/dev/null >out &&
	reflect-info out >info &&
	test_grep "NROWS=24" info
'

# crashing STATUS ARGS...: reflect-project ARGS dies with exit STATUS,
# leaving no core file; its stderr in err (exec: no shell in between
# adds its own word on the signal).
crashing () {
	(
		ulimit -c 0 &&
		want=$1 &&
		shift &&
		test_expect_code $want sh -c \
			"exec reflect-project \"\$@\" <gbuf >out 2>err" reflect-project "$@"
	)
}

# crashed HOW STATUS SIGNAL ARGS...: reflect-project with crash.so's
# way HOW dies of the signal (exit STATUS) after one line naming the
# mode, its file, the call, and SIGNAL's name.
crashed () {
	how=$1 status=$2 signal=$3 &&
	shift 3 &&
	crashing $status "$@" -m "$P/crash.so:how=$how:row=5" &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: mode .crash. (.$P/crash\.so.) crashed in run() on frame 1, row 6: .* ($signal); the mode has a bug: report it to its author with the input that makes it crash$" err
}

test_expect_success 'a mode that faults: mode, file, frame and row, then the signal' '
	crashed segv 139 SIGSEGV &&
	crashed segv 139 SIGSEGV -j 1 &&
	crashed segv 139 SIGSEGV -j 4
'

test_expect_success 'a mode whose stack overflows is reported too' '
	crashed stack 139 SIGSEGV -j 1 &&
	crashed stack 139 SIGSEGV -j 3
'

test_expect_success 'illegal instruction, abort, bus error, arithmetic exception' '
	crashed ill 132 SIGILL &&
	crashed abort 134 SIGABRT &&
	crashed bus 135 SIGBUS &&
	crashed fpe 136 SIGFPE
'

test_expect_success 'a crash in create() names the call, no frame' '
	crashing 139 -m "$P/crash.so:in_create=1" &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: mode .crash. (.$P/crash\.so.) crashed in create(): segmentation fault (SIGSEGV); " err
'

test_expect_success 'a mode that does not crash runs as before' '
	reflect-project -m "$P/crash.so:how=none" <gbuf >out 2>err &&
	test_line_count 0 err &&
	reflect-info out >info &&
	test_grep "NROWS=24" info
'

# The mirror's pixels (mask 1) of the G-buffer: row 21, pixel 4 is one,
# row 6, pixel 4 a wall.
test_expect_success 'setup: a shaded stream, and which pixels are walls' '
	reflect-shade <gbuf >shaded 2>/dev/null &&
	reflect-project -fa <gbuf |
	awk "body && (++n == 20 * 16 + 4 || n == 5 * 16 + 4) { print \$18 } /^\$/ { body = 1 }" >mask &&
	printf "0\n1\n" >expect &&
	diff -u expect mask
'

# wrote TOOL INPUT MODE WHAT: TOOL stops, exit 1, naming the frame, row
# 21, pixel 4, the mode and what it wrote (a regex).
wrote () {
	test_expect_code 1 $1 -m "$P/$3:x=3:y=20" <$2 >out 2>err &&
	test_grep "^$1: .<stdin>.: frame 1, row 21, pixel 4: mode .bad_[a-z]*. broke its output contract: $4" err &&
	! grep -v "prefiltering" err | grep -v "broke its output contract"
}

test_expect_success 'a projection mode that writes NaN: stopped, named' '
	wrote reflect-project gbuf "projection-bad_out.so" "channel .R\.X. is nan (--invalid=clamp or --invalid=zero goes on)$" &&
	wrote reflect-project gbuf "projection-bad_out.so:out=6" "channel .hit\.dist. is nan, not a distance" &&
	wrote reflect-project gbuf "projection-bad_out.so:out=4:value=inf" "channel .D\.Y. is inf (--invalid"
'

test_expect_success 'an infinite distance is a distance; a wall is not checked' '
	reflect-project -m "$P/projection-bad_out.so:x=3:y=20:out=6:value=inf" <gbuf >out 2>err &&
	test_line_count 0 err &&
	reflect-project -m "$P/projection-bad_out.so:x=3:y=5" <gbuf >out 2>err &&
	test_line_count 0 err
'

test_expect_success 'a shade mode: roughness.eff outside [0, 1], a radiance below 0 or NaN' '
	wrote reflect-shade gbuf "shade-bad_out.so:value=2" "channel .roughness\.eff. is 2, outside \[0, 1\]" &&
	wrote reflect-shade gbuf "shade-bad_out.so" "channel .roughness\.eff. is nan, outside \[0, 1\]" &&
	wrote reflect-shade gbuf "shade-bad_spec.so:value=-1" "channel .spec\.R. is -1, not a radiance (finite, not negative)" &&
	wrote reflect-shade gbuf "shade-bad_spec.so:out=2:value=inf" "channel .spec\.B. is inf, not a radiance"
'

test_expect_success 'an occlusion mode: a factor outside [0, 1]' '
	wrote reflect-occlude shaded "occlusion-bad_out.so:value=-1" "channel .occlusion. is -1, outside \[0, 1\]"
'

test_expect_success 'an accumulate mode: a value not finite, a variance below 0' '
	wrote reflect-accumulate shaded "accumulate-bad_out.so" "the value of channel .spec\.R. is nan$" &&
	wrote reflect-accumulate shaded "accumulate-bad_out.so:value=-inf" "the value of channel .spec\.R. is -inf$" &&
	wrote reflect-accumulate shaded "accumulate-bad_out.so:out=1:value=-1" "the variance of channel .spec\.R. is negative$" &&
	reflect-accumulate -m "$P/accumulate-bad_out.so:x=3:y=20:out=1:value=inf" <shaded >out 2>err &&
	test_line_count 0 err
'

test_expect_success 'a filter mode: a filtered value not finite' '
	wrote reflect-filter shaded "filter-bad_out.so" "pass 1 wrote channel .spec\.R. as nan$" &&
	wrote reflect-filter shaded "filter-bad_out.so:out=2:value=inf" "pass 1 wrote channel .spec\.B. as inf$"
'

# field ROW PIXEL CHANNEL: the value of CHANNEL at that pixel (counted
# from 1) of the ascii stream out, whose data follow the empty line.
field () {
	awk -v want="$3" -v at=$((($1 - 1) * 16 + $2)) "
		/^CHANNELS=/ { sub(/^CHANNELS=/, \"\"); for (i = 1; i <= NF; i++) if (\$i == want) col = i }
		body && ++n == at { print \$col }
		/^\$/ { body = 1 }" out
}

test_expect_success '--invalid=clamp repairs and counts what a mode wrote' '
	reflect-project -fa --invalid=clamp -m "$P/projection-bad_out.so:x=3:y=20" <gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: .<stdin>.: frame 1: 1 pixel where the mode broke its output contract clamped (or zeroed)$" err &&
	test "$(field 21 4 R.X)" = 0 &&
	reflect-shade -fa --invalid=clamp -m "$P/shade-bad_spec.so:x=3:y=20:value=inf" <gbuf >out 2>err &&
	test_grep "^reflect-shade: .<stdin>.: frame 1: 1 pixel where the mode broke its output contract clamped (or zeroed)$" err &&
	test "$(field 21 4 spec.R)" = 3.40282347e+38
'

test_expect_success '--invalid=zero writes the pixel.s outputs 0 and counts it' '
	reflect-project -fa --invalid=zero -m "$P/projection-bad_out.so:x=3:y=20:out=7" <gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: .<stdin>.: frame 1: 1 pixel where the mode broke its output contract zeroed$" err &&
	test "$(field 21 4 R.X)" = 0 &&
	test "$(field 21 4 probe.dist)" = 0 &&
	test "$(field 21 5 probe.dist)" = inf
'

test_done
