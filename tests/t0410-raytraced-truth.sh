#!/bin/sh
test_description='reflect-shade -m raytraced against the path-traced references'
. "$srcdir/tests/lib.sh"

# The references beside the source tree, or where REFLECT_TRUTH says
# (../shared/truth/README.md: what they are and how they are scored).
truth="${REFLECT_TRUTH:-$srcdir/../shared/truth}"

# Relative RMSE over the eroded mask at 1024 rays, separable masking as
# Cycles 3.4 renders: the targets, with the reference's own noise (room-
# floor 0.0108, room-spheres 0.0067) under them.  Measured when written:
# 0.0117 and 0.0148; sampler=mis (the same integral, less noise) 0.0114 on
# room-floor.
for case in room-floor:0.031:vndf room-spheres:0.023:vndf room-floor:0.031:mis
do
	scene=${case%%:*}
	sampler=${case##*:}
	limit=${case#*:}
	limit=${limit%:*}
	if ! test -f "$truth/$scene.gbuf.exr"
	then
		test_skip "$scene at 1024 rays ($sampler)" "no references in $truth"
		continue
	fi
	test_expect_success "$scene: relative RMSE under $limit at 1024 rays ($sampler)" '
		reflect-import --box=-5,0,-5,5,4,5 --center=0,2,0 "$truth/$scene.gbuf.exr" |
			reflect-project >gbuf.rfl &&
		reflect-shade -m raytraced:samples=1024:masking=separable:sampler=$sampler --final \
			--env="$truth/$scene.probe.cube.exr" gbuf.rfl >shaded.rfl &&
		reflect-import "$truth/$scene.ref.exr" >ref.rfl &&
		"$builddir/tests/truthscore" shaded.rfl ref.rfl >score &&
		echo "$scene: $(cat score)" &&
		awk -v limit=$limit "{ exit !(\$1 > 30000 && \$2 < limit) }" score
	'
done

test_done
