#!/bin/sh
test_description='reflect-shade(1) and the mode pages document every option and parameter'
. "$srcdir/tests/lib.sh"

# documented PAGE WORD...: the page (roff, dashes escaped) names each.
documented () {
	page=$1
	shift
	missing=
	for w
	do
		roff=$(printf "%s" "$w" | sed "s/-/\\\\\\\\-/g")
		grep -e "$roff" "$page" >/dev/null || missing="$missing $w"
	done
	if test -n "$missing"
	then
		echo "$page does not document:$missing" >&2
		return 1
	fi
}

test_expect_success 'reflect-shade(1) documents every option of its usage line' '
	usage_options reflect-shade >options &&
	test $(wc -l <options) -gt 20 &&
	documented "$srcdir/doc/reflect-shade.1" $(cat options) --help
'

test_expect_success 'every mode reflect-shade lists has a page with each of its parameters' '
	reflect-shade -l >list &&
	awk "/^[a-z]/ { print \$1 }" list >modes &&
	test $(wc -l <modes) -ge 4 &&
	while read -r m
	do
		page="$srcdir/doc/reflect-mode-$m.7" &&
		test -f "$page" &&
		params=$(awk -v m="$m" "
			/^[a-z]/ { cur = \$1 }
			cur == m && /^    [a-z_]+=/ { sub(/^ +/, \"\"); sub(/=.*/, \"\"); print }
		" list) &&
		writes=$(awk -v m="$m" "
			/^[a-z]/ { cur = \$1 }
			cur == m && /^  writes: / { sub(/^  writes: /, \"\"); print }
		" list) &&
		test -n "$writes" &&
		documented "$page" $params "$m" $writes &&
		grep -e "reflect\\\\-mode\\\\-$m" "$srcdir/doc/reflect-shade.1" >/dev/null ||
		return 1
	done <modes
'

test_expect_success 'the pages give the defaults the plugins have' '
	grep -e "default 1" "$srcdir/doc/reflect-mode-approx.7" &&
	grep -e "default 6" "$srcdir/doc/reflect-mode-approx.7" &&
	grep -e "default 4" "$srcdir/doc/reflect-mode-godot.7" &&
	grep -e "^    clamp=1	" list &&
	grep -e "^    power=4	" list
'

test_done
