#!/bin/sh
test_description='image and environment paths that are no regular file: refused at once, never a hang'
. "$srcdir/tests/lib.sh"

SQ="'"

# refused TOOL ARGS...: exits 1 within 20 s with one line on stderr that
# names the path and says it is no regular file (or, for a FIFO nobody
# writes to, that it is empty).  OpenImageIO's probes read /dev/zero for
# ever, and opening a FIFO waits for a writer: each ran until killed.
refused () {
	test_expect_code 1 timeout 20 "$@" >out 2>err </dev/null &&
	test_one_line_message "$1" err &&
	test ! -s out
}

test_expect_success 'the inputs: a FIFO nobody writes to, a directory, a frame' '
	mkfifo fifo &&
	mkfifo fifo.dds &&
	mkdir dir &&
	reflect-gbuffer -x 8 -y 6 | reflect-project >frame.rfl
'

test_expect_success 'reflect-shade --env' '
	refused reflect-shade --env=/dev/zero frame.rfl &&
	test_grep "cannot open ${SQ}/dev/zero${SQ}: not a regular file (a character device)" err &&
	refused reflect-shade --env=dir frame.rfl &&
	test_grep "cannot open ${SQ}dir${SQ}: not a regular file (a directory)" err &&
	refused reflect-shade --env=fifo frame.rfl &&
	test_grep "${SQ}fifo${SQ}: empty input" err &&
	refused reflect-shade --env=fifo.dds frame.rfl &&
	test_grep "cannot open ${SQ}fifo.dds${SQ}: not a regular file (a FIFO)" err
'

test_expect_success 'a pipe that carries a stream is an environment' '
	reflect-prefilter --size=8 >env.rfl &&
	reflect-shade -h --env=env.rfl frame.rfl >want &&
	cat env.rfl | timeout 20 reflect-shade -h --env=/dev/stdin frame.rfl >got &&
	cmp want got
'

test_expect_success 'PROBE_ENV names a file, never standard input' '
	for v in - /dev/zero fifo dir /dev/stdin
	do
		sed "s|^PROBE_ENV=.*|PROBE_ENV=$v|" frame.rfl >named.rfl &&
		refused reflect-shade named.rfl || return 1
	done &&
	sed "s|^PROBE_ENV=.*|PROBE_ENV=-|" frame.rfl >named.rfl &&
	refused reflect-shade named.rfl &&
	test_grep "PROBE_ENV ${SQ}-${SQ}: a stream${SQ}s header cannot name standard input" err
'

test_expect_success 'reflect-prefilter' '
	refused reflect-prefilter /dev/zero &&
	test_grep "not a regular file (a character device)" err &&
	refused reflect-prefilter fifo &&
	refused reflect-prefilter dir
'

test_expect_success 'reflect-import' '
	refused reflect-import /dev/zero &&
	test_grep "cannot open ${SQ}/dev/zero${SQ}: not a regular file (a character device)" err &&
	refused reflect-import fifo &&
	test_grep "not a regular file (a FIFO)" err &&
	refused reflect-import dir
'

test_expect_success 'a scene normal map' '
	for f in /dev/zero fifo dir
	do
		printf "probe box -5 -5 -5 5 5 5\nsphere center 0 0 -2 radius 0.5 normalmap image %s\n" \
			$f >s.scene &&
		refused reflect-gbuffer -x 4 -y 4 s.scene &&
		test_grep "not a regular file" err || return 1
	done
'

test_done
