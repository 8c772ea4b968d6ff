#!/bin/sh
test_description='tests/lib.sh: a step whose &&-chain is broken fails, whatever its commands return'
. "$srcdir/tests/lib.sh"

# A test file is run as the suite runs one, its trash directory under
# this one; steps are written in double quotes, as the file is written
# from inside a step.
run_file () {
	builddir=$PWD sh "$1" >out 2>err
}

test_expect_success 'a command that does not chain on fails its step' '
	cat >lost.sh <<-\EOF &&
	. "$srcdir/tests/lib.sh"
	test_expect_success "lost" "
		false
		true
	"
	test_done
	EOF
	test_expect_code 1 run_file lost.sh &&
	test_grep "^not ok 1 - lost$" out &&
	test_grep "^# broken &&-chain: a command of this step does not end with &&" out &&
	test_grep "^#  false$" out
'

test_expect_success 'so does one whose commands all succeed' '
	cat >kept.sh <<-\EOF &&
	. "$srcdir/tests/lib.sh"
	test_expect_success "newline" "
		true
		true
	"
	test_expect_success "semicolon" "
		true; true
	"
	test_expect_success "background" "
		true &
		wait
	"
	test_done
	EOF
	test_expect_code 1 run_file kept.sh &&
	test_grep "^not ok 1 - newline$" out &&
	test_grep "^not ok 2 - semicolon$" out &&
	test_grep "^not ok 3 - background$" out &&
	test $(grep -c "^# broken &&-chain" out) -eq 3
'

test_expect_success 'whole chains pass: here-documents, loops, comments, blocks' '
	cat >whole.sh <<-\EOF &&
	. "$srcdir/tests/lib.sh"
	test_expect_success "whole" "
		cat >f <<-EOT &&
		a line
		EOT
		# a comment between two commands
		for i in 1 2
		do
			test -f f || return 1
		done &&

		(cd . && test -f f) &&
		if test -f f
		then
			echo yes
		fi &&
		{ echo a; echo b; } | sort >/dev/null
	"
	test_done
	EOF
	run_file whole.sh &&
	test_grep "^ok 1 - whole$" out &&
	! grep "broken" out
'

test_expect_success 'a whole chain that fails is a plain failure, with its log' '
	cat >fails.sh <<-\EOF &&
	. "$srcdir/tests/lib.sh"
	test_expect_success "fails" "
		echo before &&
		false &&
		echo after
	"
	test_done
	EOF
	test_expect_code 1 run_file fails.sh &&
	test_grep "^not ok 1 - fails$" out &&
	test_grep "^# before$" out &&
	! grep "after\|broken" out
'

test_done
