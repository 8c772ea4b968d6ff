#!/bin/sh
test_description='bad input to the stream reader: one clear line, exit 1, no crash'
. "$srcdir/tests/lib.sh"

SQ="'"

# expect_bad FILE PATTERN TOOL [ARGS...]: TOOL [ARGS...] FILE exits with 1
# and prints exactly one line on stderr, "TOOL: 'FILE': " then PATTERN (a
# basic regex matching the rest of the line).
expect_bad () {
	file=$1 pattern=$2
	shift 2
	test_expect_code 1 "$@" "$file" >out 2>err &&
	test_one_line_message "$1" err &&
	test_grep "^$1: $SQ$file$SQ: $pattern\$" err
}

# header NCOLS NROWS NCOMP CHANNELS [FORMAT]: a float header by hand.
header () {
	printf '#?REFLECT1\nNCOLS=%s\nNROWS=%s\nNCOMP=%s\nCHANNELS=%s\n' \
		"$1" "$2" "$3" "$4" &&
	case ${5:-float} in
	float) printf 'BigEndian=0\nFORMAT=float\n\n' ;;
	*) printf 'FORMAT=%s\n\n' "$5" ;;
	esac
}

# A G-buffer header reflect-project takes (9 channels, a probe).
gbuffer_header () {
	printf '#?REFLECT1\nPROBE_BOX=-3 0 -2 3 3 2\nPROBE_CENTER=0 1.5 0\n' &&
	printf 'NCOLS=%s\nNROWS=%s\nNCOMP=9\n' "$1" "$2" &&
	printf 'CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z\n' &&
	printf 'BigEndian=0\nFORMAT=float\n\n'
}

# The bad inputs, one file each; the list of names is kept in "cases".
test_expect_success 'make the bad inputs' '
	{ printf "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n"; } >wrong-magic &&
	printf "P6\n2 2\n255\n" >not-a-header &&
	{ printf "#?REFLECT2\n"; header 1 1 1 a | sed 1d; } >newer-version &&
	{ printf "#?REFLECT1x\n"; header 1 1 1 a | sed 1d; } >bad-identifier &&
	header 2 2 3 "a b" >ncomp-mismatch &&
	header 2 2 3 "a b a" >duplicate-channel &&
	header 2 2 3 "a b c" >invalid-channel &&
	sed "s/^CHANNELS=.*/CHANNELS=a b=1 c/" invalid-channel >invalid-channel.tmp &&
	mv invalid-channel.tmp invalid-channel &&
	{ header 3 2 2 "a b" && head -c 32 /dev/zero; } >truncated-row &&
	{ header 3 2 2 "a b" && head -c 30 /dev/zero; } >truncated-float &&
	{ header 3 2 2 "a b" && head -c 24 /dev/zero; } >truncated-frame &&
	header 4194304 4194304 4194304 a >size-overflow &&
	header 99999999999999999999999 1 1 a >size-too-large &&
	header 2 ten 1 a >size-not-a-number &&
	header 2 12abc 1 a >size-trailing-junk &&
	header -4 2 1 a >size-negative &&
	header 0 2 1 a >size-zero &&
	header 2 2 1 a | sed /^FORMAT=/d >missing-format &&
	header 2 2 1 a | sed /^NCOLS=/d >missing-ncols &&
	header 2 2 1 a | sed /^BigEndian=/d >missing-bigendian &&
	header 2 2 1 a | sed "s/^BigEndian=0/BigEndian=yes/" >bad-bigendian &&
	printf "#?REFLECT1\nNCOLS=2\nNROWS=2\nNCOLS=3\nNCOMP=1\nCHANNELS=a\n" \
		>duplicate-key &&
	printf "BigEndian=0\nFORMAT=float\n\n" >>duplicate-key &&
	long=$(awk "BEGIN { while (n++ < 2044) printf \"x\" }") &&
	{ printf "#?REFLECT1\nLONG=%s\n" "$long" && header 1 1 1 a | sed 1d; } >long-line &&
	: >empty &&
	LC_ALL=C awk "BEGIN { x = 1; for (i = 0; i < 8192; i++) {
		x = (x * 75 + 74) % 65537; printf \"%c\", x % 255 + 1 } }" |
	head -c 4096 >garbage &&
	test "$(wc -c <garbage)" -eq 4096 &&
	{ printf "#?REFLECT1\n" && cat garbage; } >garbage-after-magic &&
	header 2 2 1 a | sed "\$d" >unclosed-header &&
	header 2 2 1 a double >format-double &&
	{ header 2 2 1 a ascii && printf "1 2\nx 4\n"; } >ascii-not-a-number &&
	{ header 2 2 1 a ascii && printf "1 2\n3\n"; } >ascii-truncated &&
	{ header 1 1 2 "a b" && head -c 12 /dev/zero; } >extra-data &&
	printf "#?REFLECT1\nNCOLS=2\tNROWS=1\n\n" >tab-in-value &&
	{ header 1 1 1 a && head -c 4 /dev/zero &&
	  header 1 2 1 b && head -c 6 /dev/zero; } >truncated-second-frame &&
	{ gbuffer_header 3 2 && head -c 150 /dev/zero; } >gbuffer-truncated &&
	wc -c truncated-row truncated-float long-line &&
	test "$(sed -n 2p long-line | wc -c)" -eq 2050
