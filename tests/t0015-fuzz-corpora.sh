#!/bin/sh
test_description='the fuzz harnesses replayed over their corpora and the bugs they found'
. "$srcdir/tests/lib.sh"

# Each harness aborts on what it checks (a message without text or with a
# control byte, a header that does not come back, radiance that is not
# finite, the vector and plain reads disagreeing) and, in the sanitizer
# build, on any memory error or undefined behaviour.
for t in header scene dds ktx numeric probes envstream cache shade exr png hdr sniff gltf
do
	test_expect_success "replay the $t corpus" '
		"$builddir/tests/fuzz/replay-'$t'" "$srcdir/tests/fuzz/corpus/'$t'" >out &&
		test $(grep -c "^ran " out) -ge 3
	'
done

# The harnesses must fail on what they check, or they test nothing.
test_expect_success 'the numeric harness takes the box projection' '
	"$builddir/tests/fuzz/replay-numeric" "$srcdir/tests/fuzz/corpus/numeric/floor" &&
	REFLECT_PLUGIN_PATH=/nonexistent \
		"$builddir/tests/fuzz/replay-numeric" "$srcdir/tests/fuzz/corpus/numeric/floor"
'

# They failed on what they check before the fixes they came with: a NaN
# texel of a stream environment, a NaN emission shaded.
test_expect_success 'the environment and shading harnesses hold their corpora finite' '
	"$builddir/tests/fuzz/replay-envstream" "$srcdir/tests/fuzz/corpus/envstream/raw-ascii-nan" &&
	"$builddir/tests/fuzz/replay-shade" "$srcdir/tests/fuzz/corpus/shade/final-clamp" &&
	TMPDIR=$PWD "$builddir/tests/fuzz/replay-cache" "$srcdir/tests/fuzz/corpus/cache/entry-nan" &&
	! ls -d fuzz-cache-* 2>/dev/null
'

test_expect_success 'the glTF harness checks each status and leaves nothing' '
	TMPDIR=$PWD "$builddir/tests/fuzz/replay-gltf" "$srcdir/tests/fuzz/corpus/gltf" >out &&
	test $(grep -c "^ran " out) -ge 20 &&
	! ls -d fuzz-gltf-* 2>/dev/null
'

test_expect_success 'random bytes through every harness' '
	for t in header scene dds ktx numeric probes envstream cache shade exr png hdr sniff gltf
	do
		for seed in 1 2 3 4 5 6 7 8
		do
			awk -v seed=$seed -v t=$t "BEGIN {
				srand(seed); n = 64 + int(rand() * 2000)
				for (i = 0; i < n; i++) printf \"%c\", int(rand() * 256)
			}" >random-$t-$seed || return 1
		done &&
		"$builddir/tests/fuzz/replay-$t" random-$t-* >out &&
		test $(grep -c "^ran " out) -eq 8 || return 1
	done
'

test_done
