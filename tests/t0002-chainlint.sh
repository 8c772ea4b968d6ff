#!/bin/sh
test_description='every loop in a test body ends its last command with || return 1 (tests/chainlint.sh)'
. "$srcdir/tests/lib.sh"

# The linter must catch what it is for, or it tests nothing.
test_expect_success 'chainlint finds a loop whose failure would be lost' '
	{
		echo "test_expect_success \"lost\" '\''" &&
		printf "\tfor a in 1 2\n\tdo\n\t\tfalse\n\tdone\n" &&
		echo "'\''"
	} >lost.sh &&
	test_expect_code 1 sh "$srcdir/tests/chainlint.sh" lost.sh >out &&
	test_grep "^lost.sh:5: the loop ending here" out &&
	{
		echo "test_expect_success \"kept\" '\''" &&
		printf "\tfor a in 1 2\n\tdo\n\t\tfalse || return 1\n\tdone\n" &&
		echo "'\''"
	} >kept.sh &&
	sh "$srcdir/tests/chainlint.sh" kept.sh
'

test_expect_success 'the suite keeps the rule' '
	sh "$srcdir/tests/chainlint.sh" "$srcdir"/tests/t*.sh
'

test_done