'

cases='wrong-magic not-a-header newer-version bad-identifier ncomp-mismatch
duplicate-channel invalid-channel truncated-row truncated-float
truncated-frame size-overflow size-too-large size-not-a-number
size-trailing-junk size-negative size-zero missing-format missing-ncols
missing-bigendian bad-bigendian duplicate-key long-line empty garbage
garbage-after-magic unclosed-header format-double ascii-not-a-number
ascii-truncated extra-data tab-in-value truncated-second-frame'

test_expect_success 'wrong magic' '
	{ printf "#?NOTREFLECT\nFORMAT=ascii\n\n"; } >other-magic &&
	expect_bad other-magic \
		"not a reflect stream: expected $SQ#?REFLECT1$SQ, got $SQ#?NOTREFLECT$SQ" \
		reflect-info &&
	expect_bad wrong-magic \
		"not a reflect stream: it is a Radiance HDR image; reflect-import reads images into streams, and --env takes environments" \
		reflect-info &&
	expect_bad not-a-header \
		"not a reflect stream: expected $SQ#?REFLECT1$SQ at the start" \
		reflect-info
'

# reflect-import reads no DDS or KTX cube: the message sends those to
# the tools that read environments, and shows that they do.
test_expect_success 'a DDS or KTX cube where a stream goes' '
	reflect-prefilter --size=8 -o cube.ktx &&
	reflect-prefilter --size=8 -o cube.ktx2 &&
	"$builddir/tests/mkdds" cube.dds 8 1 &&
	for f in cube.dds cube.ktx cube.ktx2
	do
		test_expect_code 1 reflect-info $f 2>err &&
		test_one_line_message reflect-info err &&
		test_grep "not a reflect stream: it is a \(DDS\|KTX\|KTX 2\) image; DDS and KTX cubes are environments: reflect-prefilter reads them, and reflect-shade --env takes them$" err &&
		test_expect_code 1 reflect-info <$f 2>err &&
		test_grep "reflect-prefilter reads them" err &&
		! grep reflect-import err &&
		reflect-prefilter $f >env.rfl &&
		reflect-gbuffer -x 4 -y 4 | reflect-project |
			reflect-shade --env=$f >shaded.rfl &&
		test -s env.rfl && test -s shaded.rfl || return 1
	done
'

test_expect_success 'newer version' '
	expect_bad newer-version \
		"stream version 2 is newer than this reader${SQ}s (1); upgrade reflect" \
		reflect-info &&
	expect_bad bad-identifier \
		"bad stream identifier $SQ#?REFLECT1x$SQ" reflect-info
'

test_expect_success 'NCOMP not matching CHANNELS' '
	expect_bad ncomp-mismatch "NCOMP=3 but CHANNELS names 2 channels" reflect-info
'

test_expect_success 'duplicate and invalid channel names' '
	expect_bad duplicate-channel \
		"CHANNELS: channel ${SQ}a$SQ is named twice" reflect-info &&
	expect_bad invalid-channel \
		"CHANNELS: ${SQ}b=1$SQ is not a valid channel name (1 to 63 printable characters, no $SQ,$SQ or $SQ=$SQ)" \
		reflect-info
'

test_expect_success 'data truncated in the middle of a row' '
	expect_bad truncated-row \
		"data ends in the middle of row 2 of 2 (pixel 2 of 3)" reflect-info &&
	test_grep "^	NCOLS=3$" out
'

