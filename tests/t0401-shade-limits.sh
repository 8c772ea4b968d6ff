#!/bin/sh
test_description='every mode equals none where the spec says it must'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

CH="roughness hit.dist probe.dist N.X N.Y N.Z V.X V.Y V.Z D.X D.Y D.Z"

# tuples FILE AWK-CONDITION: 40 pseudo-random tuples (roughness, hit
# distance, probe distance, N.V) that the condition then pins; V and D
# vary too, so that spec differs from pixel to pixel.
tuples () {
	awk -v seed=7 "BEGIN {
		srand(seed)
		for (k = 0; k < 40; k++) {
			pr = rand(); d = 12 * rand(); l = 0.1 + 8 * rand(); nv = 2 * rand() - 1
			$2
			a = 6.2832 * rand()
			printf \"%.6f %.6f %.6f 0 1 0 %.9g %.9g 0 %.9g %.9g %.9g\n\", pr, d, l,
				sqrt(1 - nv * nv), nv, cos(a), 0.3, sin(a)
		}
	}" | stream "$1" 40 1 "$CH"
}

# same_as_none FILE MODE...: the modes write the bytes none writes.
same_as_none () {
	sa_file=$1
	shift
	reflect-shade -h -m none --env=chain.rfl "$sa_file" >none.out &&
	for m
	do
		reflect-shade -h -m "$m" --env=chain.rfl "$sa_file" >mode.out &&
		cmp none.out mode.out || {
			echo "mode $m differs from none on $sa_file" >&2
			return 1
		}
	done
}

test_expect_success 'setup' '
	level_chain chain.rfl 64 7 unity
'

test_expect_success 'hdrp at roughness 1 is none' '
	tuples r1.txt "pr = 1" &&
	same_as_none r1.txt hdrp
'

test_expect_success 'godot at roughness 1 (and 0) is none, at any power' '
	same_as_none r1.txt godot godot:power=2 godot:power=0 godot:distance=0.5 &&
	tuples r0.txt "pr = 0" &&
	same_as_none r0.txt godot godot:power=2 hdrp approx approx:clamp=0
'

test_expect_success 'approx with the clamp is none when hit.dist >= distance' '
	tuples far.txt "d = 6 + 10 * rand(); if (k == 0) d = 6" &&
	same_as_none far.txt approx &&
	tuples far3.txt "d = 3 + 10 * rand(); if (k == 0) d = 3" &&
	same_as_none far3.txt approx:distance=3
'

test_expect_success 'approx without the clamp is none exactly at hit.dist = distance' '
	tuples at.txt "d = 6" &&
	same_as_none at.txt approx:clamp=0
'

test_expect_success 'hdrp is none when the hit is no nearer than the probe (d >= |R|)' '
	tuples ratio.txt "l = d * (0.2 + 0.8 * rand()); if (k == 0) l = d" &&
	same_as_none ratio.txt hdrp
'

test_expect_success 'every mode is none when hit.dist is inf' '
	tuples inf.txt "d = \"inf\"; l = \"inf\"" &&
	grep -q "inf" inf.txt &&
	same_as_none inf.txt approx approx:clamp=0 approx:distance=0.1 hdrp godot \
		godot:power=0
'

test_expect_success 'every mode is none with projection infinite (hand-made G-buffer)' '
	awk "BEGIN {
		srand(3)
		for (k = 0; k < 30; k++) {
			nv = rand()
			printf \"%.5f %.5f %.5f 0 1 0 %.9g %.9g 0 %.4f\n\", 6 * rand() - 3,
				3 * rand(), 4 * rand() - 2, sqrt(1 - nv * nv), nv, rand()
		}
	}" | stream gb.txt 30 1 "P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness" \
		"PROBE_BOX=-3 0 -2 3 3 2" "PROBE_CENTER=0 1.5 0" &&
	reflect-project -m infinite gb.txt >inf.rfl &&
	same_as_none inf.rfl approx approx:clamp=0 hdrp godot godot:power=2
'

test_expect_success 'every mode is none with projection infinite (default scene)' '
	reflect-gbuffer -x 48 -y 27 | reflect-project -m infinite >scene.rfl &&
	same_as_none scene.rfl approx approx:clamp=0 hdrp godot
'

test_expect_success 'a point outside the box gets infinite distances, so none' '
	printf "5 1 0 0 1 0 0 1 0 0.5\n-4 1 3 0 1 0 0.6 0.8 0 0.3\n" |
	stream out.txt 2 1 "P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness" \
		"PROBE_BOX=-3 0 -2 3 3 2" "PROBE_CENTER=0 1.5 0" &&
	reflect-project out.txt >out.rfl &&
	reflect-project -fa out.txt | column - hit.dist probe.dist >dist &&
	printf "inf inf\ninf inf\n" >want &&
	cmp_numbers want dist &&
	same_as_none out.rfl approx approx:clamp=0 hdrp godot
'

# By default such input is refused (t0016); --invalid=clamp and zero go
# on, and neither may let a NaN through.
test_expect_success 'NaN and odd inputs never give NaN (--invalid=clamp, zero)' '
	printf "%s\n" "nan 1 1 0 1 0 0 1 0 0 0 1" "0.5 nan 1 0 1 0 0 1 0 0 0 1" \
		"0.5 1 nan 0 1 0 0 1 0 0 0 1" "0.5 -inf 1 0 1 0 0 1 0 0 0 1" \
		"0.5 1 0 0 1 0 0 1 0 0 0 1" "0 0 0 0 1 0 0 1 0 0 0 1" \
		"-3 2 1 0 1 0 0 1 0 0 0 1" "7 2 1 0 1 0 0 1 0 0 0 1" \
		"0.5 2 1 nan 1 0 0 1 0 0 0 1" "0.5 2 1 0 1 0 0 -1 0 0 0 1" \
		"0.5 2 1 0 1 0 0 1 0 nan 0 1" "0.5 2 1 0 1 0 0 1 0 inf 0 1" |
	stream odd.txt 12 1 "$CH" &&
	for m in none approx approx:clamp=0 hdrp godot godot:power=0
	do
		for policy in clamp zero
		do
			reflect-shade -fa -m $m --invalid=$policy --env=chain.rfl odd.txt \
				>odd.out 2>/dev/null &&
			column odd.out roughness.eff spec.R spec.G spec.B >got &&
			test_line_count 12 got &&
			if grep -i nan got
			then
				echo "mode $m wrote NaN with --invalid=$policy" >&2
				return 1
			fi || return 1
		done || return 1
	done
'

test_done
