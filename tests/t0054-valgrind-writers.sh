#!/bin/sh
test_description='the image writers under valgrind: no memory error, no leak'
. "$srcdir/tests/lib.sh"

# The writers name the path, not their temporary file, in a message: a
# close that succeeded looked for the temporary file's name in a message
# buffer nobody had written (valgrind: "Conditional jump or move depends
# on uninitialised value(s)" in name_path, from reflect-compare -o and
# reflect-montage -o).  99 is valgrind's: an error or a leak.
valgrind_ok () {
	"$builddir/libtool" --mode=execute \
		$VALGRIND -q --error-exitcode=99 --leak-check=full "$@" >/dev/null 2>err
	got=$?
	if test "$got" -ne 0
	then
		echo "expected exit status 0 under valgrind, got $got: $*" >&2
		cat err >&2
		return 1
	fi
}

valgrind_reason=
if test -n "$VALGRIND" &&
	! "$builddir/libtool" --mode=execute $VALGRIND -q --error-exitcode=99 \
		"$builddir/bin/reflect-info" -V >/dev/null 2>valgrind.err
then
	valgrind_reason="valgrind cannot run the tools: $(head -n 1 valgrind.err)"
	VALGRIND=
fi

test_expect_success 'the inputs' '
	reflect-gbuffer -x 24 -y 16 | reflect-project | reflect-shade --size=8 >a.rfl &&
	reflect-gbuffer -x 24 -y 16 | reflect-project | reflect-shade --size=8 -m none >b.rfl
'

if test -n "$VALGRIND"
then
	test_expect_success 'reflect-export -o, PNG and OpenEXR' '
		valgrind_ok "$builddir/bin/reflect-export" -o a.png a.rfl &&
		valgrind_ok "$builddir/bin/reflect-export" -o a.exr a.rfl &&
		valgrind_ok "$builddir/bin/reflect-export" --depth=16 -o a16.png a.rfl &&
		test -s a.png && test -s a.exr && test -s a16.png
	'
	test_expect_success 'reflect-compare -o' '
		valgrind_ok "$builddir/bin/reflect-compare" -o heat.png a.rfl a.rfl &&
		valgrind_ok "$builddir/bin/reflect-compare" -o heat.exr a.rfl a.rfl &&
		test -s heat.png && test -s heat.exr
	'
	test_expect_success 'reflect-montage -o' '
		valgrind_ok "$builddir/bin/reflect-montage" -o m.png A=a.rfl B=b.rfl:spec.R,spec.G,spec.B &&
		valgrind_ok "$builddir/bin/reflect-montage" -o m.exr A=a.rfl B=b.rfl &&
		test -s m.png && test -s m.exr
	'
	# PNG files made in memory, for the page's data: URIs
	test_expect_success 'reflect-report -o' '
		valgrind_ok "$builddir/bin/reflect-report" -o r.html a.rfl b=b.rfl &&
		test_grep "data:image/png;base64," r.html
	'
else
	for t in 'reflect-export -o, PNG and OpenEXR' 'reflect-compare -o' \
		'reflect-montage -o' 'reflect-report -o'
	do
		test_skip "$t" "${valgrind_reason:-no valgrind}"
	done
fi

test_done
