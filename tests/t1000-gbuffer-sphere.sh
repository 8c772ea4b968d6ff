#!/bin/sh
test_description='a camera looking straight at a sphere: P, N, V and depth by hand'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"

test_expect_success 'setup' '
	cat >sphere.scene <<-\EOF &&
	# a unit sphere at the origin, seen from 5 m along +Z
	probe box -10 -10 -10 10 10 10
	camera position 0 0 5 target 0 0 0 up 0 1 0 fov 40
	sphere center 0 0 0 radius 1 roughness 0.3
	EOF
	reflect-gbuffer -x 3 -y 3 -fa sphere.scene >out.txt
'

# The centre pixel of an odd image looks exactly along the view direction:
# the ray from (0,0,5) along -Z meets the sphere at t = 4, P = (0,0,1),
# where the normal is (0,0,1) and the way back to the eye (0,0,1).
test_expect_success 'the centre pixel sees the sphere head on' '
	gb_pixel out.txt 1 1 P.X P.Y P.Z N.X N.Y N.Z Ng.X Ng.Y Ng.Z V.X V.Y V.Z depth \
		>actual &&
	echo "0 0 1  0 0 1  0 0 1  0 0 1  4" >expect &&
	test_cmp_numbers expect actual 0
'

test_expect_success 'the centre pixel has the sphere material' '
	gb_pixel out.txt 1 1 roughness metallic albedo.R albedo.G albedo.B mask objid \
		>actual &&
	echo "0.3 1 1 1 1 1 1" >expect &&
	test_cmp_numbers expect actual 1e-7
'

# Corner pixel (0, 0): x = 2(0.5)/3 - 1 = -2/3, y = 2/3, so the ray is
# (-2/3 t, 2/3 t, -1) with t = tan 20deg = 0.363970234: it passes the
# sphere (1.72 m off axis at z = 0) and meets the wall z = -10 after 15 m
# along -Z: P = (-15 (2/3) t, 15 (2/3) t, -10) = (-3.63970234, 3.63970234,
# -10).  V = (cam - P)/|cam - P| with |cam - P| = 15.8585897.
test_expect_success 'a corner pixel misses the sphere and sees the far wall' '
	gb_pixel out.txt 0 0 P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z depth mask objid \
		>actual &&
	echo "-3.63970234 3.63970234 -10  0 0 1  0.229509838 -0.229509838 0.945859645  15.8585897  0 -6" >expect &&
	test_cmp_numbers expect actual 2e-6
'

test_expect_success 'V is the unit vector from P to the camera on every pixel' '
	gb_data out.txt | awk "{
		dx = 0 - \$1; dy = 0 - \$2; dz = 5 - \$3
		l = sqrt(dx * dx + dy * dy + dz * dz)
		e = (dx / l - \$10) ^ 2 + (dy / l - \$11) ^ 2 + (dz / l - \$12) ^ 2
		if (e > 1e-12 || (\$20 - l) ^ 2 > 1e-10) { print NR \": \" \$0; bad = 1 }
	} END { exit bad }"
'

test_done
