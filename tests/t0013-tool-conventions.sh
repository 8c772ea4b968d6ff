#!/bin/sh
test_description='tool conventions: --help, usage, -V, messages, exit status, full disk, closed pipe, stdin'
. "$srcdir/tests/lib.sh"

SQ="'"
tools='reflect-info reflect-project reflect-export'

test_expect_success 'set up a G-buffer' '
	cat >in.txt <<-\EOF
	#?REFLECT1
	PROBE_BOX=-3 0 -2 3 3 2
	PROBE_CENTER=0 1.5 0
	NCOLS=2
	NROWS=1
	NCOMP=9
	CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z
	FORMAT=ascii

	0 1 0 0 1 0 0 1 0
	1 1 0 1 0 0 1 0 0
	EOF
'

for tool in $tools
do
	test_expect_success "$tool --help: usage on stdout, exit 0" '
		'$tool' --help >out 2>err &&
		test_grep "^usage: '$tool' " out &&
		test ! -s err
	'

	test_expect_success "$tool: an unknown option gives the usage on stderr, exit 1" '
		test_expect_code 1 '$tool' --no-such-option >out 2>err &&
		test ! -s out &&
		test_grep "^usage: '$tool' " err &&
		test_grep "^'$tool': unrecognized option .--no-such-option.$" err &&
		test_expect_code 1 '$tool' -Z >out 2>err &&
		test ! -s out &&
		test_grep "^'$tool': invalid option -- .Z.$" err &&
		test_grep "^usage: '$tool' " err
	'

	test_expect_success "$tool -V: tool, library and plugin ABI versions" '
		'$tool' -V >out 2>err &&
		test ! -s err &&
		test_line_count 3 out &&
		test_grep "^'$tool' (reflect) [0-9][0-9.]*$" out &&
		test_grep "^libreflect [0-9][0-9.]*$" out &&
		test_grep "^plugin ABI 1\.3$" out
	'
done

test_expect_success 'a missing file: cannot open, exit 1' '
	test_expect_code 1 reflect-project nope >out 2>err &&
	echo "reflect-project: cannot open ${SQ}nope${SQ}: No such file or directory" >expect &&
	diff -u expect err &&
	test ! -s out &&
	test_expect_code 1 reflect-info nope 2>err &&
	echo "reflect-info: cannot open ${SQ}nope${SQ}: No such file or directory" >expect &&
	diff -u expect err &&
	test_expect_code 1 reflect-export -o out.exr nope 2>err &&
	echo "reflect-export: cannot open ${SQ}nope${SQ}: No such file or directory" >expect &&
	diff -u expect err
'

test_expect_success 'a directory as input: a system error, exit 2' '
	mkdir dir &&
	test_expect_code 2 reflect-info dir 2>err &&
	echo "reflect-info: cannot read ${SQ}dir${SQ}: Is a directory" >expect &&
	diff -u expect err
'

test_expect_success 'two files: usage, exit 1' '
	test_expect_code 1 reflect-project in.txt in.txt >out 2>err &&
	test ! -s out &&
	test_grep "^usage: reflect-project " err
'

if test -w /dev/full
then
	test_expect_success 'stdout on a full disk: exit 2, a message naming the error' '
		test_expect_code 2 reflect-project in.txt >/dev/full 2>err &&
		test_one_line_message reflect-project err &&
		test_grep "No space left on device" err &&
		test_expect_code 2 reflect-project -fa in.txt >/dev/full 2>err &&
		test_one_line_message reflect-project err &&
		test_grep "No space left on device" err &&
		test_expect_code 2 reflect-info -s in.txt >/dev/full 2>err &&
		test_one_line_message reflect-info err &&
		test_grep "^reflect-info: cannot write .<stdout>.: No space left on device$" err
	'

	test_expect_success 'a full disk also fails --help and -V' '
		for tool in $tools
		do
			test_expect_code 2 $tool --help >/dev/full 2>err &&
			test_grep "^$tool: .*No space left on device$" err &&
			test_expect_code 2 $tool -V >/dev/full 2>err &&
			test_grep "^$tool: .*No space left on device$" err || return 1
		done
	'

	test_expect_success 'a big stream on a full disk fails while writing' '
		head -c 720000 /dev/zero >big.raw &&
		test_expect_code 2 reflect-project --invalid=zero -H -x 200 -y 100 \
			-c "P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z" \
			--box=-3,0,-2,3,3,2 --center=0,1.5,0 big.raw >/dev/full 2>err &&
		test_one_line_message reflect-project err &&
		test_grep "^reflect-project: cannot write .<stdout>.: No space left on device$" err
	'
