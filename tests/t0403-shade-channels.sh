#!/bin/sh
test_description='reflect-shade keeps every channel, shows walls directly, writes its keys and the final colour'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

# words HEX...: little-endian bytes of 32-bit words (the data of a
# headerless stream, -H), written with printf octal escapes.
words () {
	for w
	do
		for i in 7 5 3 1
		do
			printf "\\$(printf %03o "0x$(echo "$w" | cut -c$i-$((i + 1)))")"
		done
	done
}

test_expect_success 'setup' '
	level_chain chain.rfl 64 7 unity &&
	level_chain faces.rfl 64 7 unity 10
'

# Channels the modes do not read, with awkward bits: a NaN with a
# payload, -0, a denormal, infinities, a negative number.
test_expect_success 'extra channels come out byte-identical (headerless input)' '
	words 7fc12345 3e800000 40000000 80000000 00000000 00000000 3f800000 00000001 \
	      7f800000 3f400000 3f000000 c0e80000 3f800000 00000000 00000000 ff800000 \
	      4b7fffff 00000000 7f800000 7f7fffff 00000000 3f800000 00000000 bf800000 \
	      >in.bin &&
	test $(wc -c <in.bin) -eq 96 &&
	for m in none approx hdrp
	do
		reflect-shade -m $m --env=chain.rfl -H -x 3 -y 1 \
			-c "extra roughness hit.dist probe.dist D.X D.Y D.Z other.thing" \
			-h in.bin >out.bin &&
		test $(wc -c <out.bin) -eq $((3 * 12 * 4)) &&
		od -An -v -tx4 -w32 in.bin | tr -s " " >want &&
		od -An -v -tx4 -w48 out.bin | cut -d" " -f1-9 >got &&
		cmp want got || return 1
	done
'

test_expect_success 'channel order is kept, outputs appended, spec last' '
	printf "%s\n" "1 0.5 2 3 0 0 1 9" "2 0.25 inf inf 1 0 0 -9" |
	stream in.txt 2 1 "a roughness hit.dist probe.dist D.X D.Y D.Z z" &&
	reflect-shade -fa -m hdrp --env=chain.rfl in.txt >out.txt &&
	test_grep "^CHANNELS=a roughness hit.dist probe.dist D.X D.Y D.Z z roughness.eff spec.R spec.G spec.B$" out.txt &&
	column out.txt a z >got &&
	printf "1 9\n2 -9\n" >want &&
	cmp_numbers want got 0
'

test_expect_success 'channels of the same names are overwritten, not doubled' '
	reflect-shade -fa -m none --env=chain.rfl in.txt >once.txt &&
	reflect-shade -fa -m approx --env=chain.rfl once.txt >twice.txt &&
	test_grep "^CHANNELS=a roughness hit.dist probe.dist D.X D.Y D.Z z roughness.eff spec.R spec.G spec.B$" twice.txt &&
	test_grep "^SHADE=approx$" twice.txt
'

test_expect_success 'header keys: SHADE, ENV_MAPPING, ENV_STEPS, PROBE_ENV, the command line' '
	reflect-shade -fa -m approx:clamp=0 --env=chain.rfl in.txt >out.txt &&
	test_grep "^SHADE=approx:clamp=0$" out.txt &&
	test_grep "^ENV_MAPPING=unity$" out.txt &&
	test_grep "^ENV_STEPS=6$" out.txt &&
	test_grep "^PROBE_ENV=chain.rfl$" out.txt &&
	test_grep "^reflect-shade -fa -m approx:clamp=0 --env=chain.rfl in.txt$" out.txt &&
	reflect-shade in.txt -fa --env=chain.rfl >out.txt &&
	test_grep "^reflect-shade in.txt -fa --env=chain.rfl$" out.txt &&
	test_grep "^SHADE=approx$" out.txt
'

# P on the walls of the box (-3,0,-2)-(3,3,2) seen from (0,1.5,0): the
# faces +X -X +Y -Y +Z -Z hold 10..15 at level 0 of faces.rfl.
test_expect_success 'mask 0 pixels show the environment from the probe centre toward P' '
	printf "%s\n" "3 1.5 0 0" "-3 1.5 0 0" "0 3 0 0" "0 0 0 0" "0 1.5 2 0" \
		"0 1.5 -2 0" "3 1.5 0 1" "0 1.5 -2 0.25" |
	awk "{ print \$1, \$2, \$3, 0, 1, 0, 0, 1, 0, 0.5, 0, 0, 1, \$4 }" |
	stream walls.txt 8 1 "P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness D.X D.Y D.Z mask" \
		"PROBE_BOX=-3 0 -2 3 3 2" "PROBE_CENTER=0 1.5 0" &&
	reflect-shade -fa -m none --env=faces.rfl walls.txt >out.txt &&
	column out.txt spec.R spec.G spec.B >got &&
	# mask 1: lod(0.5) = 0.5 (1.7 - 0.35) 6 = 4.05 of a chain whose level
	# k is k; mask 0.25: a quarter of that and three quarters of -Z.
	printf "%s\n" "10 10 10" "11 11 11" "12 12 12" "13 13 13" "14 14 14" \
		"15 15 15" "4.05 4.05 4.05" "12.2625 12.2625 12.2625" >want &&
	cmp_numbers want got 2e-5
