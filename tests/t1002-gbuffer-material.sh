#!/bin/sh
test_description='per-object roughness, metallic, albedo and mask'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"

# Five spheres 2 m apart on the X axis; a 1x1 camera slides along them
# (--path=line keeps the view direction), so frame k sees sphere k+1 head
# on at P = (x, 0, 0.5).
test_expect_success 'setup' '
	cat >row.scene <<-\EOF &&
	probe box -10 -10 -10 10 10 10
	camera position -4 0 5 target -4 0 0 fov 10
	sphere center -4 0 0 radius 0.5 roughness 0.05
	sphere center -2 0 0 radius 0.5 smoothness 0.75
	sphere center  0 0 0 radius 0.5 roughness 0.5 metallic 0 albedo 0.2 0.4 0.6
	sphere center  2 0 0 radius 0.5 roughness 0.9 reflective off
	sphere center  4 0 0 radius 0.5
	EOF
	reflect-gbuffer -x 1 -y 1 -n 5 --path=line:4,0,5 -fa row.scene >out.txt
'

test_expect_success 'each frame sees its sphere head on' '
	gb_frame_pixels out.txt P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z objid >actual &&
	cat >expect <<-\EOF &&
	-4 0 0.5  0 0 1  0 0 1  1
	-2 0 0.5  0 0 1  0 0 1  2
	 0 0 0.5  0 0 1  0 0 1  3
	 2 0 0.5  0 0 1  0 0 1  4
	 4 0 0.5  0 0 1  0 0 1  5
	EOF
	test_cmp_numbers expect actual 1e-6
'

# Defaults for objects: roughness 0.5, metallic 1, albedo 1 1 1 (the
# white metal of the write-up's previews), reflective (mask 1);
# smoothness s is roughness 1 - s.
test_expect_success 'roughness, metallic, albedo and mask per object' '
	gb_frame_pixels out.txt roughness metallic albedo.R albedo.G albedo.B mask >actual &&
	cat >expect <<-\EOF &&
	0.05 1 1   1   1   1
	0.25 1 1   1   1   1
	0.5  0 0.2 0.4 0.6 1
	0.9  1 1   1   1   0
	0.5  1 1   1   1   1
	EOF
	test_cmp_numbers expect actual 1e-7
'

# 3x1 at 40 degrees: the left pixel looks 36 degrees off axis (x = -2/3,
# aspect 3) and meets the wall x = -10 before z = -10.
test_expect_success 'walls are not reflective, objects are' '
	cat >two.scene <<-\EOF &&
	probe box -10 -10 -10 10 10 10
	camera position 0 0 5 target 0 0 0 fov 40
	rect center 0 0 0 normal 0 0 1 size 1 1 roughness 0.125
	EOF
	reflect-gbuffer -x 3 -y 1 -fa two.scene >out2.txt &&
	gb_pixel out2.txt 0 0 mask roughness objid >actual &&
	gb_pixel out2.txt 1 0 mask roughness objid >>actual &&
	cat >expect <<-\EOF &&
	0 1 -2
	1 0.125 1
	EOF
	test_cmp_numbers expect actual 0
'

test_done
