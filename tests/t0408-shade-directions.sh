#!/bin/sh
test_description='any float lookup direction: the plain and vector samplers agree and stay inside the cube'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

# Level 0 holds 10 + f on face f (+X -X +Y -Y +Z -Z = 0..5), level k the
# value k: at roughness 0 a lookup names its face, at roughness 0.5
# (linear mapping, 3 steps: lod 1.5) it must read 1.5 whatever the face.
# 8 texels a face, so the centre u = v = 0.5 is between four texels of
# the face alone and reads its value exactly.
#
# The directions, with the face each must land on (- where the direction
# has no face and only agreement and bounds are asserted):
#   zero, and -0: -X, its centre (the documented choice) -> 11
#   denormals: (0,0,-2.3e-41) -> -Z 15; (1e-45,0,0) -> +X 10;
#     (1e-40,5e-41,-2e-41) -> +X, off centre -> -
#   huge: (3e38,-3e38,1) is a tie of x and y, and ties go to x -> -;
#     (1e30,1e-30,0) -> +X 10
#   infinite or NaN anywhere: refused by default; black (0) with
#     --invalid=zero, in the pass and the service
#   exact axes -> their faces; (1,1,0), (1,1,1), (-1,-1,-1): edges and
#     corners -> -
cat >dirs <<\EOF_DIRS
0 0 0 11
-0 -0 -0 11
0 0 -2.3e-41 15
1e-45 0 0 10
1e-40 5e-41 -2e-41 -
-1e-45 1e-45 0 -
3e38 -3e38 1 -
1e30 1e-30 0 10
inf 0 0 0
-inf inf 0 0
inf inf inf 0
nan 0 0 0
nan nan nan 0
0 nan 1 0
1 0 0 10
-1 0 0 11
0 1 0 12
0 -1 0 13
0 0 1 14
0 0 -1 15
1 1 0 -
1 1 1 -
-1 -1 -1 -
-1e-38 0 0 11
EOF_DIRS

test_expect_success 'the directions, at roughness 0 and 0.5' '
	level_chain chain.rfl 8 4 linear 10 &&
	awk "{ print \$1, \$2, \$3, 0 }" dirs | stream d0.txt 8 3 "D.X D.Y D.Z roughness" &&
	awk "{ print \$1, \$2, \$3, 0.5 }" dirs | stream d1.txt 8 3 "D.X D.Y D.Z roughness"
'

for r in 0 1
do
	test_expect_success "plain and vector reads agree (roughness file d$r)" '
		REFLECT_SIMD=off reflect-shade -h -f a -m none --invalid=zero --env=chain.rfl d'$r'.txt >plain &&
		reflect-shade -h -f a -m none --invalid=zero --env=chain.rfl d'$r'.txt >vector &&
		cmp_numbers plain vector 1e-5
	'
done

test_expect_success 'every read is finite and inside the cube' '
	for f in d0 d1
	do
		REFLECT_SIMD=off reflect-shade -f a -m none --invalid=zero --env=chain.rfl $f.txt >$f.out &&
		column $f.out spec.R spec.G spec.B >$f.spec &&
		awk "{ for (i = 1; i <= 3; i++) if (!(\$i >= 0 && \$i <= 15)) exit 1 }" $f.spec ||
		return 1
	done
'

test_expect_success 'a direction with a face reads that face, at lod 0' '
	paste -d " " dirs d0.spec | awk "\$4 != \"-\" { print \$4, \$4, \$4 }" >want &&
	paste -d " " dirs d0.spec | awk "\$4 != \"-\" { print \$5, \$6, \$7 }" >got &&
	cmp_numbers want got 1e-6
'

test_expect_success 'every finite direction reads lod 1.5 at roughness 0.5' '
	awk "{ v = \$4 == \"0\" ? 0 : 1.5; print v, v, v }" dirs >want &&
	cmp_numbers want d1.spec 1e-6
'

# The test plugin samples through the host's service, which reads
# through the pass's own kernels (plugin ABI 1.1): the same numbers, to
# the last bit or two.
test_expect_success 'the host service agrees with the pass' '
	radiance="$REFLECT_TEST_PLUGINS/shade_radiance.so" &&
	for f in d0 d1
	do
		reflect-shade -f a -m "$radiance" --invalid=zero --env=chain.rfl $f.txt >service.out &&
		column service.out spec.R spec.G spec.B >service &&
		cmp_numbers $f.spec service 1e-5 || return 1
	done
'

test_done
