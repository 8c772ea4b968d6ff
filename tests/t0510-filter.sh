#!/bin/sh
test_description='reflect-filter: quad and atrous, bands of rows, refusals'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"
SQ="'"

# A 3x3 frame, v = 10 y + x: its aligned 2x2 quads are (0,0)-(1,1),
# mean 5.5; (2,0)-(2,1), mean (2 + 12) / 2 = 7; (0,2)-(1,2), mean 20.5;
# (2,2) alone, 22.
test_expect_success 'quad: the means of the aligned 2x2 quads, odd edges too' '
	stream quad.txt 3 3 "spec.R X" <<-\EOF &&
	0 1
	1 1
	2 1
	10 1
	11 1
	12 1
	20 1
	21 1
	22 1
	EOF
	reflect-filter -fa -m quad quad.txt >out.txt &&
	test_grep "^FILTER=quad$" out.txt &&
	column out.txt spec.R X >got &&
	cat >expect <<-\EOF &&
	5.5 1
	5.5 1
	7 1
	5.5 1
	5.5 1
	7 1
	20.5 1
	20.5 1
	22 1
	EOF
	diff -u expect got
'

# with SPEC: the default scene's G-buffer (mask, objid, N, P, roughness,
# hit.dist, depth), with spec.R G B appended as an awk expression of o,
# the objid.
with_spec () {
	reflect-gbuffer -fa -x 64 -y 48 | reflect-project -fa | awk -v expr="$1" '
	/^CHANNELS=/ {
		n = split(substr($0, 10), ch, " ")
		for (i = 1; i <= n; i++) if (ch[i] == "objid") oc = i
		print $0 " spec.R spec.G spec.B"; next
	}
	/^NCOMP=/ { print "NCOMP=" substr($0, 7) + 3; next }
	!body && /^$/ { body = 1; print; next }
	body {
		o = $oc
		v = expr == "constant" ? 0.75 : o + 0.5
		print $0, v, v * 2, v * 3; next
	}
	{ print }'
}

test_expect_success 'atrous: a constant image comes out unchanged, byte for byte' '
	with_spec constant >flat.txt &&
	reflect-filter -fa flat.txt >out.txt &&
	column out.txt spec.R spec.G spec.B | sort -u >got &&
	echo "0.75 1.5 2.25" >expect &&
	diff -u expect got
'

test_expect_success 'atrous: no value crosses from one object to another' '
	with_spec objid >objects.txt &&
	reflect-filter -fa -m atrous:lobe=0:plane=10:normal=0 objects.txt >out.txt &&
	column out.txt objid spec.R spec.G spec.B >got &&
	awk "{ v = \$1 + 0.5; if (\$2 != v || \$3 != v * 2 || \$4 != v * 3) { print; bad = 1 } }
		END { exit bad }" got &&
	test $(cut -d" " -f1 got | sort -u | wc -l) -gt 3
'

# 4 rays with the footprint of 64 (frames=16): noisy but sharp, the input
# a filter wants (reflect-filter(1): filtering a 4-ray footprint blurs
# twice).
test_expect_success 'setup: a small scene, 4 rays and 1024' '
	reflect-gbuffer -x 240 -y 160 | reflect-project >scene.rfl &&
	reflect-prefilter --size=32 -o room.rfl 2>/dev/null &&
	reflect-shade -fa -j2 -m raytraced:samples=1024 --final --env=room.rfl scene.rfl >ref.txt &&
	reflect-shade -fa -m raytraced:samples=4:frames=16 --final --env=room.rfl scene.rfl \
		>noisy.txt &&
	reflect-shade -m raytraced:samples=4:frames=16 --final --env=room.rfl scene.rfl \
		>noisy.rfl
'

for m in atrous quad atrous:passes=2:color=1
do
	test_expect_success "$m: the bytes do not depend on the thread count" '
		reflect-filter -h -j1 -m $m noisy.rfl >j1 &&
		reflect-filter -h -j2 -m $m noisy.rfl >j2 &&
		reflect-filter -h -j5 -m $m noisy.rfl >j5 &&
		test -s j1 &&
		cmp j1 j2 &&
		cmp j1 j5
	'
done

# The four-lane code (forced) and the eight-lane one (where the machine
# has AVX2): the same operations lane by lane, so the same bytes.
test_expect_success 'atrous: four lanes and eight give the same bytes' '
	reflect-filter -h -m atrous:color=1 noisy.rfl >wide &&
	REFLECT_SIMD=off reflect-filter -h -m atrous:color=1 noisy.rfl >narrow &&
	test -s wide &&
	cmp wide narrow
'

# err FILE: the squared error of R G B against ref.txt on the reflective
# pixels, all of them and those on an edge (a neighbour of another
# object or off the mask), as "all edges".
err () {
	paste -d" " "$1" ref.col | awk -v w=240 '{
		m[NR] = $1; o[NR] = $2
		d[NR] = ($3 - $6) ^ 2 + ($4 - $7) ^ 2 + ($5 - $8) ^ 2
	} END {
		for (i = 1; i <= NR; i++) {
			if (m[i] < 0.5) continue
			all += d[i]; na++
			x = (i - 1) % w; edge = 0
			for (dy = -1; dy <= 1; dy++) for (dx = -1; dx <= 1; dx++) {
				j = i + dy * w + dx
				if (j < 1 || j > NR || x + dx < 0 || x + dx >= w) continue
				if (m[j] < 0.5 || o[j] != o[i]) edge = 1
			}
			if (edge) { ed += d[i]; ne++ }
		}
		printf "%.6g %.6g\n", sqrt(all / na), sqrt(ed / ne)
	}'
}

