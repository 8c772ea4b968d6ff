#!/bin/sh
test_description='reflect-shade -m raytraced: threads, frames, convergence, refusals'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

# Pixels of a small frame; two frames of the same view (FRAME=0 and 1).
npix=$((48 * 32))

# rmse A B: root mean square difference of two one-number-a-line files.
rmse () {
	paste "$1" "$2" | awk '{ d = $1 - $2; s += d * d; n++ } END { printf "%.6g\n", sqrt(s / n) }'
}

# corr A B R: correlation of A - R and B - R (the noise of two renders).
corr () {
	paste "$1" "$2" "$3" | awk '{
		a = $1 - $3; b = $2 - $3; sa += a; sb += b; saa += a * a; sbb += b * b
		sab += a * b; n++
	} END {
		ca = saa / n - (sa / n) ^ 2; cb = sbb / n - (sb / n) ^ 2
		printf "%.4f\n", (sab / n - sa * sb / n / n) / sqrt(ca * cb)
	}'
}

test_expect_success 'setup: two frames of a small scene, a small room' '
	reflect-gbuffer -x 48 -y 32 -n 2 | reflect-project >scene.rfl &&
	reflect-prefilter --size=32 -o room.rfl 2>/dev/null &&
	reflect-shade -fa -m raytraced:samples=2048:pattern=deterministic --env=room.rfl \
		scene.rfl >ref.txt &&
	column ref.txt spec.G | head -n $npix >ref
'

for m in raytraced raytraced:pattern=deterministic raytraced:estimator=original \
	raytraced:mipoffset=1:masking=separable raytraced:samples=3:animate=1:seed=9 \
	raytraced:sampler=mis raytraced:sampler=mis:pattern=white:samples=100
do
	test_expect_success "$m: the bytes do not depend on the thread count" '
		reflect-shade -h -j1 -m $m --final --env=room.rfl scene.rfl >j1 &&
		reflect-shade -h -j2 -m $m --final --env=room.rfl scene.rfl >j2 &&
		reflect-shade -h -j5 -m $m --final --env=room.rfl scene.rfl >j5 &&
		test $(wc -c <j1) -eq $((2 * npix * (23 + 8 + 3 + 3 + 3) * 4)) &&
		cmp j1 j2 &&
		cmp j1 j5
	'
done

test_expect_success 'it writes spec and, with --final, R G B; every value finite' '
	reflect-shade -fa -m raytraced:samples=8 --final --env=room.rfl scene.rfl >out.txt &&
	test_grep "^SHADE=raytraced:samples=8$" out.txt &&
	test_grep "^CHANNELS=.* spec.R spec.G spec.B R G B diffuse.R diffuse.G diffuse.B$" out.txt &&
	! grep -i "nan\|inf" out.txt | grep -v "^[A-Z_]*=" | grep -q . &&
	column out.txt spec.R spec.G spec.B R G B | awk "NF != 6 { exit 1 }"
'

test_expect_success 'more rays, less error: 4, 16, 64 rays against 2048' '
	for k in 4 16 64
	do
		reflect-shade -fa -m raytraced:samples=$k --env=room.rfl scene.rfl >k$k.txt &&
		column k$k.txt spec.G | head -n $npix >k$k &&
		rmse k$k ref >e$k || return 1
	done &&
	awk -v a="$(cat e4)" -v b="$(cat e16)" -v c="$(cat e64)" \
		"BEGIN { exit !(b < 0.7 * a && c < 0.7 * b) }"
'

test_expect_success 'without animate, frame 1 repeats frame 0' '
	reflect-shade -fa -m raytraced:samples=1 --env=room.rfl scene.rfl >still.txt &&
	column still.txt spec.G >still &&
	head -n $npix still >f0 &&
	tail -n $npix still >f1 &&
	cmp f0 f1
'

# frames FILE N: one file per frame (f0 f1 ...) of a one-column file of N
# frames, and mean: the per-pixel mean of frames 2 .. N-1.
frames () {
	awk -v npix=$npix -v n=$2 '{
		f = int((NR - 1) / npix); print > ("f" f)
		if (f >= 2) s[(NR - 1) % npix] += $1
	} END {
		for (i = 0; i < npix; i++) printf "%.9g\n", s[i] / (n - 2) > "mean"
	}' "$1"
}

test_expect_success 'setup: 66 frames of the same view' '
	reflect-gbuffer -x 48 -y 32 -n 66 | reflect-project >frames.rfl
'

# One ray a pixel, a new pattern each frame: against the mean of 64 other
# frames (the one-ray estimator's own expectation, blur of its footprint
# included: frames=1 keeps every frame's footprint that of one ray), the
# noise of frame 0 and of frame 1 must be unrelated.  The
# original's sliding seed, which hands frame 1 frame 0's second number,
# or a pattern that ignores FRAME, would show here.
test_expect_success 'animate=1 (white): frame 1 does not reuse frame 0'"'"'s numbers' '
	reflect-shade -fa -m raytraced:samples=1:animate=1:pattern=white:frames=1 \
		--env=room.rfl frames.rfl >anim.txt &&
	column anim.txt spec.G >anim &&
	frames anim 66 &&
	! cmp -s f0 f1 &&
	c=$(corr f0 f1 mean) &&
	echo "correlation of the noise of frames 0 and 1: $c" &&
	awk -v c="$c" "BEGIN { exit !(c < 0.1 && c > -0.1) }" &&
	c=$(corr f0 f0 mean) &&
	test "$c" = 1.0000
'