test_expect_success 'data truncated in the middle of a float' '
	expect_bad truncated-float \
		"data ends inside a float in row 2 of 2 (pixel 1 of 3, channel ${SQ}b$SQ)" \
		reflect-info
'

test_expect_success 'data truncated at the end of a row' '
	expect_bad truncated-frame "data ends after row 1 of 2" reflect-info
'

test_expect_success 'the same errors when the rows are read (-s)' '
	expect_bad truncated-row \
		"data ends in the middle of row 2 of 2 (pixel 2 of 3)" reflect-info -s &&
	expect_bad truncated-float \
		"data ends inside a float in row 2 of 2 (pixel 1 of 3, channel ${SQ}b$SQ)" \
		reflect-info -s
'

test_expect_success 'NCOLS*NROWS*NCOMP overflowing size_t' '
	expect_bad size-overflow \
		"NCOLS\*NROWS\*NCOMP (4194304\*4194304\*4194304) overflows the size of memory" \
		reflect-info &&
	expect_bad size-too-large \
		"header line 2: NCOLS is too large (${SQ}99999999999999999999999$SQ)" \
		reflect-info
'

test_expect_success 'non-numeric size' '
	expect_bad size-not-a-number \
		"header line 3: NROWS is not a number (${SQ}ten$SQ)" reflect-info &&
	expect_bad size-trailing-junk \
		"header line 3: NROWS is not a number (${SQ}12abc$SQ)" reflect-info
'

test_expect_success 'negative and zero size' '
	expect_bad size-negative \
		"header line 2: NCOLS is negative (${SQ}-4$SQ)" reflect-info &&
	expect_bad size-zero "header line 2: NCOLS must be at least 1" reflect-info
'

test_expect_success 'missing FORMAT, NCOLS, BigEndian' '
	expect_bad missing-format "header has no FORMAT line" reflect-info &&
	expect_bad missing-ncols "header has no NCOLS line" reflect-info &&
	expect_bad missing-bigendian \
		"header has no BigEndian line for float data" reflect-info
'

test_expect_success 'bad BigEndian value, a key given twice' '
	expect_bad bad-bigendian \
		"header line 6: BigEndian must be 0 or 1, not ${SQ}yes$SQ" reflect-info &&
	expect_bad duplicate-key "header line 4: NCOLS given twice" reflect-info
'

test_expect_success 'a header line over 2048 bytes' '
	expect_bad long-line "header line 2 is longer than 2048 bytes" reflect-info
'

test_expect_success 'empty input' '
	expect_bad empty "empty input: no stream header" reflect-info &&
	test_expect_code 1 reflect-info <empty 2>err &&
	test_one_line_message reflect-info err &&
	test_grep "^reflect-info: $SQ<stdin>$SQ: empty input: no stream header$" err
'

test_expect_success 'binary garbage' '
	expect_bad garbage \
		"not a reflect stream: expected $SQ#?REFLECT1$SQ at the start" \
		reflect-info &&
	expect_bad garbage-after-magic "header line 2 holds binary data" reflect-info
'

test_expect_success 'header without the closing empty line' '
	expect_bad unclosed-header \
		"header ends at line 8 without the empty line that closes it" reflect-info
'

test_expect_success 'unsupported FORMAT=double' '
	expect_bad format-double \
		"header line 6: FORMAT ${SQ}double$SQ is not supported (float or ascii)" \
		reflect-info
'

test_expect_success 'ascii data with a non-number' '
	expect_bad ascii-not-a-number \
		"ascii data: ${SQ}x$SQ is not a number (row 2 of 2, pixel 1 of 2, channel ${SQ}a$SQ)" \
		reflect-info -s &&
	expect_bad ascii-not-a-number \
		"ascii data: ${SQ}x$SQ is not a number (row 2 of 2, pixel 1 of 2, channel ${SQ}a$SQ)" \
		reflect-info &&
	expect_bad ascii-truncated \
		"data ends in the middle of row 2 of 2 (pixel 2 of 2)" reflect-info
'

test_expect_success 'more data than the header said' '
	expect_bad extra-data \
		"frame 2: not a reflect stream: expected $SQ#?REFLECT1$SQ at the start of the frame (more data than the previous header said?)" \
		reflect-info
'

test_expect_success 'errors in a later frame name the frame' '
	expect_bad truncated-second-frame \
		"frame 2: data ends inside a float in row 2 of 2 (pixel 1 of 1, channel ${SQ}b$SQ)" \
		reflect-info &&
	test_grep "^frame 2:$" out
