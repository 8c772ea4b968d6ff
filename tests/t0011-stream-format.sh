#!/bin/sh
test_description='the stream format: frames, ascii, headerless, byte order, header lines, alignment, CRLF'
. "$srcdir/tests/lib.sh"

SQ="'"

# A 3x3 G-buffer in ascii, with an extra channel of awkward values that
# reflect-project passes through.
test_expect_success 'set up a G-buffer' '
	cat >in.txt <<-\EOF &&
	#?REFLECT1
	reflect-gbuffer --scene=room
	MY_KEY=hello world
	camera.fov=45
	PROBE_BOX=-3 0 -2 3 3 2
	PROBE_CENTER=0 1.5 0
	NCOLS=3
	NROWS=3
	NCOMP=10
	CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z extra
	FORMAT=ascii

	0 1 0 0 1 0 0 1 0 0.1
	1 1 0 1 0 0 1 0 0 1e-30
	-1 0.5 1 0 0 1 0 0 1 3.40282347e+38
	0.5 2 -1 0 -1 0 0 -1 0 -0
	2 1 1 -1 0 0 -1 0 0 nan
	-2 1 -1 0 0 -1 0 0 -1 -inf
	0 0 0 0 1 0 0.6 0.8 0 1.17549435e-38
	1 2 1 0 1 0 0 0.8 0.6 1.40129846e-45
	0 1.5 0 0 1 0 0 1 0 16777217
	EOF
	names="P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z extra" &&
	names="$names R.X R.Y R.Z D.X D.Y D.Z hit.dist probe.dist" &&
	echo "$names" >names &&
	reflect-project in.txt >f.rf &&
	test_grep "^CHANNELS=$names$" f.rf &&
	test_grep "^NCOMP=18$" f.rf &&
	reflect-project -h in.txt >raw
'

# Data of a float stream of one 3x3x18 frame: its last 648 bytes.
data () {
	tail -c 648 "$1"
}

# The data lines of the first frame of an ascii stream.
ascii_data () {
	sed "1,/^$/d" "$1"
}

test_expect_success 'multiple frames back to back, each printed by reflect-info' '
	{
		printf "#?REFLECT1\nNCOLS=2\nNROWS=1\nNCOMP=1\nCHANNELS=a\n" &&
		printf "BigEndian=1\nFORMAT=float\n\n" &&
		printf "\077\200\000\000\100\000\000\000" &&
		printf "#?REFLECT1\nFRAME=1\nNCOLS=1\nNROWS=3\nNCOMP=2\nCHANNELS=x y\n" &&
		printf "FORMAT=ascii\n\n1 2\n3 4\n5 6\n\n\n" &&
		printf "#?REFLECT1\nNCOLS=1\nNROWS=1\nNCOMP=1\nCHANNELS=last\n" &&
		printf "BigEndian=0\nFORMAT=float\n\n\000\000\000\000"
	} >frames.rf &&
	reflect-info frames.rf >out.tab &&
	tab=$(printf "\t") &&
	sed "s/^$tab/> /" out.tab >out &&
	test "$(grep -c "^$tab" out.tab)" -eq 18 &&
	cat >expect <<-\EOF &&
	frame 1:
	> NCOLS=2
	> NROWS=1
	> NCOMP=1
	> CHANNELS=a
	> BigEndian=1
	> FORMAT=float
	frame 2:
	> FRAME=1
	> NCOLS=1
	> NROWS=3
	> NCOMP=2
	> CHANNELS=x y
	> FORMAT=ascii
	frame 3:
	> NCOLS=1
	> NROWS=1
	> NCOMP=1
	> CHANNELS=last
	> BigEndian=0
	> FORMAT=float
	EOF
	diff -u expect out &&
	reflect-info -s frames.rf >stats &&
	awk "\$1 == \"a\" || \$1 == \"y\" || \$1 == \"last\" { print \$1, \$2, \$3, \$4 }" \
		stats >got &&
	printf "a 1 2 1.5\ny 2 6 4\nlast 0 0 0\n" >expect &&
	diff -u expect got
'

test_expect_success 'every frame goes through reflect-project' '
	cat f.rf f.rf f.rf >three.rf &&
	reflect-project three.rf >out.rf &&
	reflect-info out.rf >info &&
	test "$(grep -c "^frame " info)" -eq 3 &&
	test_grep "^frame 3:$" info &&
	test "$(grep -c "^	reflect-project three.rf$" info)" -eq 3 &&
	test "$(grep -c "^	reflect-project in.txt$" info)" -eq 3 &&
	reflect-project -h three.rf >three.raw &&
	cat raw raw raw | cmp - three.raw
'

