#!/bin/sh
test_description='a tool that fails after its stream began ends it so that every reader fails'
. "$srcdir/tests/lib.sh"

P=$REFLECT_TEST_PLUGINS
export REFLECT_PLUGIN_PATH="$builddir/plugins/.libs:$P"
sq="'"

# The stream of a mode that fails at row 500 of 600, its status left out.
failing () {
	reflect-project -j1 -m bail_at_row:row=500 g.rfl 2>/dev/null
	return 0
}

# A second reflect-project in a pipe, taking the NaN rows, its status
# in st1.
again () {
	reflect-project --invalid=zero 2>err1
	echo $? >st1
}

# bail_at_row gives up in run() at one row.  With -j1 and rows of 256
# pixels, a block is a few hundred rows, so a frame of 600 rows that
# fails at row 500 has sent whole blocks before it failed.
test_expect_success 'setup: a G-buffer, and the stream of a mode that never fails' '
	reflect-gbuffer -x 256 -y 600 >g.rfl &&
	reflect-project -j1 -m bail_at_row:row=1000000 g.rfl >good.rfl &&
	ncomp=$(reflect-info good.rfl | sed -n "s/^	NCOMP=//p") &&
	echo $((256 * ncomp * 4)) >row-bytes
'

# The bytes of a stream's first header, up to its empty line.
header_bytes () {
	echo $(($(grep -a -b -m 1 -x "" "$1" | cut -d: -f1) + 1))
}

test_expect_success 'a mode that fails after rows went out: its rows, NaN, a trailer' '
	test_expect_code 1 reflect-project -j1 -m bail_at_row:row=500 g.rfl >bad.rfl 2>err &&
	test_one_line_message reflect-project err &&
	msg="reflect-project: ${sq}g.rfl${sq}: frame 1, mode ${sq}bail_at_row${sq}: row 501 is one it cannot take at all" &&
	test_grep "^$msg\$" err &&
	hdr=$(header_bytes bad.rfl) && good=$(header_bytes good.rfl) &&
	row=$(cat row-bytes) &&
	# the trailer: after the frame${sq}s 600 rows
	tail -c +$((hdr + 600 * row + 1)) bad.rfl >trailer &&
	cut=$(sed -n "s/^FAILED_ROWS=//p" trailer) &&
	test "$cut" -gt 0 && test "$cut" -lt 500 &&
	printf "#?REFLECT1\nFAILED_ROWS=%s\nFAILED=%s\n\n" "$cut" "$msg" >expect &&
	cmp expect trailer &&
	# the rows before the cut are the mode${sq}s, byte for byte
	cmp -n $((cut * row)) -i $good:$hdr good.rfl bad.rfl &&
	# the rest of the frame is NaN
	tail -c +$((hdr + cut * row + 1)) bad.rfl | head -c $(((600 - cut) * row)) |
	od -An -v -tx4 | tr -s " " "\\n" | sed "/^$/d" | sort -u >values &&
	echo 7fc00000 >expect &&
	diff -u expect values
'

# Across a pipe: every reader refuses the trailer with the message, a
# tool that writes a stream ends its own with one in turn, and the
# file made of the frame before it is removed.
test_expect_success 'every reader after it fails, with the message, across pipes' '
	re="failed in frame 1, which holds only its first [0-9]* of 600 rows (the rest are NaN): reflect-project: .g\\.rfl.: frame 1, mode .bail_at_row.: row 501 is one it cannot take at all" &&
	test_expect_code 1 reflect-info bad.rfl >/dev/null 2>err &&
	test_grep "^reflect-info: .bad\\.rfl.: frame 2: the tool that wrote the stream $re$" err &&
	failing | test_expect_code 1 reflect-export -c P.X,P.Y,P.Z -o out.png 2>err &&
	test_grep "^reflect-export: .<stdin>.: frame 2: the tool that wrote the stream $re; .out\\.png., made of that frame, is removed$" err &&
	! test -e out.png &&
	failing | test_expect_code 1 reflect-compare -c P.X,P.Y,P.Z - good.rfl >/dev/null 2>err &&
	test_grep "^reflect-compare: .*the tool that wrote the stream $re$" err &&
	failing | again | test_expect_code 1 reflect-info >/dev/null 2>err2 &&
	echo 1 >expect && cmp expect st1 &&
	test_grep "^reflect-project: .<stdin>.: frame 2: the tool that wrote the stream $re$" err1 &&
	test_grep "^reflect-info: .<stdin>.: frame 2: the tool that wrote the stream failed after frame 1: reflect-project: .<stdin>.: frame 2: the tool that wrote" err2
'

# A frame the tool cannot take after one it wrote: the stream used to
# end after a whole frame, and read as a good stream of one.
test_expect_success 'a failure between frames: the frame before is whole, the stream is not' '
	cat >two <<-\EOF &&
	#?REFLECT1
	NCOLS=1
	NROWS=1
	NCOMP=9
	CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z
	PROBE_BOX=-1 -1 -1 1 1 1
	FORMAT=ascii

	0	0	0	0	1	0	0	1	0
	#?REFLECT1
	NCOLS=1
	NROWS=1
	NCOMP=3
	CHANNELS=P.X P.Y P.Z
	PROBE_BOX=-1 -1 -1 1 1 1
	FORMAT=ascii

	0	0	0
	EOF
	test_expect_code 1 reflect-project -fa two >out 2>err &&
	tail -n 3 out >trailer &&
	printf "#?REFLECT1\nFAILED=reflect-project: %s\n\n" "$(cat err | sed "s/^reflect-project: //")" >expect &&
	diff -u expect trailer &&
	test_expect_code 1 reflect-info out >/dev/null 2>err &&
	test_grep "^reflect-info: .out.: frame 2: the tool that wrote the stream failed after frame 1: reflect-project: input has no channel .N\\.X. (mode .box. reads " err
'

test_expect_success 'ascii data: the rest as nan; -h: no header, no trailer' '
	test_expect_code 1 reflect-project -fa -j1 -m bail_at_row:row=0 g.rfl >bad.txt 2>/dev/null &&
	test_grep "^FAILED_ROWS=0$" bad.txt &&
	sed -n "/^$/,\$p" bad.txt | sed -n 2p >first &&
	ncomp=$(reflect-info good.rfl | sed -n "s/^	NCOMP=//p") &&
	tr "\\t" "\\n" <first | sort -u >values &&
	echo nan >expect && diff -u expect values &&
	test_expect_code 1 reflect-info bad.txt 2>err &&
	test_grep "holds only its first 0 of 600 rows" err &&
	test_expect_code 1 reflect-project -h -j1 -m bail_at_row:row=500 g.rfl >raw 2>/dev/null &&
	! grep -a "FAILED" raw
'

test_expect_success '-v names an optional input the stream lacks, once' '
	sed -n "1,9p" two >one &&
	cat one one | reflect-project -v -m bevel >/dev/null 2>err &&
	test_grep "^reflect-project: .<stdin>.: frame 1: mode .bevel. reads as NaN its optional input .roughness., which the stream lacks$" err &&
	test $(grep -c "optional input" err) = 1 &&
	reflect-project -v -m bevel g.rfl >/dev/null 2>err &&
	! grep "optional input" err &&
	reflect-project -m bevel one >/dev/null 2>err &&
	test_line_count 0 err
'

test_done
