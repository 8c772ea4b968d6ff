#!/bin/sh
test_description='reflect-trace: the ground truth of a scene, by closed forms and against Cycles'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"
. "$srcdir/tests/shade-lib.sh"

truth="${REFLECT_TRUTH:-$srcdir/../shared/truth}"

# uniform_sky FILE: a prefiltered chain of 4 levels of radiance 1.
uniform_sky () {
	awk 'BEGIN { n = 8
		for (k = 0; k < 4; k++) {
			printf "#?REFLECT1\nENVMAP=CUBE\nLEVEL=%d\nLEVELS=4\nPREFILTER=ggx\n", k
			printf "MAPPING=unity\nSTEPS=3\nNCOLS=%d\nNROWS=%d\nNCOMP=3\n", n, 6 * n
			printf "CHANNELS=R G B\nFORMAT=ascii\n\n"
			for (j = 0; j < 6 * n * n; j++) print 1, 1, 1
			n = n / 2
		} }' >"$1"
}
examples="$srcdir/doc/examples"

# A room of uniform radiance 2: every reflected ray sees 2, so a pixel is
# 2 times the lobe's directional albedo; a mirror's (roughness 0) is 1.
test_expect_success 'a mirror in a uniformly emitting room gives the emission' '
	cat >mirror.scene <<-\EOF &&
	probe box -5 -5 -5 5 5 5
	room emission 2 2 2
	camera position 0 1 2 target 0 0 -1 fov 40
	rect plane y 0 min -4 -4 max 4 4 roughness 0
	EOF
	reflect-trace -x 4 -y 4 --samples=64 -fa mirror.scene >m.txt &&
	column m.txt mask R G B >got &&
	awk "\$1 == 1 { n++; for (k = 2; k <= 4; k++) if (\$k < 1.9999 || \$k > 2.0001) bad = 1 }
	     END { exit bad || n < 8 }" got
'

# The white furnace: a room of radiance 1 and a white GGX floor.  With
# height-correlated masking a pixel is the albedo A + B of the lobe at
# its n.v, which reflect-shade --final of the same pixels reads from
# the DFG table (integrated by other code, on a grid): within 1 %.
test_expect_success 'the white furnace gives the directional albedo of the DFG table' '
	for r in 0.2 0.5 0.9
	do
		cat >furnace.scene <<-EOF &&
		probe box -50 -50 -50 50 50 50
		room emission 1 1 1
		camera position 0 1 3 target 0 0 -2 fov 70
		rect plane y 0 min -40 -40 max 40 40 roughness $r
		EOF
		reflect-trace -x 8 -y 6 --samples=4096 --masking=correlated -fa \
			furnace.scene >t.txt &&
		uniform_sky sky.rfl &&
		reflect-gbuffer -x 8 -y 6 furnace.scene | reflect-project |
			reflect-shade -fa -m none --final --env=sky.rfl >s.txt &&
		column t.txt mask R >a &&
		column s.txt R >b &&
		paste a b | awk -v r=$r "\$1 == 1 { n++; d = (\$2 - \$3) / \$3; if (d < 0) d = -d
			if (d > worst) worst = d }
			END { printf \"roughness %s: worst %.4f\n\", r, worst; exit !(n > 10 && worst < 0.01) }" ||
		return 1
	done
'

test_expect_success 'separable masking is darker than correlated, by Cycles'"'"'s margin' '
	cat >furnace.scene <<-\EOF &&
	probe box -50 -50 -50 50 50 50
	room emission 1 1 1
	camera position 0 1 3 target 0 0 -2 fov 70
	rect plane y 0 min -40 -40 max 40 40 roughness 0.9
	EOF
	reflect-trace -x 4 -y 3 --samples=2048 -fa furnace.scene >sep.txt &&
	reflect-trace -x 4 -y 3 --samples=2048 --masking=correlated -fa furnace.scene >cor.txt &&
	column sep.txt mask R >a &&
	column cor.txt R >b &&
	paste a b | awk "\$1 == 1 { n++; if (!(\$2 < \$3 * 0.99)) bad = 1 } END { exit bad || !n }"
'

test_expect_success 'two halves: independent, and their mean is the pixel' '
	reflect-trace -x 16 -y 9 --samples=64 --halves -fa >h.txt &&
	column h.txt R half1.R half2.R mask >got &&
	awk "{ m = (\$2 + \$3) / 2; d = \$1 - m; if (d < 0) d = -d; if (d > 1e-5 * (1 + \$1)) bad = 1
	       if (\$4 == 1 && \$2 != \$3) differ++ }
	     END { exit bad || differ < 20 }" got
'

test_expect_success 'the same bytes at 1 and 2 threads; a seed moves the noise' '
	reflect-trace -x 24 -y 12 --samples=16 -j 1 -h >one &&
	reflect-trace -x 24 -y 12 --samples=16 -j 2 -h >two &&
	cmp one two &&
	reflect-trace -x 24 -y 12 --samples=16 --seed=5 -h >other &&
	! cmp -s one other
