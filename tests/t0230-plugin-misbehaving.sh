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

test_done