'

test_expect_success '--center overrides PROBE_CENTER for the walls' '
	reflect-shade -fa -m none --env=faces.rfl --center=0,1.5,3 walls.txt >out.txt &&
	column out.txt spec.R | sed -n 6p >got &&
	echo 15 >want &&
	cmp_numbers want got 2e-5 &&
	column out.txt spec.R | sed -n 5p >got &&
	echo 15 >want &&
	cmp_numbers want got 2e-5 &&
	test_grep "^PROBE_CENTER=0 1.5 3$" out.txt
'

test_expect_success 'a stream without mask is reflective everywhere and needs no probe' '
	reflect-shade -fa -m none --env=faces.rfl in.txt >out.txt &&
	column out.txt spec.R >got &&
	printf "%s\n" 4.05 2.2875 >want &&
	cmp_numbers want got 2e-5
'

# The split-sum reference values at n.v = 0.5, roughness 0.5 (A, B) and
# at n.v = 1, roughness 0.8, from tests/unit/test-dfg.c's quadrature.
test_expect_success '--final: R G B = spec x (F0 A + B), F0 = lerp(0.04, albedo, metallic)' '
	printf "%s\n" "1 1 0.5 0" "0 1 0.5 0" "0.5 0.2 0.4 0.6" |
	awk "{ print 0, 1, 0, 0.866025404, 0.5, 0, 0.5, 0, 0, 1, \$1, \$2, \$3, \$4 }" |
	stream mat.txt 3 1 "N.X N.Y N.Z V.X V.Y V.Z roughness D.X D.Y D.Z metallic albedo.R albedo.G albedo.B" &&
	reflect-shade -fa -m none --final --diffuse=off --env=chain.rfl mat.txt >out.txt &&
	test_grep "^CHANNELS=.* spec.R spec.G spec.B R G B$" out.txt &&
	column out.txt spec.R R G B >got &&
	awk -v a=0.83492 -v b=0.02235 "
		NR == 1 { m = 1; r = 1; g = 0.5; bl = 0 }
		NR == 2 { m = 0; r = 1; g = 0.5; bl = 0 }
		NR == 3 { m = 0.5; r = 0.2; g = 0.4; bl = 0.6 }
		{
			s = \$1
			printf \"%.6f %.6f %.6f\n\", s * ((0.04 + (r - 0.04) * m) * a + b),
				s * ((0.04 + (g - 0.04) * m) * a + b),
				s * ((0.04 + (bl - 0.04) * m) * a + b)
		}" got >want &&
	awk "{ print \$2, \$3, \$4 }" got >rgb &&
	cmp_numbers want rgb 5e-3
'

test_expect_success '--final without metallic and albedo is a white metal (F0 = 1)' '
	printf "0 1 0 0 1 0 0.8 0 0 1\n" |
	stream white.txt 1 1 "N.X N.Y N.Z V.X V.Y V.Z roughness D.X D.Y D.Z" &&
	reflect-shade -fa -m none --final --env=chain.rfl white.txt >out.txt &&
	column out.txt spec.R R G B >got &&
	awk "{ e = 0.55512 + 0.00005; printf \"%.6f %.6f %.6f\n\", \$1 * e, \$1 * e, \$1 * e }" got >want &&
	awk "{ print \$2, \$3, \$4 }" got >rgb &&
	cmp_numbers want rgb 5e-3
'

test_expect_success '--final: walls are the environment itself, R G B = spec' '
	reflect-shade -fa -m none --final --env=faces.rfl walls.txt >out.txt &&
	column out.txt spec.R R | sed -n 1,6p >got &&
	awk "{ exit !(\$1 == \$2) }" got
'

test_expect_success 'a stream with a mask but no probe centre is refused' '
	sed "/^PROBE_/d" walls.txt >nocentre.txt &&
	test_expect_code 1 reflect-shade -m none --env=faces.rfl nocentre.txt >/dev/null 2>err &&
	test_one_line_message reflect-shade err &&
	test_grep "center" err &&
	reflect-shade -m none --env=faces.rfl --center=0,1.5,0 nocentre.txt >/dev/null
'

test_expect_success 'several frames go through, each with its own keys' '
	cat in.txt in.txt >two.txt &&
	reflect-shade -fa -m none --env=chain.rfl two.txt >out.txt &&
	test $(grep -c "^SHADE=none$" out.txt) -eq 2 &&
	column out.txt spec.R >got &&
	test_line_count 4 got
'

test_done