'

# A room alone is read a chunk of 64 rays at a time, in float, by vector
# code; a scene with an object the reflected rays could meet takes each
# ray through rf__trace and the walls one by one, in double.  An object
# far outside the room is never met, so the two must agree but for the
# rays within float rounding of an edge of the pattern: measured at
# 80x60 and 1024 samples, a relative RMSE of 1.3e-5 and at most 6.7e-4
# (2 pixels of 4800 over 1e-6); held to 1e-4 and 0.05 (one window-edge
# ray of 1024 that changes sides moves a pixel by 0.017).  A wall
# misread, a face or a window wrong in the chunk is far beyond.
test_expect_success 'the walls by the chunk equal the walls ray by ray' '
	cp "$examples/room-floor.scene" alone.scene &&
	cp alone.scene far.scene &&
	echo "sphere center 0 50 0 radius 0.1 reflective off" >>far.scene &&
	reflect-trace -x 80 -y 60 --samples=1024 alone.scene >alone.rfl &&
	reflect-trace -x 80 -y 60 --samples=1024 far.scene >far.rfl &&
	# exit 3: some pixel over the default threshold of 1e-6
	{ reflect-compare -f a -c R,G,B alone.rfl far.rfl >chunk.score || test $? = 3; } &&
	cat chunk.score &&
	awk "{ exit !(\$2 < 1e-4 && \$4 < 0.05) }" chunk.score &&
	! cmp -s alone.rfl far.rfl
'

test_expect_success 'walls are their emission; bad options are refused' '
	reflect-trace -x 16 -y 9 --samples=4 -fa >w.txt &&
	reflect-gbuffer -x 16 -y 9 -fa -c mask,emission >g.txt &&
	column w.txt mask R G B >a &&
	column g.txt mask emission.R emission.G emission.B >b &&
	paste a b | awk "\$1 == 0 && (\$2 != \$6 || \$3 != \$7 || \$4 != \$8) { bad = 1 } END { exit bad }" &&
	test_expect_code 1 reflect-trace --samples=0 >/dev/null 2>err &&
	test_grep "samples" err &&
	test_expect_code 1 reflect-trace --masking=both >/dev/null 2>err &&
	test_grep "masking: .both. is not separable or correlated" err &&
	test_expect_code 1 reflect-trace --objects=some >/dev/null 2>err &&
	test_grep "objects: .some. is not hidden or visible" err &&
	test_expect_code 1 reflect-trace --samples=1 --halves >/dev/null 2>err &&
	test_grep "2 or more for halves" err
'

# With the reflective objects hidden the scene is its box, and the box
# projection of any point inside it is exact: the raytraced mode through
# the probe reflect-capture bakes from the same scene integrates the same
# lobe against the same walls.  At 1024 samples each the two differ by
# their noise and the probe's texels (measured: 0.014), where the
# classic none misses by 0.47.
test_expect_success 'reflect-trace and raytraced through a captured probe agree' '
	s="$examples/room-spheres.scene" &&
	reflect-trace -x 80 -y 60 --samples=1024 "$s" >t.rfl &&
	reflect-capture --hide-reflective "$s" >cap.rfl &&
	reflect-gbuffer -x 80 -y 60 -c P,N,Ng,V,roughness,mask,objid,depth "$s" |
		reflect-project >g.rfl &&
	reflect-shade -m raytraced:samples=1024:masking=separable --final --env=cap.rfl \
		g.rfl >r.rfl 2>/dev/null &&
	{ reflect-compare -f a --mask --erode=1 r.rfl t.rfl >score || test $? = 3; } &&
	cat score &&
	awk "{ exit !(\$2 < 0.025 && \$6 > 2000) }" score &&
	reflect-shade -m none --final --env=cap.rfl g.rfl >n.rfl 2>/dev/null &&
	{ reflect-compare -f a --mask --erode=1 n.rfl t.rfl >score || test $? = 3; } &&
	awk "{ exit !(\$2 > 0.3) }" score
'

# The references' own noise is 0.0108 and 0.0067 (their README); at 4096
# samples reflect's adds less than that.
for case in room-floor:0.020 room-spheres:0.012
do
	scene=${case%%:*} bound=${case#*:}
	if ! test -f "$truth/$scene.ref.exr"
	then
		test_skip "$scene: against Cycles" "no references in $truth"
		continue
	fi
	test_expect_success "$scene: within $bound of Cycles over the eroded mask" '
		reflect-trace -x 320 -y 240 --samples=4096 "$examples/$scene.scene" >t.rfl &&
		reflect-import "$truth/$scene.ref.exr" >ref.rfl 2>/dev/null &&
		# exit 3: over the default threshold of 1e-6, as any render is
		{ reflect-compare -f a -c R,G,B --mask --erode=1 t.rfl ref.rfl >score ||
			test $? = 3; } &&
		cat score &&
		awk -v bound=$bound "{ exit !(\$2 <= bound) }" score
	'
done

test_done