test_expect_success 'ascii output (-fa) writes floats exactly and reads back' '
	reflect-project -fa f.rf >a.txt &&
	test_grep "^FORMAT=ascii$" a.txt &&
	! grep "^BigEndian=" a.txt &&
	ascii_data a.txt >a.data &&
	test_line_count 9 a.data &&
	awk "{ print \$10 }" a.data >extra &&
	cat >expect <<-\EOF &&
	0.100000001
	1e-30
	3.40282347e+38
	-0
	nan
	-inf
	1.17549435e-38
	1.40129846e-45
	16777216
	EOF
	diff -u expect extra &&
	reflect-project a.txt >f2.rf &&
	data f.rf >d1 &&
	data f2.rf >d2 &&
	cmp d1 d2
'

test_expect_success 'headerless output (-h) is the data alone' '
	test "$(wc -c <raw)" -eq 648 &&
	data f.rf | cmp - raw
'

test_expect_success 'headerless input (-H -x -y -c NAMES)' '
	reflect-info -s f.rf | sed 1,/^.channel/d >expect &&
	reflect-info -s -H -x 3 -y 3 -c "$(cat names)" raw >out &&
	test_grep "^	CHANNELS=$(cat names)$" out &&
	sed 1,/^.channel/d out >got &&
	test_line_count 18 got &&
	diff -u expect got &&
	reflect-project -h -H -x 3 -y 3 -c "$(tr " " , <names)" \
		--box=-3,0,-2,3,3,2 --center=0,1.5,0 raw >raw2 &&
	cmp raw raw2
'

test_expect_success 'headerless input (-c COUNT) names the channels c0 c1 ...' '
	reflect-info -H -x 3 -y 3 -c 18 raw >out &&
	test_grep "^	NCOMP=18$" out &&
	test_grep "^	CHANNELS=c0 c1 c2 c3 c4 c5 c6 c7 c8 c9 c10 c11 c12 c13 c14 c15 c16 c17$" out &&
	test_expect_code 1 reflect-info -H -x 3 -y 3 -c 0 raw 2>err &&
	test_grep "^reflect-info: option -c: .0. is neither a channel count in \[1, 1024\] nor a list of names$" err
'

# Bytes that look like blanks are data, not gaps between headerless frames.
test_expect_success 'headerless frames whose data looks like blanks' '
	printf "\000\000\000\000\040\040\040\040\012\012\012\012\015\011\040\012" \
		>blanks.raw &&
	reflect-info -s -H -x 1 -y 1 -c v blanks.raw >out &&
	test "$(grep -c "^frame " out)" -eq 4 &&
	awk "\$1 == \"v\" { print \$2 }" out >got &&
	sed -n 1,3p got >got3 &&
	printf "0\n1.356316e-19\n6.646346e-33\n" >expect &&
	diff -u expect got3
'

test_expect_success 'big-endian data made by hand reads as the same numbers' '
	{
		printf "#?REFLECT1\nNCOLS=2\nNROWS=2\nNCOMP=1\nCHANNELS=v\n" &&
		printf "BigEndian=1\nFORMAT=float\n\n" &&
		printf "\077\300\000\000\300\040\000\000\076\040\000\000\107\177\340\000"
	} >be.rf &&
	{
		printf "#?REFLECT1\nNCOLS=2\nNROWS=2\nNCOMP=1\nCHANNELS=v\n" &&
		printf "BigEndian=0\nFORMAT=float\n\n" &&
		printf "\000\000\300\077\000\000\040\300\000\000\040\076\000\340\177\107"
	} >le.rf &&
	reflect-info -s be.rf >be.out &&
	test_grep "^	BigEndian=1$" be.out &&
	awk "\$1 == \"v\" { print \$2, \$3, \$4, \$5, \$6 }" be.out >got &&
	echo "-2.5 65504 16375.79 0 0" >expect &&
	diff -u expect got &&
	reflect-info -s le.rf >le.out &&
	awk "\$1 == \"v\" { print \$2, \$3, \$4, \$5, \$6 }" le.out >got &&
	diff -u expect got
'

test_expect_success 'a big-endian G-buffer gives the same output as the native one' '
	reflect-project -h -fa f.rf >native.txt &&
	reflect-project -h in.txt |
	od -An -v -to1 |
	awk "{ for (i = 1; i <= NF; i += 4)
		printf \"\\\\%s\\\\%s\\\\%s\\\\%s\", \$(i+3), \$(i+2), \$(i+1), \$i }" >swapped &&
	test "$(wc -c <swapped)" -eq $((648 * 4)) &&
	if test "$(grep -a "^BigEndian=" f.rf)" = "BigEndian=0"
	then
		other=1
	else
		other=0
	fi &&
	{
		printf "#?REFLECT1\nPROBE_BOX=-3 0 -2 3 3 2\nPROBE_CENTER=0 1.5 0\n" &&
		printf "NCOLS=3\nNROWS=3\nNCOMP=18\nCHANNELS=%s\n" "$(cat names)" &&
		printf "BigEndian=%s\nFORMAT=float\n\n" $other &&
		printf "$(cat swapped)"
	} >swapped.rf &&
	test_grep "^BigEndian=$other$" swapped.rf &&
	! data swapped.rf | cmp -s - raw &&
	reflect-project -h -fa swapped.rf >swapped.txt &&
	diff -u native.txt swapped.txt
