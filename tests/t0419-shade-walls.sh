#!/bin/sh
test_description='reflect-shade runs a radiance mode only between walls, unless it writes more than spec'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

P=$REFLECT_TEST_PLUGINS

# One row of six pixels, walls at x = 0, 2 and 3, a partial mask at 4:
# P on the walls of the box (-3,0,-2)-(3,3,2) seen from (0,1.5,0), whose
# faces +X -X +Y -Y +Z -Z hold 10..15 at level 0 of faces.rfl.  The test
# modes write spec = (x, y, 1).
test_expect_success 'setup' '
	level_chain faces.rfl 64 7 unity 10 &&
	printf "%s\n" "3 1.5 0 0" "0 1.5 2 1" "-3 1.5 0 0" "0 3 0 0" "0 1.5 -2 0.25" \
		"0 0 0 1" |
	awk "{ print \$1, \$2, \$3, 0, 1, 0, 0, 1, 0, 0.5, 0, 0, 1, \$4 }" |
	stream walls.txt 6 1 "P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness D.X D.Y D.Z mask" \
		"PROBE_BOX=-3 0 -2 3 3 2" "PROBE_CENTER=0 1.5 0" &&
	# walls: the face; mask 1: the mode; mask 0.25: a quarter of the
	# mode, three quarters of -Z (15)
	printf "%s\n" "10 10 10" "1 0 1" "11 11 11" "12 12 12" "12.25 11.25 11.5" \
		"5 0 1" >want
'

# shade_walls fails its run on a pixel whose mask is 0.
test_expect_success 'a mode of spec outputs only is not run on walls' '
	for j in 1 2 5
	do
		reflect-shade -j$j -fa -m "$P/shade_walls.so" --env=faces.rfl walls.txt \
			>out.txt || return 1
		column out.txt spec.R spec.G spec.B >got &&
		cmp_numbers want got 2e-5 || return 1
	done
'

test_expect_success 'a mode with another output runs on walls too' '
	reflect-shade -fa -m "$P/shade_walls_extra.so" --env=faces.rfl walls.txt >out.txt &&
	column out.txt walls.seen >got &&
	printf "%s\n" 1 0 1 1 0 0 >want.seen &&
	cmp_numbers want.seen got 0 &&
	column out.txt spec.R spec.G spec.B >got &&
	cmp_numbers want got 2e-5
'

test_done
