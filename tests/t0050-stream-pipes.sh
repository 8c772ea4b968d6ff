#!/bin/sh
test_description='a stream given by a path that is a pipe: read whole, its first bytes included'
. "$srcdir/tests/lib.sh"

# A stream tool looks at the first bytes of a path to tell a stream from
# an image.  Looking at them through stdio and rewinding lost stdio's
# first 4 KB on a pipe, where rewind cannot go back: the header went, and
# the tool said the input was no stream.

test_expect_success 'the stream: a frame much longer than 4 KB' '
	reflect-gbuffer -x 40 -y 30 >frame.rfl &&
	test $(wc -c <frame.rfl) -gt 20000 &&
	reflect-export -c all -o want.exr frame.rfl &&
	reflect-project -h frame.rfl >want
'

test_expect_success 'a FIFO' '
	mkfifo fifo &&
	{ cat frame.rfl >fifo & } &&
	timeout 20 reflect-project -h fifo >got &&
	cmp want got
'

test_expect_success '/dev/stdin and /dev/fd/0 on a pipe' '
	cat frame.rfl | timeout 20 reflect-project -h /dev/stdin >got1 &&
	cmp want got1 &&
	cat frame.rfl | timeout 20 reflect-export -c all -o got.exr /dev/fd/0 &&
	cmp want.exr got.exr
'

test_expect_success 'a process substitution, where a shell has one' '
	if command -v bash >/dev/null
	then
		timeout 20 bash -c "reflect-info <(cat frame.rfl)" >info &&
		test_grep "^	NCOLS=40$" info
	fi
'

test_expect_success 'a stream shorter than what is looked at' '
	printf "#?REF" >short.rfl &&
	cat short.rfl | test_expect_code 1 reflect-info /dev/stdin 2>err &&
	test_one_line_message reflect-info err
'

test_expect_success 'a regular file as /dev/stdin: read from its start' '
	reflect-project -h /dev/stdin <frame.rfl >got2 &&
	cmp want got2
'

test_expect_success 'an image in a FIFO: refused, since decoders read files' '
	mkfifo img.fifo &&
	{ cat want.exr >img.fifo & } &&
	test_expect_code 1 timeout 20 reflect-info img.fifo 2>err &&
	test_one_line_message reflect-info err &&
	test_grep "not a regular file (a FIFO)" err
'

test_done
