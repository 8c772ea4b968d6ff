#!/bin/sh
test_description='reflect-shade -m footprint: its lanes, any width, any thread count'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

# A frame 61 wide: its rows are not whole chunks of eight pixels (the
# mode reads the environment for eight at a time) nor whole vectors.
test_expect_success 'setup: an odd frame, the room prefiltered small' '
	reflect-prefilter --size=32 -o room.rfl 2>/dev/null &&
	reflect-gbuffer -x 61 -y 37 | reflect-project >odd.rfl
'

# The chunks start where each span starts, whatever the rows a thread
# takes: the bytes are the same at any thread count, with the vector
# code and without.
for simd in on off
do
	test_expect_success "the bytes do not depend on the thread count (REFLECT_SIMD=$simd)" '
		for m in footprint footprint:taps=3 footprint:lobe=round
		do
			REFLECT_SIMD=$simd reflect-shade -h -j1 -m $m --env=room.rfl odd.rfl >j1 &&
			REFLECT_SIMD=$simd reflect-shade -h -j2 -m $m --env=room.rfl odd.rfl >j2 &&
			REFLECT_SIMD=$simd reflect-shade -h -j5 -m $m --env=room.rfl odd.rfl >j5 &&
			cmp j1 j2 && cmp j1 j5 || return 1
		done
	'
done

# The mode's own lanes give the same bits at four lanes and at eight
# (the same polynomials, no fused multiply-add); what differs between
# REFLECT_SIMD=off and on is the host's reads of the environment, which
# round differently (t0405: by far less than 1e-3 of the room's
# radiance), so the two agree as closely as mode none's do.
test_expect_success 'vector and plain code agree as closely as none' '
	for m in none footprint
	do
		reflect-shade -f a -m $m --env=room.rfl odd.rfl >$m.vector &&
		REFLECT_SIMD=off reflect-shade -f a -m $m --env=room.rfl odd.rfl >$m.plain &&
		column $m.vector spec.R spec.G spec.B >$m.v &&
		column $m.plain spec.R spec.G spec.B >$m.p &&
		test_line_count $((61 * 37)) $m.p &&
		paste $m.v $m.p | awk "{ for (i = 1; i <= 3; i++) {
			d = \$i - \$(i + 3); d = d < 0 ? -d : d; if (d > m) m = d } }
			END { print m + 0 }" >$m.diff || return 1
	done &&
	echo "largest difference: none $(cat none.diff) footprint $(cat footprint.diff)" &&
	awk -v n="$(cat none.diff)" "{ exit !(\$1 <= 1e-6 + 4 * n && \$1 < 1e-3) }" footprint.diff
'

# A pixel's taps do not depend on its neighbours': every seventh pixel
# of the frame, shaded as a frame of their own (one row of 323), gives
# the bytes it has in the whole frame.
test_expect_success 'a pixel does not depend on the chunk it is read in' '
	reflect-shade -f a -m footprint --env=room.rfl odd.rfl >all.txt &&
	column all.txt spec.R spec.G spec.B >all.spec &&
	reflect-project -fa <odd.rfl >odd.txt &&
	awk "body { if (++n % 7 == 3) print; next } /^\$/ { body = 1 }" odd.txt >some.body &&
	test_line_count 323 some.body &&
	{
		sed -e "/^\$/q" -e "s/^NCOLS=.*/NCOLS=323/" -e "s/^NROWS=.*/NROWS=1/" odd.txt &&
		cat some.body
	} >some.txt &&
	reflect-shade -f a -m footprint --env=room.rfl some.txt >some.out &&
	column some.out spec.R spec.G spec.B >some.spec &&
	awk "NR % 7 == 3" all.spec >want &&
	test_line_count 323 want &&
	cmp want some.spec
'

test_done
