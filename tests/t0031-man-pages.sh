#!/bin/sh
test_description='the man pages render cleanly and document every option'
. "$srcdir/tests/lib.sh"

if command -v groff >/dev/null 2>&1
then
	for page in "$srcdir"/doc/*.[157]
	do
		name=$(basename "$page")
		test_expect_success "$name renders without warnings" '
			groff -man -ww -z "$page" 2>err &&
			! test -s err
		'
	done
else
	test_skip 'the pages render without warnings' 'no groff'
fi

for tool in reflect-info reflect-project reflect-export reflect-accumulate reflect-filter reflect-capture reflect-trace reflect-montage reflect-join \
	reflect-occlude reflect-compare reflect-report
do
	test_expect_success "$tool(1) documents every option of its usage line" '
		page="$srcdir/doc/$tool.1" &&
		usage_options $tool >options &&
		test -s options &&
		echo --help >>options &&
		missing= &&
		while read -r opt
		do
			roff=$(printf "%s" "$opt" | sed "s/-/\\\\\\\\-/g") || return 1
			grep -e "$roff" "$page" >/dev/null || missing="$missing $opt" || return 1
		done <options &&
		if test -n "$missing"
		then
			echo "$page does not document:$missing" >&2
			false
		fi
	'
done

test_expect_success 'every page is installed (in a dist_man_MANS)' '
	for page in "$srcdir"/doc/*.[157]
	do
		cat "$srcdir"/Makefile.am "$srcdir"/*/*.am |
		grep -e "doc/$(basename "$page")" >/dev/null || {
			echo "$page is in no dist_man_MANS" >&2
			exit 1
		}
	done
'

test_done
