#!/bin/sh
test_description='the classic modes against the path-traced references, as measured independently'
. "$srcdir/tests/lib.sh"

truth="${REFLECT_TRUTH:-$srcdir/../shared/truth}"

# Relative RMSE of R G B over the eroded mask, --final on a white metal,
# the references' probe prefiltered by reflect: the figures an
# independent implementation of the write-up's modes measured on the two
# scenes, which reflect's must match to 0.01.
for case in room-floor:none:0.566 room-floor:approx:0.492 room-floor:hdrp:0.456 \
	room-floor:godot:0.467 room-spheres:none:0.480 room-spheres:approx:0.308 \
	room-spheres:hdrp:0.390 room-spheres:godot:0.314
do
	scene=${case%%:*} rest=${case#*:}
	mode=${rest%%:*} want=${rest#*:}
	if ! test -f "$truth/$scene.gbuf.exr"
	then
		test_skip "$scene, $mode: $want" "no references in $truth"
		continue
	fi
	test_expect_success "$scene, $mode: $want within 0.01" '
		if ! test -f "$scene.g.rfl"
		then
			reflect-import --box=-5,0,-5,5,4,5 --center=0,2,0 "$truth/$scene.gbuf.exr" |
				reflect-project >"$scene.g.rfl" &&
			reflect-prefilter -o "$scene.env.rfl" "$truth/$scene.probe.cube.exr" 2>/dev/null &&
			reflect-import "$truth/$scene.ref.exr" >"$scene.ref.rfl"
		fi &&
		reflect-shade -m $mode --final --env="$scene.env.rfl" "$scene.g.rfl" >s.rfl &&
		{ reflect-compare -f a --mask --erode=1 s.rfl "$scene.ref.rfl" >score ||
			test $? = 3; } &&
		echo "$scene $mode: $(cat score)" &&
		awk -v want=$want "{ d = \$2 - want; exit !(d < 0.01 && d > -0.01) }" score
	'
done

test_done
