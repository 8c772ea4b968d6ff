#!/bin/sh
test_description='scene emission: colours, the walls pattern, windows, images; shown by the G-buffer and reflect-shade'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"

# The references' room: 10 x 4 x 10, the pattern of cell 1 m, lines
# 0.08 m, base 0.3, checker 0.25, line 1, line-white 0.5, the -z wall's
# colour C = (0.3 0.45 1).
test_expect_success 'setup: the references room' '
	cat >room.scene <<-\EOF
	probe box -5 0 -5 5 4 5 center 0 2 0
	pattern cell 1 line-width 0.08 base 0.3 checker 0.25 line 1 line-white 0.5
	wall +x pattern 1 0.3 0.2
	wall -x pattern 0.25 0.9 0.3
	wall +y pattern 0.3 0.9 0.9
	wall -y pattern 0.9 0.35 0.85
	wall +z pattern 1 0.85 0.2
	wall -z pattern 0.3 0.45 1
	window -z min -2.5 1 max -0.5 2.8 radiance 16 14 11 mullions 0.1 0.2 0.2 0.2
	window +x min -1 1.2 max 2 2.6 radiance 6 8 12
	EOF
'

# emission_at X Y Z DX DY DZ: the emission where the ray from (X, Y, Z)
# along (DX, DY, DZ) meets the room (a 1x1 image looks along its centre).
emission_at () {
	sed "/^camera/d" room.scene >one.scene &&
	up="0 1 0" &&
	if test "$5" != 0; then up="0 0 -1"; fi &&
	echo "camera position $1 $2 $3 target $(echo "$1 $4 $2 $5 $3 $6" |
		awk "{ print \$1 + \$2, \$3 + \$4, \$5 + \$6 }") up $up fov 10" >>one.scene &&
	reflect-gbuffer -x 1 -y 1 -fa -c objid,emission one.scene >one.txt &&
	gb_data one.txt
}

# On -z, (u, v) = (x, y).  (0.25, 1.5): su 0.25, sv 1.5, 0.25 m and
# 0.5 m from the nearest lines (wider than 0.04): a cell, floor 0 +
# floor 1 odd: C (0.3 + 0.25) = 0.165 0.2475 0.55.  (1.02, 1.5): 0.02 m
# from the line x = 1: 1 (0.5 C + 0.5) = 0.65 0.725 1.  (-0.3, 1.5):
# floor -1 + floor 1 even: 0.3 C = 0.09 0.135 0.3.  (-1, 2): inside the
# window, 0.5 m and 0.1 m from its middle (-1.5, 1.9) (mullions reach
# 0.05 m either side): 16 14 11.  (-1.5, 2.5): on the vertical mullion:
# 0.2.  Negative wall ids: -z is RF_WALL_ZMIN, -6.
test_expect_success 'the pattern, lines, checker parity, windows and mullions by hand' '
	emission_at 0.25 1.5 0 0 0 -1 >got &&
	echo "-6 0.165 0.2475 0.55" >expect &&
	test_cmp_numbers expect got 1e-6 &&
	emission_at 1.02 1.5 0 0 0 -1 >got &&
	echo "-6 0.65 0.725 1" >expect &&
	test_cmp_numbers expect got 1e-6 &&
	emission_at -0.3 1.5 0 0 0 -1 >got &&
	echo "-6 0.09 0.135 0.3" >expect &&
	test_cmp_numbers expect got 1e-6 &&
	emission_at -1 2 0 0 0 -1 >got &&
	echo "-6 16 14 11" >expect &&
	test_cmp_numbers expect got 0 &&
	emission_at -1.5 2.5 0 0 0 -1 >got &&
	echo "-6 0.2 0.2 0.2" >expect &&
	test_cmp_numbers expect got 1e-7
'

# On +x, (u, v) = (z, y): (z 1.5, y 2) is inside the window (u in
# (-1, 2), v in (1.2, 2.6)); with the axes the other way round, u = 2
# would be outside.  On the floor (x, z): (0.5, -0.5) has floor 0 +
# floor -1 odd: C (0.55) = 0.495 0.1925 0.4675.
test_expect_success 'each wall has its own (u, v)' '
	emission_at 0 2 1.5 1 0 0 >got &&
	echo "-1 6 8 12" >expect &&
	test_cmp_numbers expect got 0 &&
	emission_at 0.5 2 -0.5 0 -1 0 >got &&
	echo "-4 0.495 0.1925 0.4675" >expect &&
	test_cmp_numbers expect got 1e-6