# The Hammersley sets (shifted per pixel by blue noise, or not) move by
# the R2 step each frame: every pixel's series over frames is itself
# low-discrepancy, frame 1's error leans against frame 0's rather than
# repeating it, and the mean of 64 frames is far closer to the converged
# value than one frame (frames=64: each ray's footprint that of 64 rays,
# as the mean will have them).
for p in blue deterministic
do
	test_expect_success "animate=1 ($p): frames move and average out" '
		reflect-shade -fa -m raytraced:samples=1:animate=1:pattern=$p:frames=64 \
			--env=room.rfl frames.rfl >anim.txt &&
		column anim.txt spec.G >anim &&
		frames anim 66 &&
		! cmp -s f0 f1 &&
		c=$(corr f0 f1 mean) &&
		echo "correlation of the noise of frames 0 and 1: $c" &&
		awk -v c="$c" "BEGIN { exit !(c < 0.1) }" &&
		one=$(rmse f0 ref) &&
		many=$(rmse mean ref) &&
		echo "error of one frame $one, of the mean of 64 $many" &&
		awk -v a="$one" -v b="$many" "BEGIN { exit !(b < 0.25 * a) }"
	'
done

test_expect_success 'the seed changes the noise, and only the noise' '
	reflect-shade -fa -m raytraced:samples=16:seed=1 --env=room.rfl scene.rfl >s1.txt &&
	reflect-shade -fa -m raytraced:samples=16 --seed=1 --env=room.rfl scene.rfl >s2.txt &&
	column s1.txt spec.G | head -n $npix >s1 &&
	column s2.txt spec.G | head -n $npix >s2 &&
	column k16.txt spec.G | head -n $npix >s0 &&
	cmp s1 s2 &&
	! cmp -s s0 s1 &&
	awk -v a="$(rmse s0 ref)" -v b="$(rmse s1 ref)" "BEGIN { exit !(b < 1.5 * a && a < 1.5 * b) }"
'

test_expect_success 'bad parameters: refused with the name and what is allowed' '
	test_expect_code 1 reflect-shade -m raytraced:samples=0 --env=room.rfl scene.rfl 2>err &&
	test_one_line_message reflect-shade err &&
	test_grep "samples" err &&
	test_expect_code 1 reflect-shade -m raytraced:pattern=purple --env=room.rfl \
		scene.rfl 2>err &&
	test_grep "purple" err &&
	test_grep "white|blue|deterministic" err &&
	test_expect_code 1 reflect-shade -m raytraced:estimator=guess --env=room.rfl \
		scene.rfl 2>err &&
	test_grep "exact|original" err &&
	test_expect_code 1 reflect-shade -m raytraced:samples=2.5 --env=room.rfl \
		scene.rfl 2>err &&
	test_grep "samples" err
'

test_expect_success 'sampler=mis: refused with estimator=original, named choices' '
	test_expect_code 1 reflect-shade -m raytraced:sampler=mis:estimator=original \
		--env=room.rfl scene.rfl 2>err &&
	test_one_line_message reflect-shade err &&
	test_grep "estimator=exact" err &&
	test_expect_code 1 reflect-shade -m raytraced:sampler=light --env=room.rfl \
		scene.rfl 2>err &&
	test_grep "vndf|mis" err
'

# Below 4 rays the table would cost more than twice the rays
# (reflect-mode-raytraced(7)): the lobe alone, the same bytes.  From 4 rays
# on (a three-column table up to 24, a larger one above), the mixture
# moves the numbers of the pixels that see the windows, and only those.
test_expect_success 'sampler=mis: the lobe alone below 4 rays, moved from 4' '
	reflect-shade -h -m raytraced:samples=3 --env=room.rfl scene.rfl >v3 &&
	reflect-shade -h -m raytraced:samples=3:sampler=mis --env=room.rfl scene.rfl >m3 &&
	cmp v3 m3 &&
	for k in 4 16 64
	do
		reflect-shade -fa -m raytraced:samples=$k --env=room.rfl scene.rfl >v.txt &&
		reflect-shade -fa -m raytraced:samples=$k:sampler=mis --env=room.rfl \
			scene.rfl >m.txt &&
		column v.txt spec.G | head -n $npix >v &&
		column m.txt spec.G | head -n $npix >m &&
		moved=$(paste v m | awk "\$1 != \$2" | wc -l) &&
		echo "$k rays: $moved of $npix pixels moved" &&
		test $moved -gt 0 &&
		test $moved -lt $npix || return 1
	done
'

# Ng is optional (plugin ABI 1.1): without it no ray is cut by the
# geometry, and where the shading normal is the geometric one (no normal
# map) nothing changes at all.
test_expect_success 'a stream without Ng: shaded, the same where N is Ng' '
	reflect-gbuffer -x 48 -y 32 -c P,N,V,roughness,mask,objid,depth |
		reflect-project >no-ng.rfl &&
	reflect-gbuffer -x 48 -y 32 -c P,N,Ng,V,roughness,mask,objid,depth |
		reflect-project >with-ng.rfl &&
	reflect-shade -fa -m raytraced:samples=16 --env=room.rfl no-ng.rfl >no-ng.txt &&
	reflect-shade -fa -m raytraced:samples=16 --env=room.rfl with-ng.rfl >with-ng.txt &&
	column no-ng.txt spec.R spec.G spec.B >a &&
	column with-ng.txt spec.R spec.G spec.B >b &&
	test_line_count $npix a &&
	! grep -i "nan\|inf" a &&
	same=$(paste -d" " a b | awk "\$1 == \$4 && \$2 == \$5 && \$3 == \$6" | wc -l) &&
	echo "$same of $npix pixels alike" &&
	test $same -gt $((npix * 9 / 10)) &&
	! cmp -s a b
'

test_done
