#!/bin/sh
test_description='reflect-shade -m raytraced:filtering=stochastic: threads, default, mean'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

npix=$((32 * 24))

# With pattern=deterministic every seed draws the same rays, so the
# seeds change only the levels that filtering=stochastic picks: their
# mean must be the trilinear render, which reads the same rays at the
# same lods.  Few rays, so the lods are high and the levels far apart.
m=raytraced:samples=4:pattern=deterministic

test_expect_success 'setup: a small frame, a small room' '
	reflect-gbuffer -x 32 -y 24 | reflect-project >scene.rfl &&
	reflect-prefilter --size=32 -o room.rfl 2>/dev/null
'

for o in filtering=stochastic filtering=stochastic:sampler=mis \
	filtering=stochastic:samples=3:animate=1:seed=9 filtering=stochastic:pattern=white
do
	test_expect_success "$o: the bytes do not depend on the thread count" '
		reflect-shade -h -j1 -m raytraced:$o --env=room.rfl scene.rfl >j1 &&
		reflect-shade -h -j2 -m raytraced:$o --env=room.rfl scene.rfl >j2 &&
		reflect-shade -h -j5 -m raytraced:$o --env=room.rfl scene.rfl >j5 &&
		test $(wc -c <j1) -eq $((npix * (31 + 3) * 4)) &&
		cmp j1 j2 &&
		cmp j1 j5
	'
done

test_expect_success 'the default is trilinear, and stochastic reads differ from it' '
	reflect-shade -h -m raytraced --env=room.rfl scene.rfl >default &&
	reflect-shade -h -m raytraced:filtering=trilinear --env=room.rfl scene.rfl >tri &&
	reflect-shade -h -m raytraced:filtering=stochastic --env=room.rfl scene.rfl >st &&
	cmp default tri &&
	! cmp -s tri st
'

# Ranges first=0 and 5 of total=8 take the numbers of rays 0 .. 7, as one
# run of 8 does: merged, the same sum in another order, within t0520's
# bound of float sums (2.4e-6 of the value).
test_expect_success 'two ranges of rays read the levels one run does' '
	reflect-shade -fa -m raytraced:filtering=stochastic:samples=8 --env=room.rfl \
		scene.rfl >full.txt &&
	{
		reflect-shade -m raytraced:filtering=stochastic:samples=5:total=8 \
			--env=room.rfl scene.rfl &&
		reflect-shade -m raytraced:filtering=stochastic:samples=3:first=5:total=8 \
			--env=room.rfl scene.rfl
	} | reflect-accumulate -fa >merged.txt &&
	column full.txt spec.R spec.G spec.B >a &&
	column merged.txt spec.R spec.G spec.B >b &&
	test $(wc -l <a) -eq $npix &&
	paste a b | awk "{
		for (k = 1; k <= 3; k++) {
			d = \$k - \$(k + 3); d = d < 0 ? -d : d
			s = \$k < 0 ? -\$k : \$k
			if (s > 0 && d / s > r) r = d / s
		}
	} END { print \"largest relative difference\", r + 0; exit !(r <= 2.4e-6) }"
'

# ratio TRILINEAR: over the pixels, the sum of (mean of the 32 seeds -
# TRILINEAR)^2 over the sum of the variances of those means (each
# pixel's sample variance / 32, plus 1e-6 of the value squared for the
# different rounding of one level read and two blended).  For an
# unbiased mean its expectation is 1; a pixel can be the same for all 32
# seeds (a ray whose lod is 1.96 picks level 2 with probability 0.3), so
# no pixel is tested alone.  Also "sum": of mean - TRILINEAR, whose
# deviation is dev.
ratio () {
	paste "$1" $(seq -f s%g 1 32) | awk -v S=32 '{
		t = $1; m = 0; q = 0
		for (k = 2; k <= S + 1; k++) m += $k
		m /= S
		for (k = 2; k <= S + 1; k++) q += ($k - m) ^ 2
		var = q / (S - 1); e = 1e-6 * (t < 0 ? -t : t) + 1e-9
		if (var > 0) n++
		num += (m - t) ^ 2; den += var / S + e * e; d += m - t
	} END { printf "%d %.4f %.4g %.4g\n", n, num / den, d, sqrt(den) }'
}

# Seeds 1-32 gave a ratio of 0.87, seeds 33-64 0.91, the sums 0.3 and
# 1.3 deviations: within 0.5 .. 1.8 and 4 deviations.  The trilinear
# render of lods half a level lower (frames=2: twice the rays share the
# lobe) gives 55: the bounds tell a bias of a fraction of a level.
test_expect_success 'the mean over 32 seeds is the trilinear render' '
	reflect-shade -fa -m $m --env=room.rfl scene.rfl >tri.txt &&
	column tri.txt spec.R >tri &&
	test $(wc -l <tri) -eq $npix &&
	reflect-shade -fa -m $m:frames=2 --env=room.rfl scene.rfl >lower.txt &&
	column lower.txt spec.R >lower &&
	for s in $(seq 1 32)
	do
		reflect-shade -fa -m $m:filtering=stochastic --seed=$s --env=room.rfl \
			scene.rfl >s.txt &&
		column s.txt spec.R >s$s &&
		test $(wc -l <s$s) -eq $npix || return 1
	done &&
	ratio tri >r && ratio lower >rl &&
	read n r d dev <r && read nl rl dl devl <rl &&
	echo "pixels that vary $n, ratio $r, sum $d, deviation $dev; half a level lower: $rl" &&
	awk -v n=$n -v r=$r -v d=$d -v dev=$dev -v rl=$rl -v npix=$npix "BEGIN {
		exit !(n > npix / 2 && r > 0.5 && r < 1.8 && (d < 0 ? -d : d) < 4 * dev &&
			rl > 10)
	}"
'

test_done