'

test_expect_success 'a colour for the room, a colour for an object' '
	cat >colours.scene <<-\EOF &&
	probe box -2 -2 -2 2 2 2
	room emission 0.5 0.25 2
	camera position 0 0 1.5 target 0 0 0 fov 100
	sphere center 0 0 0 radius 0.5 emission 3 4 5
	EOF
	reflect-gbuffer -x 3 -y 3 -fa -c objid,emission colours.scene >c.txt &&
	gb_data c.txt >got &&
	awk "\$1 == 1 && !(\$2 == 3 && \$3 == 4 && \$4 == 5) { bad = 1 }
	     \$1 < 0 && !(\$2 == 0.5 && \$3 == 0.25 && \$4 == 2) { bad = 1 }
	     \$1 == 1 { sphere++ } \$1 < 0 { wall++ }
	     END { exit bad || !sphere || !wall }" got
'

# A 2x2 float image spanning 2 x 2 m from (-1, 0) of the -z wall: its
# texel centres at u = -0.5, 0.5 and v = 1.5 (top row), 0.5; at a centre
# the bilinear lookup is that texel, times the gain.
test_expect_success 'an image on a wall, in metres, with its gain' '
	write_wall_image wall.exr &&
	cat >image.scene <<-\EOF &&
	probe box -5 0 -5 5 4 5 center 0 2 0
	wall -z image wall.exr size 2 2 origin -1 0 gain 2
	EOF
	cp image.scene room.scene &&
	emission_at -0.5 1.5 0 0 0 -1 >got &&
	echo "-6 2 4 6" >expect &&
	test_cmp_numbers expect got 1e-6 &&
	emission_at 0.5 0.5 0 0 0 -1 >got &&
	echo "-6 20 22 24" >expect &&
	test_cmp_numbers expect got 1e-6 &&
	# and it repeats: 2 m to the right is the same texel
	emission_at 2.5 0.5 0 0 0 -1 >got &&
	test_cmp_numbers expect got 1e-6
'

test_expect_success 'a scene without emission writes no emission channel' '
	cat >plain.scene <<-\EOF &&
	probe box -1 -1 -1 1 1 1
	EOF
	reflect-gbuffer -x 2 -y 2 plain.scene | reflect-info >info &&
	! test_grep emission info &&
	reflect-gbuffer -x 2 -y 2 -c emission plain.scene -fa >z.txt &&
	gb_data z.txt | sort -u >got &&
	echo "0 0 0" >expect &&
	test_cmp_numbers expect got 0
'