test_expect_success 'atrous lowers the error, and on the edges too' '
	column ref.txt R G B >ref.col &&
	reflect-filter -fa noisy.txt >filtered.txt &&
	column noisy.txt mask objid R G B >noisy.col &&
	column filtered.txt mask objid R G B >filtered.col &&
	before=$(err noisy.col) &&
	after=$(err filtered.col) &&
	echo "RMSE all, edges: 4 rays $before, filtered $after" &&
	set -- $before $after &&
	awk -v a=$1 -v b=$2 -v c=$3 -v d=$4 "BEGIN { exit !(c < 0.6 * a && d <= b) }"
'

test_expect_success 'a frame far taller than the bands: filtered in bounded memory' '
	if grep -q fsanitize "$builddir/Makefile"
	then
		echo "# skipped: address space limits do not mix with the sanitizers"
	else
		reflect-gbuffer -x 200 -y 12000 | reflect-project | reflect-shade -m none \
			>tall.rfl 2>/dev/null &&
		test $(wc -c <tall.rfl) -gt 300000000 &&
		(ulimit -v 150000 && cat tall.rfl | reflect-filter -j1 >/dev/null) &&
		! (ulimit -v 150000 && cat tall.rfl | reflect-accumulate -j1 >/dev/null 2>&1)
	fi
'

test_expect_success 'missing guides, NaN, unknown modes and parameters: refused' '
	stream plain.txt 2 1 "spec.R" <<-\EOF &&
	1
	2
	EOF
	test_expect_code 1 reflect-filter plain.txt 2>err &&
	test_one_line_message reflect-filter err &&
	test_grep "no channel .N.X., which mode .atrous. is guided by" err &&
	stream nan.txt 2 1 "spec.R" <<-\EOF &&
	1
	nan
	EOF
	test_expect_code 1 reflect-filter -m quad nan.txt 2>err &&
	test_one_line_message reflect-filter err &&
	test_grep "frame 1, row 1, pixel 2: channel .spec.R. is nan" err &&
	test_expect_code 1 reflect-filter -m atrous:passes=12 plain.txt 2>err &&
	test_grep "passes" err &&
	test_expect_code 1 reflect-filter -m blur plain.txt 2>err &&
	test_grep "blur" err &&
	test_expect_code 1 reflect-filter -m none plain.txt 2>err &&
	test_grep "reflect-shade" err
'

# floor FILE NY V: a 5x5 floor of one object, roughness 0.5, spec.R 1 + x,
# whose centre pixel has the normal (0, NY, 0) and spec.R V (awk program
# text).
floor () {
	awk -v ny="$2" -v v="$3" "BEGIN {
		for (y = 0; y < 5; y++) for (x = 0; x < 5; x++)
			print 0, (x == 2 && y == 2 ? ny : 1), 0, x * 0.1, 0, y * 0.1, 0.5, 1,
				(x == 2 && y == 2 ? v : 1 + x)
	}" | stream "$1" 5 5 "N.X N.Y N.Z P.X P.Y P.Z roughness objid spec.R"
}

# The normals' weight is a power of their dot product: a normal 1e20
# long made it inf, then inf / inf, and atrous wrote NaN over the rows
# around it with exit 0.  A normal is a direction, whatever its length.
test_expect_success 'atrous: a huge but finite normal weighs as the unit one' '
	floor unit.txt 1 3 &&
	reflect-filter -fa unit.txt | column - spec.R >want &&
	for ny in 1e20 3.4e38 4e-20
	do
		floor long.txt $ny 3 &&
		reflect-filter -fa long.txt | column - spec.R >got &&
		cmp_numbers want got 1e-6 || return 1
	done &&
	# no direction at all: the pixel keeps its value, and weighs nothing
	floor zero.txt 0 3 &&
	reflect-filter -fa zero.txt | column - spec.R >got &&
	test "$(sed -n 13p got)" = 3 &&
	! grep -i nan got
'

# A filter mode adds and subtracts values: 3e38 beside -3e38 made inf -
# inf, NaN out of atrous and inf out of quad, with exit 0.
test_expect_success 'values past a quarter of the float range are refused' '
	floor big.txt 1 8.5e37 &&
	for m in atrous atrous:color=1 quad
	do
		reflect-filter -fa -m $m big.txt >out.txt &&
		! grep -i -E "nan|inf" out.txt || return 1
	done &&
	floor huge.txt 1 -3e38 &&
	for m in atrous quad
	do
		test_expect_code 1 reflect-filter -m $m huge.txt >/dev/null 2>err &&
		test_one_line_message reflect-filter err &&
		test_grep "frame 1, row 3, pixel 3: channel .spec.R. is -3e+38, past a quarter of the float range (8.50706e+37), where a filter${SQ}s sums overflow$" err ||
		return 1
	done
'

test_done
