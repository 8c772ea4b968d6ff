#!/bin/sh
test_description='reflect-plugin(7) renders without warnings and shows sphere.c as it is'
. "$srcdir/tests/lib.sh"

page=$srcdir/doc/reflect-plugin.7

test_expect_success 'the listing in the page is doc/examples/sphere.c, escaped for roff' '
	sed -n "/^\.\\\\\" BEGIN sphere\.c$/,/^\.\\\\\" END sphere\.c$/p" "$page" |
		sed "1d;\$d" >listing &&
	test_line_count $(wc -l <"$srcdir/doc/examples/sphere.c") listing &&
	cat >escape.sed <<-\EOF &&
	s/\\/\\e/g
	s/-/\\-/g
	s/'"'"'/\\(aq/g
	s/`/\\(ga/g
	s/\^/\\(ha/g
	s/~/\\(ti/g
	s/^\./\\\&./
	EOF
	sed -f escape.sed "$srcdir/doc/examples/sphere.c" >expect &&
	diff -u expect listing
'

if command -v groff >/dev/null 2>&1
then
	test_expect_success 'groff -man -ww finds nothing to warn about' '
		groff -man -ww -z "$page" 2>warnings &&
		test_line_count 0 warnings
	'

	test_expect_success 'the rendered page has the sections an author needs' '
		groff -man -Tascii -P-c -P-b -P-u "$page" >page.txt 2>/dev/null &&
		for s in NAME SYNOPSIS DESCRIPTION CONCEPTS "ABI VERSIONS" \
			"FINDING MODES" "BUILDING AND INSTALLING" DIAGNOSTICS \
			EXAMPLE ENVIRONMENT FILES "SEE ALSO"
		do
			test_grep "^$s\$" page.txt || return 1
		done &&
		test_grep "REFLECT_PLUGIN_SYSTEM_PATH" page.txt &&
		test_grep "pkg-config --variable=plugindir reflect-plugin" page.txt &&
		test_grep "^ *RF_PLUGIN_DEFINE(descriptor)$" page.txt
	'
else
	test_skip 'groff -man -ww finds nothing to warn about' 'no groff'
	test_skip 'the rendered page has the sections an author needs' 'no groff'
fi

test_done