'

# Found by tests/fuzz/fuzz-header: a tab in a header value went into the
# message as it was.
test_expect_success 'messages hold no control characters (fuzz regression)' '
	expect_bad tab-in-value \
		"header line 2: NCOLS is not a number (${SQ}2?NROWS=1$SQ)" reflect-info &&
	tab=$(printf "\t") &&
	! grep "$tab" err
'

test_expect_success 'headerless input too short' '
	head -c 10 /dev/zero >short.raw &&
	expect_bad short.raw \
		"data ends inside a float in row 2 of 2 (pixel 1 of 2, channel ${SQ}c0$SQ)" \
		reflect-info -s -H -x 2 -y 2 -c 1 &&
	expect_bad empty "empty input" reflect-info -H -x 2 -y 2 -c 1
'

test_expect_success 'bad input through reflect-project' '
	for f in wrong-magic newer-version ncomp-mismatch duplicate-channel \
		size-overflow size-negative missing-format long-line empty garbage \
		unclosed-header format-double
	do
		reflect-info $f >/dev/null 2>info.err
		test_expect_code 1 reflect-project $f >out 2>err &&
		test_one_line_message reflect-project err &&
		sed "s/^reflect-info:/reflect-project:/" info.err >expect &&
		cmp expect err &&
		test ! -s out || return 1
	done
'

test_expect_success 'truncated data through reflect-project' '
	expect_bad gbuffer-truncated \
		"data ends inside a float in row 2 of 2 (pixel 2 of 3, channel ${SQ}P.Y$SQ)" \
		reflect-project
'

test_expect_success 'truncated data through reflect-export' '
	expect_bad truncated-float \
		"data ends inside a float in row 2 of 2 (pixel 1 of 3, channel ${SQ}b$SQ)" \
		reflect-export -o out.exr -c a,b
'

# A pipe cut in the middle of a frame, while the stage still computes the
# block before: the writer thread used to give up on the failed read and
# leave the main thread waiting for it forever (25 hangs in 30 runs).  A
# run is bounded, so a hang fails the step at once.
test_expect_success 'truncated piped input ends every stream tool' '
	reflect-gbuffer -x 320 -y 180 >gbuffer &&
	head -c 4000000 gbuffer >gbuffer-cut &&
	reflect-project gbuffer >projected &&
	head -c 6000000 projected >projected-cut &&
	for i in 1 2 3 4 5 6 7 8 9 10
	do
		test_expect_code 1 timeout 20 sh -c "cat gbuffer-cut | reflect-project" \
			>/dev/null 2>err &&
		test_grep "^reflect-project: ${SQ}<stdin>${SQ}: data ends" err &&
		test_expect_code 1 timeout 20 sh -c "cat projected-cut | reflect-shade --size=8" \
			>/dev/null 2>err &&
		test_grep "^reflect-shade: ${SQ}<stdin>${SQ}: data ends" err &&
		test_expect_code 1 timeout 20 sh -c "cat projected-cut | reflect-export -c D -o out.png" \
			>/dev/null 2>err &&
		test_grep "^reflect-export: ${SQ}<stdin>${SQ}: data ends" err || return 1
	done
'

# A file truncated while a tool reads it where it lies (mapped): the
# tool's output pipe is full, so it waits with a block mapped and not
# yet read; the file then loses those pages, and reading on used to end
# the tool with a bare SIGBUS (status 135).
test_expect_success 'a mapped input that shrinks ends the tool with a message' '
	reflect-gbuffer -x 1000 -y 1000 | reflect-project >big.rfl &&
	reflect-prefilter --size=8 >env.rfl &&
	for tool in reflect-project "reflect-shade --env=env.rfl"
	do
		cp big.rfl shrinks.rfl &&
		{ timeout 60 $tool shrinks.rfl 2>err; echo $? >status; } |
		{ sleep 2 && truncate -s 1000 shrinks.rfl && cat >/dev/null; } &&
		echo 1 >expect && cmp expect status &&
		test_one_line_message "${tool%% *}" err &&
		test_grep "${SQ}shrinks.rfl${SQ}.*: the file shrank while it was read" err || return 1
	done
'