else
	test_skip 'stdout on a full disk: exit 2, a message naming the error' 'no /dev/full'
	test_skip 'a full disk also fails --help and -V' 'no /dev/full'
	test_skip 'a big stream on a full disk fails while writing' 'no /dev/full'
fi

# A closed downstream pipe ends the tool quietly: SIGPIPE (or EPIPE with
# SIGPIPE ignored by the parent) and no message.  Only stderr is checked:
# the status is the signal's.
test_expect_success 'a closed downstream pipe ends the tool quietly' '
	head -c 36000000 /dev/zero >big.raw &&
	{ reflect-project --invalid=zero -H -x 2000 -y 500 \
		-c "P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z" \
		--box=-3,0,-2,3,3,2 --center=0,1.5,0 big.raw 2>err; } |
	head -c 100 >out &&
	test "$(wc -c <out)" -eq 100 &&
	test_grep "^#?REFLECT1" out &&
	test ! -s err
'

test_expect_success 'quiet too when the parent ignores SIGPIPE' '
	(
		trap "" PIPE &&
		{ reflect-project --invalid=zero -H -x 2000 -y 500 \
			-c "P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z" \
			--box=-3,0,-2,3,3,2 --center=0,1.5,0 big.raw 2>err; } |
		head -c 100 >out
	) &&
	test "$(wc -c <out)" -eq 100 &&
	test ! -s err &&
	{ reflect-info -H -x 2000 -y 500 -c 9 big.raw 2>err.info; } | head -c 5 >out &&
	test "$(cat out)" = "frame" &&
	test ! -s err.info
'

test_expect_success 'reading - or no file means stdin' '
	reflect-info in.txt >expect &&
	reflect-info - <in.txt >got &&
	diff -u expect got &&
	reflect-info <in.txt >got &&
	diff -u expect got &&
	reflect-project -h in.txt >expect.raw &&
	reflect-project -h - <in.txt >got.raw &&
	cmp expect.raw got.raw &&
	reflect-project -fa - <in.txt >got.txt &&
	test_grep "^reflect-project -fa -$" got.txt &&
	cat in.txt | reflect-project -h >got.raw &&
	cmp expect.raw got.raw
'

# The tools with an embedded default (a scene, an environment) read a
# piped or redirected standard input and never the default instead;
# the default needs a terminal, /dev/null, or the word "default".
test_expect_success 'set up a scene unlike the default' '
	reflect-gbuffer --print-default-scene | sed "s/fov 55/fov 30/" >narrow.scene &&
	test_grep "fov 30" narrow.scene
'

for tool in "reflect-gbuffer" "reflect-trace --samples=1"
do
	test_expect_success "${tool%% *} reads a scene piped or redirected into it" '
		'"$tool"' -x 4 -y 2 </dev/null | reflect-info >default.info &&
		test_grep "CAMERA=.* 55$" default.info &&
		for how in pipe file name
		do
			case $how in
			pipe) cat narrow.scene | '"$tool"' -x 4 -y 2 >s.rfl && fov=30 ;;
			file) '"$tool"' -x 4 -y 2 <narrow.scene >s.rfl && fov=30 ;;
			name) '"$tool"' -x 4 -y 2 default <narrow.scene >s.rfl && fov=55 ;;
			esac || return 1
			reflect-info s.rfl >s.info || return 1
			test_grep "CAMERA=.* $fov$" s.info || return 1
		done
	'
done

