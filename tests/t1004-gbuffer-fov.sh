#!/bin/sh
test_description='image size and field-of-view geometry of the camera rays'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"

test_expect_success 'default size is 640x360, -x -y set it' '
	reflect-gbuffer >out.rf &&
	reflect-info out.rf >info &&
	test_grep "NCOLS=640$" info &&
	test_grep "NROWS=360$" info &&
	reflect-gbuffer -x 7 -y 3 | reflect-info >info &&
	test_grep "NCOLS=7$" info &&
	test_grep "NROWS=3$" info &&
	test_grep "NCOMP=23$" info
'

# From the centre of a 20 m cube, looking along -Z, fov 90 (tan 45 = 1),
# 4x2 pixels (aspect 2).  Pixel (i, j) looks along
#   (x * 1 * 2, y * 1, -1),  x = 2(i + 0.5)/4 - 1,  y = 1 - 2(j + 0.5)/2
# so the edge column (x = -0.75) sees (-1.5, 0.5, -1): the wall x = -10 at
# P = (-10, 3.333, -6.667), depth sqrt(155.556) = 12.4721913; the inner
# column (x = -0.25) sees (-0.5, 0.5, -1): the wall z = -10 at (-5, 5, -10),
# depth sqrt(150) = 12.2474487.
test_expect_success 'every pixel of a 4x2 image sees its ray' '
	cat >cube.scene <<-\EOF &&
	probe box -10 -10 -10 10 10 10
	camera position 0 0 0 target 0 0 -1 up 0 1 0 fov 90
	EOF
	reflect-gbuffer -x 4 -y 2 -fa -c P,depth,objid cube.scene >out.txt &&
	gb_data out.txt >actual &&
	cat >expect <<-\EOF &&
	-10  3.33333333 -6.66666667 12.4721913 -2
	 -5  5          -10         12.2474487 -6
	  5  5          -10         12.2474487 -6
	 10  3.33333333 -6.66666667 12.4721913 -1
	-10 -3.33333333 -6.66666667 12.4721913 -2
	 -5 -5          -10         12.2474487 -6
	  5 -5          -10         12.2474487 -6
	 10 -3.33333333 -6.66666667 12.4721913 -1
	EOF
	test_cmp_numbers expect actual 2e-6
'

# A tall 1x3 image at fov 60: the top pixel's centre is at y = 2/3, so
# from (0,0,0) along -Z it meets the wall z = -1 at height
# (2/3) tan 30 = 0.384900179.
test_expect_success 'the vertical field of view is the one given' '
	cat >tall.scene <<-\EOF &&
	probe box -1 -1 -1 1 1 1
	camera position 0 0 0 target 0 0 -1 fov 60
	EOF
	reflect-gbuffer -x 1 -y 3 -fa -c P tall.scene >out.txt &&
	gb_data out.txt >actual &&
	cat >expect <<-\EOF &&
	0  0.384900179 -1
	0  0           -1
	0 -0.384900179 -1
	EOF
	test_cmp_numbers expect actual 1e-7
'

# Looking along (3, 4, 0)/5 from (1, 2, 3) with +Z up: the ceiling y = 10
# is 8 m up, reached after 10 m at (7, 10, 3).
test_expect_success 'a target off the axes and another up vector' '
	cat >tilt.scene <<-\EOF &&
	probe box -10 -10 -10 10 10 10
	camera position 1 2 3 target 4 6 3 up 0 0 1 fov 20
	EOF
	reflect-gbuffer -x 1 -y 1 -fa -c P,V,depth tilt.scene >out.txt &&
	gb_data out.txt >actual &&
	echo "7 10 3  -0.6 -0.8 0  10" >expect &&
	test_cmp_numbers expect actual 1e-6
'

test_done