# Every bad input under valgrind: the exit status stays 1 and the tool
# says why (99 would be a memory error or a leak).  Valgrind exits 1 too
# when it cannot run a program (clang's DWARF 5 on valgrind 3.19), so a
# bare 1 proves nothing: the tool's own message must be there, and a
# valgrind that cannot run the tools skips these tests with its reason.
valgrind_bad () {
	"$builddir/libtool" --mode=execute \
		$VALGRIND -q --error-exitcode=99 --leak-check=full "$@" >/dev/null 2>err
	got=$?
	if test "$got" -ne 1 || ! grep "^$(basename "$1"): " err >/dev/null
	then
		echo "expected exit status 1 and a message under valgrind, got $got: $*" >&2
		cat err >&2
		return 1
	fi
}

valgrind_reason=
if test -n "$VALGRIND" &&
	! "$builddir/libtool" --mode=execute $VALGRIND -q --error-exitcode=99 \
		"$builddir/bin/reflect-info" -V >/dev/null 2>valgrind.err
then
	valgrind_reason="valgrind cannot run the tools: $(head -n 1 valgrind.err)"
	VALGRIND=
fi

if test -n "$VALGRIND"
then
	# Without -s the rows are skipped, with -s they are read.
	test_expect_success 'every bad input under valgrind (reflect-info)' '
		for f in $cases
		do
			valgrind_bad "$builddir/bin/reflect-info" $f || return 1
		done
	'
	test_expect_success 'every bad input under valgrind (reflect-info -s)' '
		for f in $cases
		do
			valgrind_bad "$builddir/bin/reflect-info" -s $f || return 1
		done
	'
	test_expect_success 'bad input under valgrind (reflect-project)' '
		for f in wrong-magic newer-version size-overflow long-line garbage \
			unclosed-header format-double gbuffer-truncated
		do
			valgrind_bad "$builddir/bin/reflect-project" -j 2 $f || return 1
		done
	'
	# Data that ends early, read from a file (mapped) and from a pipe
	# (read ahead on a thread): every thread is gone before the exit.
	test_expect_success 'bad and truncated input under valgrind (reflect-shade, reflect-export)' '
		for f in wrong-magic size-overflow garbage unclosed-header
		do
			valgrind_bad "$builddir/bin/reflect-shade" -j 2 --size=8 $f || return 1
		done &&
		# Three blocks of rows: the last one fails after the threads
		# of the first two have started.
		reflect-gbuffer -x 1500 -y 60 | reflect-project >whole &&
		size=$(wc -c <whole) &&
		head -c $((size - 1000)) whole >shade-truncated &&
		valgrind_bad "$builddir/bin/reflect-shade" -j 2 --size=8 shade-truncated &&
		test_grep "data ends" err &&
		cat shade-truncated | valgrind_bad "$builddir/bin/reflect-shade" -j 2 --size=8 &&
		test_grep "data ends" err &&
		valgrind_bad "$builddir/bin/reflect-export" -o out.exr -c D shade-truncated &&
		test_grep "data ends" err &&
		cat shade-truncated | valgrind_bad "$builddir/bin/reflect-export" -o out.exr -c D &&
		test_grep "data ends" err
	'
else
	for t in 'every bad input under valgrind (reflect-info)' \
		'every bad input under valgrind (reflect-info -s)' \
		'bad input under valgrind (reflect-project)' \
		'bad and truncated input under valgrind (reflect-shade, reflect-export)'
	do
		test_skip "$t" "${valgrind_reason:-no valgrind}"
	done
fi

# An image given where a stream goes: its format named, and the tool that
# reads images.
# An image where a stream is read is read as an image (reflect-stream(5)):
# a broken one is an error of the image, naming the file.
test_expect_success 'a broken image for a stream: one line, naming the file' '
	printf "\x89PNG\r\n\x1a\n\0\0\0\rIHDR" >image.png &&
	printf "\x76\x2f\x31\x01\x02\0\0\0channels" >image.exr &&
	printf "\xff\xd8\xff\xe0\0\x10JFIF" >image.jpg &&
	for f in image.png image.exr image.jpg
	do
		test_expect_code 1 reflect-export -o out.png $f 2>err &&
		test_one_line_message reflect-export err &&
		test_grep "cannot \(read\|open\) .$f." err ||
		return 1
	done &&
	# standard input is a stream: an image there gets the hint
	test_expect_code 1 reflect-info <image.png 2>err &&
	test_grep "not a reflect stream: it is a PNG image; reflect-import reads images into streams" err
'

test_done
