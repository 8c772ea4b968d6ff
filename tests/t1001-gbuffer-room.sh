#!/bin/sh
test_description='the room: each wall faces in, with its own objid, mask 0, roughness 1'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"

# One pixel from the capture point (0, 1.5, 0) of the room -3 0 -2 .. 3 3 2
# towards each wall: the hit is on the wall's plane straight ahead, the
# normal points back into the room.
wall () {
	target=$1 up=$2
	cat >room.scene <<-EOF &&
	probe center 0 1.5 0 box -3 0 -2 3 3 2
	camera position 0 1.5 0 target $target up $up fov 30
	EOF
	reflect-gbuffer -x 1 -y 1 -fa room.scene >out.txt &&
	gb_pixel out.txt 0 0 P.X P.Y P.Z N.X N.Y N.Z Ng.X Ng.Y Ng.Z V.X V.Y V.Z \
		depth roughness metallic mask objid >actual
}

test_expect_success 'the wall at x = 3 (+X)' '
	wall "1 1.5 0" "0 1 0" &&
	echo "3 1.5 0  -1 0 0  -1 0 0  -1 0 0  3  1 0 0 -1" >expect &&
	test_cmp_numbers expect actual 0
'

test_expect_success 'the wall at x = -3 (-X)' '
	wall "-1 1.5 0" "0 1 0" &&
	echo "-3 1.5 0  1 0 0  1 0 0  1 0 0  3  1 0 0 -2" >expect &&
	test_cmp_numbers expect actual 0
'

test_expect_success 'the ceiling y = 3 (+Y)' '
	wall "0 2 0" "0 0 1" &&
	echo "0 3 0  0 -1 0  0 -1 0  0 -1 0  1.5  1 0 0 -3" >expect &&
	test_cmp_numbers expect actual 0
'

test_expect_success 'the floor y = 0 (-Y)' '
	wall "0 1 0" "0 0 1" &&
	echo "0 0 0  0 1 0  0 1 0  0 1 0  1.5  1 0 0 -4" >expect &&
	test_cmp_numbers expect actual 0
'

test_expect_success 'the wall at z = 2 (+Z)' '
	wall "0 1.5 1" "0 1 0" &&
	echo "0 1.5 2  0 0 -1  0 0 -1  0 0 -1  2  1 0 0 -5" >expect &&
	test_cmp_numbers expect actual 0
'

test_expect_success 'the wall at z = -2 (-Z)' '
	wall "0 1.5 -1" "0 1 0" &&
	echo "0 1.5 -2  0 0 1  0 0 1  0 0 1  2  1 0 0 -6" >expect &&
	test_cmp_numbers expect actual 0
'

test_expect_success 'a room material applies to every wall' '
	cat >room.scene <<-\EOF &&
	probe center 0 1.5 0 box -3 0 -2 3 3 2
	room on roughness 0.5 metallic 0.25 albedo 0.1 0.2 0.3
	camera position 0 1.5 0 target 1 1.5 0 fov 30
	EOF
	reflect-gbuffer -x 1 -y 1 -fa room.scene >out.txt &&
	gb_pixel out.txt 0 0 roughness metallic albedo.R albedo.G albedo.B mask >actual &&
	echo "0.5 0.25 0.1 0.2 0.3 0" >expect &&
	test_cmp_numbers expect actual 1e-7
'

# Outside the room, looking away from it: nothing is hit.  No NaN: P is
# far along the ray, N = V = -ray, depth = inf, objid 0, mask 0.
test_expect_success 'room off, or outside it: nothing is hit, and no NaN' '
	cat >room.scene <<-\EOF &&
	probe center 0 1.5 0 box -3 0 -2 3 3 2
	room off
	camera position 0 1.5 0 target 0 1.5 -1 fov 30
	EOF
	reflect-gbuffer -x 1 -y 1 -fa room.scene >out.txt &&
	gb_pixel out.txt 0 0 P.X P.Y N.X N.Y N.Z V.X V.Y V.Z depth mask objid >actual &&
	echo "0 1.5  0 0 1  0 0 1  inf 0 0" >expect &&
	test_cmp_numbers expect actual 0 &&
	gb_pixel out.txt 0 0 P.Z | awk "{ exit !(\$1 < -1e29) }" &&
	! grep -i nan out.txt
'

test_done
