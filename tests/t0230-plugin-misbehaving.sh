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

test_done
