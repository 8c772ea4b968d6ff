#!/bin/sh
test_description='the library is built in layers: no area includes one above it'
. "$srcdir/tests/lib.sh"

# The order is lib/README's "layers:" line, bottom first.  An include of
# "AREA/..." or of an area's public header "reflect/NAME.h" from a file
# of lib/AREA2/ is an arrow; it must not point up, nor anywhere outside
# the areas (plugins/ least of all).

layers=$(sed -n 's/^ *layers: //p' "$srcdir/lib/README")

# area_of_header NAME: the area whose public header reflect/NAME is
area_of_header () {
	case $1 in
	reflect.h|version.h) echo util ;;
	plugin.h|probe.h) echo probe ;;
	scene.h|import.h) echo scene ;;
	host.h) echo plugin ;;
	shading.h) echo shade ;;
	surface.h) echo surface ;;
	*) echo "${1%.h}" ;;
	esac
}

# rank AREA: its place in layers, or nothing
rank () {
	i=0
	for a in $layers
	do
		test "$a" = "$1" && { echo $i; return 0; }
		i=$((i + 1))
	done
}

# arrows: every include in lib/ as "FILE AREA TARGET-AREA"
arrows () {
	for f in "$srcdir"/lib/*/*.c "$srcdir"/lib/*/*.h "$srcdir"/lib/*/*.cpp
	do
		test -f "$f" || continue
		from=$(basename "$(dirname "$f")")
		sed -n 's/^#[ 	]*include[ 	]*"\([^"]*\)".*/\1/p' "$f" |
		while read -r inc
		do
			case $inc in
			reflect/*) to=$(area_of_header "${inc#reflect/}") ;;
			*/*) to=${inc%%/*} ;;
			*) continue ;;
			esac
			echo "${f#$srcdir/} $from $to $inc"
		done || return 1
	done
}

test_expect_success 'lib/README names the layers, and every folder of lib/ is one' '
	test -n "$layers" &&
	for d in "$srcdir"/lib/*/
	do
		a=$(basename "$d") &&
		if test -z "$(rank "$a")"
		then
			echo "lib/$a/ is not in lib/README'"'"'s layers" &&
			false
		fi || return 1
	done
'

test_expect_success 'no include runs up a layer or out of lib/' '
	arrows >arrows &&
	test -s arrows &&
	: >bad &&
	while read -r file from to inc
	do
		rf=$(rank "$from") &&
		rt=$(rank "$to") &&
		if test -z "$rt"
		then
			echo "$file includes $inc: not an area of lib/" >>bad
		elif test "$rt" -gt "$rf"
		then
			echo "$file includes $inc: $from is below $to" >>bad
		fi || return 1
	done <arrows &&
	cat bad &&
	! test -s bad
'

test_expect_success 'the check sees an arrow up, and one into plugins/' '
	printf "%s\n" "lib/util/x.c util shade reflect/shading.h" \
		"lib/shade/y.c shade project project/projection.h" >fake &&
	: >bad &&
	while read -r file from to inc
	do
		rt=$(rank "$to") &&
		if test -z "$rt" || test "$rt" -gt "$(rank "$from")"
		then
			echo "$file" >>bad
		fi || return 1
	done <fake &&
	test_line_count 2 bad
'

test_done
