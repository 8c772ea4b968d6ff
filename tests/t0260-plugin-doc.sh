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

	test_expect_success 'the example mode.s man page renders without warnings' '
		groff -man -ww -z "$srcdir/doc/examples/reflect-mode-sphere.7" 2>warnings &&
		test_line_count 0 warnings
	'

	test_expect_success 'the rendered page has the sections an author needs' '
		groff -man -Tascii -P-c -P-b -P-u "$page" >page.txt 2>/dev/null &&
		for s in NAME SYNOPSIS DESCRIPTION CONCEPTS "ABI VERSIONS" \
			"FINDING MODES" "MAN PAGES OF MODES" "BUILDING AND INSTALLING" \
			DIAGNOSTICS EXAMPLE ENVIRONMENT FILES "SEE ALSO"
		do
			test_grep "^$s\$" page.txt || return 1
		done &&
		test_grep "REFLECT_PLUGIN_SYSTEM_PATH" page.txt &&
		test_grep "pkg-config --variable=plugindir reflect-plugin" page.txt &&
		test_grep "^ *RF_PLUGIN_DEFINE(descriptor)$" page.txt
	'
else
	test_skip 'groff -man -ww finds nothing to warn about' 'no groff'
	test_skip 'the example mode.s man page renders without warnings' 'no groff'
	test_skip 'the rendered page has the sections an author needs' 'no groff'
fi

# What is installed is read by authors who have only the installed
# tree: a file of the source tree (a benchmark, a test, a picture, the
# path-traced references beside it) is named only with where it lives.
# A paragraph of a page (between .PP, .TP, .IP, .SS, .SH), or an
# example file, that names one says "source tree".
pat='shared/truth|bench/|tests/|doc/[a-z-]*\.(md|png|dat)'

# unsaid PAGE: its paragraphs that break the rule, by their first line.
unsaid () {
	awk -v f="$1" -v pat="$pat" '
		function check() {
			if (para ~ pat && para !~ /source tree/)
				print f ": " first
			para = ""
			first = ""
		}
		/^\.(PP|TP|IP|SS|SH|LP|P)( |$)/ { check(); next }
		/^\.\\"/ { next }
		{
			para = para " " $0
			if (first == "" && $0 ~ pat)
				first = $0
		}
		END { check() }' "$srcdir/$1"
}

# unsaid_example FILE: the file, when it breaks the rule.
unsaid_example () {
	if grep -E "$pat" "$srcdir/$1" >/dev/null && ! grep "source tree" "$srcdir/$1" >/dev/null
	then
		echo "$1"
	fi
}

# names_truth PAGE: the page, when it names ../shared/truth.
names_truth () {
	if grep "\.\./shared/truth" "$srcdir/$1" >/dev/null
	then
		echo "$1"
	fi
}

test_expect_success 'installed docs name no file of the source tree without saying so' '
	sed -n "s|^	*\(doc/[a-z-]*\.[1357]\).*|\1|p" "$srcdir/doc/doc.am" >pages &&
	test $(wc -l <pages) -gt 20 &&
	grep -o "doc/examples/[a-zA-Z0-9./-]*" "$srcdir/doc/doc.am" | sort -u >examples &&
	test $(wc -l <examples) -ge 8 &&
	while read f
	do
		unsaid "$f" || return 1
	done <pages >bad &&
	while read f
	do
		unsaid_example "$f" || return 1
	done <examples >>bad &&
	cat bad &&
	test_line_count 0 bad &&
	while read f
	do
		names_truth "$f" || return 1
	done <pages >named &&
	echo doc/reflect-compare.1 >expect &&
	diff -u expect named
'

test_done
