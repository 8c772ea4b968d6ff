#!/bin/sh
test_description='-n frames with FRAME keys, and camera paths for animated sequences'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"

test_expect_success 'setup' '
	cat >s.scene <<-\EOF
	probe center 0 1.5 0 box -3 0 -2 3 3 2
	camera position 0 1.6 2 target 0 1 0 fov 50
	sphere center 0 1 0 radius 0.5 roughness 0.2
	EOF
'

# CAMERA and FRAME keys of every frame, numbers rounded to 6 decimals.
cameras () {
	awk -F= '
	/^CAMERA=/ { n = split($2, v, " "); s = ""
		for (i = 1; i <= n; i++) s = s sprintf(" %.6f", v[i]); cam = s }
	/^FRAME=/ { print $2 cam }' "$1"
}

test_expect_success '-n 3 writes three frames, FRAME=0..2' '
	reflect-gbuffer -x 4 -y 3 -n 3 s.scene >out.rf &&
	reflect-info out.rf >info &&
	test "$(grep -c "^frame " info)" -eq 3 &&
	grep "FRAME=" info | tr -d "\t" >actual &&
	printf "FRAME=0\nFRAME=1\nFRAME=2\n" >expect &&
	cmp expect actual
'

test_expect_success 'without a path every frame is the same image' '
	reflect-gbuffer -x 4 -y 3 -n 3 -fa s.scene >out.txt &&
	gb_data out.txt >all &&
	test_line_count 36 all &&
	sed -n 1,12p all >f0 && sed -n 13,24p all >f1 && sed -n 25,36p all >f2 &&
	cmp f0 f1 && cmp f0 f2
'

# A quarter turn a frame about the vertical through the target (0,1,0):
# +Z goes to +X, then -Z, then -X; the camera keeps its height.
test_expect_success '--orbit=360 turns the camera about its target' '
	reflect-gbuffer -x 4 -y 3 -n 4 --orbit=360 -fa s.scene >out.txt &&
	cameras out.txt >actual &&
	cat >expect <<-\EOF &&
	0  0 1.6  2  0 1 0  0 1 0  50
	1  2 1.6  0  0 1 0  0 1 0  50
	2  0 1.6 -2  0 1 0  0 1 0  50
	3 -2 1.6  0  0 1 0  0 1 0  50
	EOF
	test_cmp_numbers expect actual 1e-6
'

# The centre pixel looks straight at the sphere's centre, so it sees
# P = C - r d: from (0,1.6,2), d = (0,-0.6,-2)/2.08806, P = (0, 1.14367394,
# 0.478913143); then the same turned a quarter a frame.
test_expect_success 'an orbiting camera keeps looking at the target' '
	reflect-gbuffer -x 3 -y 3 -n 4 --path=orbit:360 -fa -c objid,P s.scene >out.txt &&
	gb_data out.txt |
	awk "NR % 9 == 5 { printf \"%d %.7f %.7f %.7f\\n\", \$1, \$2, \$3, \$4 }" >actual &&
	cat >expect <<-\EOF &&
	1  0           1.14367394  0.478913143
	1  0.478913143 1.14367394  0
	1  0           1.14367394 -0.478913143
	1 -0.478913143 1.14367394  0
	EOF
	test_cmp_numbers expect actual 1e-6
'

test_expect_success '--path=line moves position and target to the end' '
	reflect-gbuffer -x 2 -y 2 -n 3 --path=line:1,1.6,1 -fa s.scene >out.txt &&
	cameras out.txt >actual &&
	cat >expect <<-\EOF &&
	0  0   1.6 2    0   1 0    0 1 0  50
	1  0.5 1.6 1.5  0.5 1 -0.5 0 1 0  50
	2  1   1.6 1    1   1 -1   0 1 0  50
	EOF
	test_cmp_numbers expect actual 1e-6
'

test_expect_success 'bad paths are refused' '
	test_expect_code 1 reflect-gbuffer --path=spiral:3 s.scene 2>err &&
	test_grep "neither orbit:DEGREES nor line:X,Y,Z" err &&
	test_expect_code 1 reflect-gbuffer --path=line:1,2 s.scene 2>err &&
	test_grep "needs 3 comma-separated numbers" err &&
	test_expect_code 1 reflect-gbuffer -n 0 s.scene 2>err &&
	test_one_line_message reflect-gbuffer err
'

test_done
