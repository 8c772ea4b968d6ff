#!/bin/sh
test_description='the classic modes against the path-traced references, as measured independently'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

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
		truth_setup "$truth" $scene &&
		reflect-shade -m $mode --final --env="$scene.env.rfl" "$scene.g.rfl" >s.rfl &&
		{ reflect-compare -f a --mask --erode=1 s.rfl "$scene.ref.rfl" >score ||
			test $? = 3; } &&
		echo "$scene $mode: $(cat score)" &&
		awk -v want=$want "{ d = \$2 - want; exit !(d < 0.01 && d > -0.01) }" score
	'
done

test_done