test_expect_success 'reflect-shade shows the emission on walls, adds it with --final' '
	reflect-gbuffer -x 48 -y 27 -fa | reflect-project -fa >s.txt &&
	reflect-shade -fa --final s.txt >sh.txt &&
	awk "/^CHANNELS=/ { n = split(substr(\$0, 10), ch, \" \"); for (i = 1; i <= n; i++) c[ch[i]] = i }
	     body && \$c[\"mask\"] == 0 {
		walls++
		for (k = 0; k < 3; k++) {
			e = \$c[\"emission.\" substr(\"RGB\", k + 1, 1)]
			if (\$c[\"spec.\" substr(\"RGB\", k + 1, 1)] != e || \$c[substr(\"RGB\", k + 1, 1)] != e)
				bad++
		}
	     }
	     /^$/ { body = 1 }
	     END { exit bad || walls < 100 }" sh.txt &&
	cat >glow.scene <<-\EOF &&
	probe box -2 -2 -2 2 2 2
	room emission 1 1 1
	camera position 0 0 1.5 target 0 0 0 fov 20
	sphere center 0 0 0 radius 0.5 roughness 0 emission 3 3 3
	EOF
	reflect-gbuffer -x 1 -y 1 glow.scene | reflect-project |
		reflect-shade -fa -m none --final --env=default >g.txt &&
	gb_pixel g.txt 0 0 spec.R R emission.R diffuse.R >got &&
	# R = spec (F0 A + B) + diffuse + emission, F0 = 1, diffuse 0 (metal)
	awk "{ exit !(\$2 > \$1 * 0.9 + 2.999 && \$2 < \$1 * 1.01 + 3.001 && \$3 == 3 && \$4 == 0) }" got
'

# A probe that names no env in a scene that emits is that scene seen
# from the probe (what "env capture" asks), never the embedded room of
# another scene; "env default" still gets the embedded room, and so
# does a probe of a scene that emits nothing.
test_expect_success 'a probe without env in an emitting scene is captured' '
	cat >green.scene <<-\EOF &&
	probe box -2 -2 -2 2 2 2 center 0 1.5 1.5
	room emission 0 1 0
	camera position 0 0 1.5 target 0 0 0 fov 20
	sphere center 0 0 0 radius 0.5 roughness 0
	EOF
	reflect-gbuffer -x 1 -y 1 green.scene | reflect-info >info &&
	test_grep "PROBE_ENV=capture:green.scene#1$" info &&
	reflect-gbuffer -x 1 -y 1 green.scene | reflect-project |
		reflect-shade -fa -m none 2>/dev/null >g.txt &&
	gb_pixel g.txt 0 0 spec.R spec.G spec.B >got &&
	# a white mirror in a green room: no red, no blue, the green wall
	awk "{ exit !(\$1 == 0 && \$3 == 0 && \$2 > 0.9 && \$2 <= 1) }" got &&
	sed "s/radius 0.5 roughness 0$/&\nprobe box -2 -2 -2 2 2 2 env default/" \
		green.scene >two.scene &&
	reflect-gbuffer -x 1 -y 1 two.scene | reflect-info >info &&
	test_grep "PROBE_ENV=capture:two.scene#1$" info &&
	test_grep "PROBE2_ENV=default$" info &&
	printf "probe box -1 -1 -1 1 1 1\n" >dark.scene &&
	reflect-gbuffer -x 1 -y 1 dark.scene | reflect-info >info &&
	test_grep "PROBE_ENV=default$" info &&
	printf "probe box -1 -1 -1 1 1 1\nwindow +x min 0 0 max 1 1 radiance 1 1 1\n" >late.scene &&
	reflect-gbuffer -x 1 -y 1 late.scene | reflect-info >info &&
	test_grep "PROBE_ENV=capture:late.scene#1$" info &&
	cat green.scene | reflect-gbuffer -x 1 -y 1 | reflect-project >piped.rfl &&
	test_expect_code 1 reflect-shade piped.rfl >/dev/null 2>err &&
	test_grep "the scene came from standard input and cannot be read again" err
'

test_expect_success 'bad emission lines are refused with where and why' '
	for bad in "wall +q pattern 1 1 1:expected a wall (+x, -x, +y, -y, +z or -z" \
		"wall +x:expected emission R G B, pattern R G B or image FILE on this line" \
		"wall +x emission 1 1 1 pattern 1 1 1:expected one of emission, pattern or image" \
		"wall +x emission 1 -1 1:expected .emission. in \[0, 1e+30\], found -1" \
		"wall +x emission 1 1 1 size 2 2:expected .size. with an .image. only" \
		"wall +x image nothere.exr:nothere.exr" \
		"window +x min 0 0 max 1 1:expected min U V, max U V and radiance R G B" \
		"window +x min 1 0 max 0 1 radiance 1 1 1:expected min < max on every axis" \
		"pattern cell 0:expected a positive cell" \
		"pattern line-white 2:expected .line-white. in \[0, 1\]" \
		"sphere center 0 0 0 radius 0.1 emission 1 1:expected a number for .emission."
	do
		printf "probe box -1 -1 -1 1 1 1\n%s\n" "${bad%%:*}" >bad.scene &&
		test_expect_code 1 reflect-gbuffer -x 1 -y 1 bad.scene >/dev/null 2>err || return 1
		test_grep "bad.scene:2:" err || return 1
		test_grep "${bad#*:}" err || return 1
	done &&
	printf "probe box -1 -1 -1 1 1 1\nwall +x emission 1 1 1\nwall +x emission 2 2 2\n" >twice.scene &&
	test_expect_code 1 reflect-gbuffer twice.scene >/dev/null 2>err &&
	test_grep "twice.scene:3:1: expected one .wall. line for each wall, the first for this one is line 2" err
'

test_done
