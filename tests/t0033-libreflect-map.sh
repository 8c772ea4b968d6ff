#!/bin/sh
test_description='libreflect(3) maps every public function, and none that is gone'
. "$srcdir/tests/lib.sh"

page="$srcdir/doc/libreflect.3"

# declared: every function an installed header declares
declared () {
	cat "$srcdir"/include/reflect/*.h |
	tr '\n' ' ' | sed 's/;/;\n/g' |
	sed -n 's/.*RF_EXTERN[^(]*[^a-z0-9_]\(rf_[a-z0-9_]*\) *(.*/\1/p' |
	sort -u
}

# mapped: every function the page names in its header sections
mapped () {
	sed -n 's/^\.BR \(rf_[a-z0-9_]*\) [,.;]*$/\1/p' "$page" | sort -u
}

test_expect_success 'the headers declare functions, the page maps some' '
	declared >declared &&
	mapped >mapped &&
	test $(wc -l <declared) -gt 200 &&
	test -s mapped
'

test_expect_success 'every public function is on the page' '
	comm -23 declared mapped >missing &&
	cat missing &&
	! test -s missing
'

test_expect_success 'every function on the page is still declared' '
	comm -13 declared mapped >stale &&
	cat stale &&
	! test -s stale
'

test_expect_success 'a function left off the page is seen' '
	grep -v "^\.BR rf_reader_open ,$" "$page" >page &&
	sed -n "s/^\.BR \(rf_[a-z0-9_]*\) [,.;]*$/\1/p" page | sort -u >fewer &&
	comm -23 declared fewer >missing &&
	test "$(cat missing)" = rf_reader_open
'

test_done