'

test_expect_success 'unknown header keys and free lines are kept, in order' '
	reflect-project -fa in.txt >out.txt &&
	sed "/^$/q" out.txt >head.txt &&
	grep -n -e "^reflect-gbuffer --scene=room$" -e "^MY_KEY=hello world$" \
		-e "^camera.fov=45$" -e "^reflect-project -fa in.txt$" \
		-e "^PROJECTION=box$" head.txt >lines &&
	cat >expect <<-\EOF &&
	2:reflect-gbuffer --scene=room
	3:MY_KEY=hello world
	4:camera.fov=45
	7:reflect-project -fa in.txt
	8:PROJECTION=box
	EOF
	diff -u expect lines
'

test_expect_success 'each tool appends its command line, in order' '
	reflect-project in.txt |
	reflect-project -m box --center=0,1,0 - |
	reflect-project -fa -m infinite >out.txt &&
	grep "^reflect-" out.txt >got &&
	cat >expect <<-\EOF &&
	reflect-gbuffer --scene=room
	reflect-project in.txt
	reflect-project -m box --center=0,1,0 -
	reflect-project -fa -m infinite
	EOF
	diff -u expect got &&
	test_grep "^PROJECTION=infinite$" out.txt &&
	test "$(grep -c "^PROJECTION=" out.txt)" -eq 1
'

test_expect_success 'arguments with blanks or quotes are quoted in the command line' '
	cp in.txt "it${SQ}s here.txt" &&
	reflect-project -fa "--center=0,1,0" "it${SQ}s here.txt" >out.txt &&
	printf "%s\n" "reflect-project -fa --center=0,1,0 ${SQ}it${SQ}\\${SQ}${SQ}s here.txt${SQ}" \
		>expect &&
	grep -F -x -f expect out.txt
'

# The data of a float stream starts on a 4-byte boundary whatever the
# length of the header: FORMAT=float is padded with blanks.
test_expect_success 'FORMAT=float is padded so that the data is 4-byte aligned' '
	: >pads &&
	for v in x xx xxx xxxx
	do
		sed "s/^MY_KEY=.*/MY_KEY=$v/" in.txt >pad.txt &&
		reflect-project pad.txt >pad.rf &&
		size=$(wc -c <pad.rf) &&
		header=$((size - 648)) &&
		test $((header % 4)) -eq 0 &&
		head -c $header pad.rf | tail -c 2 | od -An -c >end &&
		test "$(tr -d " " <end)" = "\n\n" &&
		grep -a "^FORMAT=float *$" pad.rf >format &&
		echo $(($(wc -c <format) - 13)) >>pads || return 1
	done &&
	sort -n pads >got &&
	printf "0\n1\n2\n3\n" >expect &&
	diff -u expect got
'

test_expect_success 'the data of every frame is aligned' '
	for v in x xx xxx xxxx
	do
		sed "s/^MY_KEY=.*/MY_KEY=$v/" in.txt | reflect-project || return 1
	done >four.rf &&
	reflect-project - <four.rf >out.rf &&
	offset=0 &&
	for v in x xx xxx xxxx
	do
		sed "s/^MY_KEY=.*/MY_KEY=$v/" in.txt | reflect-project |
		reflect-project - >one.rf &&
		size=$(wc -c <one.rf) &&
		test $((size % 4)) -eq 0 &&
		offset=$((offset + size)) || return 1
	done &&
	test "$(wc -c <out.rf)" -eq $offset
'

test_expect_success 'CRLF header lines (and data) are tolerated' '
	awk "{ printf \"%s\\r\\n\", \$0 }" in.txt >crlf.txt &&
	test "$(wc -c <crlf.txt)" -eq $(($(wc -c <in.txt) + $(wc -l <in.txt))) &&
	reflect-info -s in.txt >expect &&
	reflect-info -s crlf.txt >got &&
	diff -u expect got &&
	reflect-project crlf.txt >crlf.rf &&
	data crlf.rf | cmp - raw
'

test_expect_success 'a header line of 2048 bytes is taken, with LF or CRLF' '
	long=$(awk "BEGIN { while (n++ < 2043) printf \"x\" }") &&
	{
		printf "#?REFLECT1\nLONG=%s\n" "$long" &&
		printf "NCOLS=1\nNROWS=1\nNCOMP=1\nCHANNELS=a\nFORMAT=ascii\n\n5\n"
	} >long.txt &&
	test "$(sed -n 2p long.txt | wc -c)" -eq 2049 &&
	reflect-info long.txt >out &&
	test_grep "^	LONG=x*$" out &&
	awk "{ printf \"%s\\r\\n\", \$0 }" long.txt >long-crlf.txt &&
	reflect-info long-crlf.txt >out2 &&
	diff -u out out2
'

test_done