test_expect_success 'reflect-capture and reflect-prefilter: the pipe of the man page' '
	sed "s/box -3 0 -2 3 3 2/box -3 0 -2 3 3.5 2/" narrow.scene >tall.scene &&
	reflect-capture -n 8 tall.scene >tall.rfl &&
	reflect-capture -h -n 8 tall.scene >tall.raw &&
	reflect-capture -h -n 8 </dev/null >room.raw &&
	cat tall.scene | reflect-capture -h -n 8 >piped.raw &&
	cmp tall.raw piped.raw &&
	! cmp -s tall.raw room.raw &&
	reflect-prefilter -s 4 -o expect.rfl tall.rfl 2>/dev/null &&
	reflect-capture -n 8 tall.scene | reflect-prefilter -s 4 -o got.rfl 2>/dev/null &&
	reflect-info got.rfl >got.info &&
	test_grep "NCOLS=8" got.info &&
	reflect-compare expect.rfl got.rfl >out &&
	test_grep "^PASS$" out &&
	reflect-prefilter -s 4 --size=8 -o default.rfl </dev/null 2>/dev/null &&
	reflect-prefilter -s 4 --size=8 -o named.rfl default <tall.rfl 2>/dev/null &&
	reflect-compare default.rfl named.rfl >out &&
	test_grep "^PASS$" out
'

test_expect_success 'bad input in stdin is named <stdin>' '
	printf "#?REFLECT1\nNCOLS=x\n" | test_expect_code 1 reflect-info - 2>err &&
	echo "reflect-info: ${SQ}<stdin>${SQ}: header line 2: NCOLS is not a number (${SQ}x${SQ})" >expect &&
	diff -u expect err
'

test_expect_success 'only stream data on stdout' '
	reflect-project in.txt >out.rf 2>err &&
	test ! -s err &&
	head -c 11 out.rf >magic &&
	printf "#?REFLECT1\n" | cmp - magic
'

# A message quotes names from command lines and files: none of their
# control bytes (ESC above all, which recolours or clears a terminal)
# may reach it; each is written as "?".
test_expect_success 'messages carry no control bytes' '
	esc=$(printf "\033") &&
	test_expect_code 1 reflect-shade -m "x${esc}[31mred" </dev/null 2>err &&
	! grep "$esc" err && test_grep "x?\[31mred" err &&
	test_expect_code 1 reflect-project -m "box:a${esc}=1" </dev/null 2>err &&
	! grep "$esc" err &&
	printf "probe box -1 -1 -1 1 1 1\n${esc}[2Jfoo\n" >esc.scene &&
	test_expect_code 1 reflect-gbuffer esc.scene >/dev/null 2>err &&
	! grep "$esc" err && test_grep "unknown keyword .?\[2Jfoo." err &&
	test_expect_code 1 reflect-info "no${esc}]0;title" 2>err &&
	! grep "$esc" err && test_one_line_message reflect-info err &&
	tab=$(printf "\t") &&
	test_expect_code 1 reflect-export -o "a${tab}b.nosuch" </dev/null 2>err &&
	! grep "$tab" err
'

# 20,000 one-pixel frames: a frame of one block has nothing to overlap,
# and a batch of one row needs no pool thread, so no frame starts one
# (before: 60,000 clones and 3.9 s here, now none and 0.15 s).
test_expect_success 'many small frames start no thread each' '
	awk "BEGIN {
		for (i = 0; i < 20000; i++) {
			printf \"#?REFLECT1\\nPROBE_BOX=-3 0 -2 3 3 2\\nPROBE_CENTER=0 1.5 0\\n\"
			printf \"NCOLS=1\\nNROWS=1\\nNCOMP=10\\n\"
			printf \"CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness\\n\"
			printf \"FORMAT=ascii\\n\\n0 0 0 0 1 0 0 0.6 0.8 0.3\\n\"
		}
	}" >frames.txt &&
	reflect-project -j 2 frames.txt >frames.rfl &&
	reflect-info frames.rfl | grep -c "^frame " >count &&
	echo 20000 >expect &&
	cmp expect count &&
	reflect-prefilter --size=8 >env.rfl &&
	reflect-shade -j 2 --env=env.rfl frames.rfl >shaded.rfl &&
	reflect-info shaded.rfl | grep -c "^frame " >count &&
	cmp expect count &&
	if command -v strace >/dev/null 2>&1
	then
		for tool in "reflect-project -j 2 frames.txt" "reflect-shade -j 2 --env=env.rfl frames.rfl"
		do
			ASAN_OPTIONS=detect_leaks=0 \
			"$builddir/libtool" --mode=execute strace -f -o trace -e trace=clone,clone3 \
				$builddir/bin/$tool >/dev/null &&
			grep -c "clone" trace >clones || : &&
			test "$(cat clones)" -lt 10 || return 1
		done
	fi
'

test_done
