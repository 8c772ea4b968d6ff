#!/bin/sh
test_description='each shade mode gives the spec formula at chosen inputs'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

# 7 roughnesses x 10 hit distances = 70 tuples, with the probe distance
# and N.V cycling through their own lists; they cover contact, the
# clamps at 0 and at `distance`, points behind (d < 0), no hit (inf),
# |R'| = 0, grazing and back-facing views.
test_expect_success 'make the tuples' '
	awk "BEGIN {
		np = split(\"0 0.05 0.25 0.5 0.75 0.9 1\", pr, \" \")
		nd = split(\"-1 0 0.001 0.6267 2.6297 5.999 6 6.5 12 inf\", d, \" \")
		nl = split(\"3.5424 0.6267 1 0 100 2.6297 7\", l, \" \")
		nn = split(\"1 0.8 0.4056 0.1 0 -0.3\", nv, \" \")
		for (i = 1; i <= np; i++)
			for (j = 1; j <= nd; j++) {
				k++
				c = nv[k % nn + 1]
				printf \"%s %s %s 0 1 0 %.9g %s 0 0 0 1\n\", pr[i], d[j],
					l[k % nl + 1], sqrt(1 - c * c), c
			}
	}" >data &&
	test_line_count 70 data &&
	stream in.txt 70 1 "roughness hit.dist probe.dist N.X N.Y N.Z V.X V.Y V.Z D.X D.Y D.Z" <data &&
	level_chain chain.rfl 64 7 unity
'

# The formulas of spec sections 3, 4.1, 5.1 and 6.2 in perceptual
# roughness (pr = mip / 6), with the edge cases of Part A #3, written
# again here: they share no code with the plugins.
expected () {
	awk -v mode="$1" -v clamp="${2:-1}" -v dist="${3:-6}" -v power="${4:-4}" '
	function sat(x) { return x > 0 ? (x < 1 ? x : 1) : 0 }
	function lerp(a, b, t) { return a + (b - a) * t }
	{
		pr = $1; d = $2; l = $3; nv = $5 * $8
		inf = (d == "inf")
		if (mode == "none") r = pr
		else if (mode == "approx") {
			if (inf) r = pr
			else {
				if (clamp) d = d < 0 ? 0 : (d > dist ? dist : d)
				r = sat(lerp(0, 6 * pr, d / dist) / 6)
			}
		} else if (mode == "hdrp") {
			if (pr == 0) r = 0
			else if (inf) r = pr
			else {
				if (d <= 0) c = 0
				else if (l == 0) c = pr
				else { c = pr * d / l; c = c < 0 ? 0 : (c > pr ? pr : c) }
				r = lerp(c, pr, pr)
			}
		} else if (mode == "godot") {
			if (inf) r = pr
			else {
				f = (1 - (nv > 0 ? nv : 0)) ^ power
				x = sat(d * (1 - f) / dist + (1 - f) * pr)
				r = lerp(6 * pr ^ 4, 6 * pr, x) / 6
			}
		}
		printf "%.9g\n", r
	}' data
}

for m in none approx approx:clamp=0 approx:distance=3 approx:clamp=0:distance=3 \
	hdrp godot godot:power=2 godot:distance=2.5 godot:power=1:distance=10
do
	test_expect_success "$m: roughness.eff equals the formula at 70 tuples" '
		reflect-shade -fa -m "$m" --env=chain.rfl in.txt >out.txt &&
		column out.txt roughness.eff >got &&
		test_line_count 70 got &&
		set -- $(echo "$m" | sed "s/:/ /g") &&
		mode=$1 clamp=1 dist=6 power=4 &&
		shift &&
		for kv
		do
			case $kv in
			clamp=*) clamp=${kv#clamp=} ;;
			distance=*) dist=${kv#distance=} ;;
			power=*) power=${kv#power=} ;;
			esac || return 1
		done &&
		expected $mode $clamp $dist $power >want &&
		cmp_numbers want got 1e-6
	'

	test_expect_success "$m: spec samples the lod of the unity mapping" '
		column out.txt roughness.eff spec.R spec.G spec.B >got &&
		awk "$AWK_LOD"" { v = lod(\"unity\", 6, \$1); print v, v, v }" got >want &&
		awk "{ print \$2, \$3, \$4 }" got >spec &&
		cmp_numbers want spec 2e-5
	'
done

test_expect_success 'no mode writes NaN or a roughness outside [0, 1]' '
	for m in none approx approx:clamp=0 hdrp godot
	do
		reflect-shade -fa -m $m --env=chain.rfl in.txt >out.txt &&
		column out.txt roughness.eff spec.R >got &&
		! grep -i nan got &&
		awk "\$1 < 0 || \$1 > 1 { bad = 1 } END { exit bad }" got || return 1
	done
'

test_done
