#!/bin/sh
test_description='reflect-shade --lod and --box-projection=off: the write-up s switches'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

test_expect_success 'setup: a chain whose level k holds k, a projected G-buffer' '
	level_chain chain.rfl 32 6 unity &&
	reflect-gbuffer -x 48 -y 27 >g.rfl &&
	reflect-project g.rfl >box.rfl &&
	reflect-project -m infinite g.rfl >inf.rfl
'

test_expect_success '--lod=L reads every mirror at L, whatever the mode' '
	# a read of constant levels gives its lod: 2.7 everywhere on the mask
	for m in none approx hdrp godot
	do
		reflect-shade -fa -m $m --lod=2.7 --env=chain.rfl box.rfl >out.txt &&
		column out.txt mask spec.G | awk "\$1 == 1" >got || return 1
		test -s got &&
		awk "{ if (\$2 < 2.6999 || \$2 > 2.7001) bad++ } END { exit bad > 0 }" got || return 1
	done &&
	reflect-shade -fa -m none --lod=0 --env=chain.rfl box.rfl >zero.txt &&
	column zero.txt mask spec.G | awk "\$1 == 1 && \$2 != 0 { bad++ } END { exit bad > 0 }"
'

test_expect_success '--lod leaves a mode that writes radiance alone' '
	reflect-shade -h -m raytraced:samples=4 --env=chain.rfl box.rfl >a.raw &&
	reflect-shade -h -m raytraced:samples=4 --lod=3 --env=chain.rfl box.rfl >b.raw &&
	cmp a.raw b.raw
'

test_expect_success '--lod out of range is refused' '
	test_expect_code 1 reflect-shade --lod=-1 --env=chain.rfl box.rfl >/dev/null 2>err &&
	test_grep "lod" err &&
	test_expect_code 1 reflect-shade --lod=x --env=chain.rfl box.rfl >/dev/null 2>err &&
	test_grep "lod" err
'

test_expect_success '--box-projection=off: every mode is the classic lookup along R' '
	reflect-shade -fa -m none inf.rfl >classic.txt 2>/dev/null &&
	column classic.txt spec.R spec.G spec.B >want &&
	for m in none approx hdrp godot
	do
		reflect-shade -fa -m $m --box-projection=off box.rfl >off.txt 2>/dev/null &&
		column off.txt spec.R spec.G spec.B >got &&
		cmp want got || return 1
	done &&
	# and not what they give with it on
	reflect-shade -fa -m none box.rfl 2>/dev/null >on.txt &&
	column on.txt spec.R spec.G spec.B >on &&
	! cmp -s want on
'

test_expect_success 'PROBE_BOX_PROJECTION=0 in the stream does the same' '
	reflect-project --box-projection=off g.rfl >off.rfl &&
	reflect-info off.rfl | grep "PROBE_BOX_PROJECTION=0" &&
	reflect-shade -fa -m hdrp off.rfl >h.txt 2>/dev/null &&
	column h.txt spec.R spec.G spec.B >got &&
	cmp want got
'

test_expect_success 'the occlusion after it still box-projects, as the write-up does' '
	reflect-shade -m approx --box-projection=off box.rfl 2>/dev/null | reflect-occlude -fa >o1.txt &&
	reflect-shade -m approx box.rfl 2>/dev/null | reflect-occlude -fa >o2.txt &&
	column o1.txt occlusion >a && column o2.txt occlusion >b &&
	cmp a b &&
	awk "\$1 < 1 { n++ } END { exit !(n > 0) }" a
'

# A projection without parallax (one that reads no P) writes the probe
# with box projection off: the modes that trace rays from P then take the
# room as far away as it did, not as a box.
test_expect_success 'after -m infinite, the modes that trace rays keep their directions' '
	reflect-info inf.rfl | grep "PROBE_BOX_PROJECTION=0" &&
	reflect-info box.rfl | grep "PROBE_BOX_PROJECTION=1" &&
	reflect-project --box-projection=off g.rfl >off.rfl &&
	for m in raytraced:samples=4 footprint
	do
		reflect-shade -h -m $m inf.rfl >inf.raw 2>/dev/null &&
		reflect-shade -h -m $m off.rfl >off.raw 2>/dev/null &&
		reflect-shade -h -m $m box.rfl >box.raw 2>/dev/null &&
		test -s inf.raw &&
		cmp inf.raw off.raw &&
		! cmp -s inf.raw box.raw || return 1
	done
'

test_done
