#!/bin/sh
test_description='reflect-shade blends several probes: HDRP weights by hand, each probe its own box, smooth across'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

# uniform_chain FILE V: a prefiltered chain of 4 levels, V everywhere.
uniform_chain () {
	awk -v v="$2" 'BEGIN { n = 8
		for (k = 0; k < 4; k++) {
			printf "#?REFLECT1\nENVMAP=CUBE\nLEVEL=%d\nLEVELS=4\nPREFILTER=ggx\n", k
			printf "MAPPING=unity\nSTEPS=3\nNCOLS=%d\nNROWS=%d\nNCOMP=3\n", n, 6 * n
			printf "CHANNELS=R G B\nFORMAT=ascii\n\n"
			for (j = 0; j < 6 * n * n; j++) print v, v, v
			n = n / 2
		} }' >"$1"
}

# Probe A: x in [-2, 0.5], fading over 1 m toward +x only, importance 1;
# probe B: x in [-0.5, 2], fading over 1 m toward -x only.  A comes
# first: wA = smoothstep((0.5 - x)/1), wB = min(smoothstep((x + 0.5)/1),
# 1 - wA), and since smoothstep(t) + smoothstep(1 - t) = 1 the two add
# up to 1 across the metre between them.  With A's environment 1 and
# B's 3, spec = wA + 3 wB:
#   x     -1   -0.5  -0.25    0      0.25     0.5  1    3 (outside both)
#   wA     1    1    0.84375  0.5    0.15625  0    0    0
#   wB     0    0    0.15625  0.5    0.84375  1    1    0
#   spec   1    1    1.3125   2      2.6875   3    3    1 (the fallback: A along R)
probe_keys="PROBE_BOX=-2 0 -1 0.5 2 1
PROBE_CENTER=-0.75 1 0
PROBE_BLEND=1 0 0 0 0 0
PROBE_IMPORTANCE=1
PROBE_ENV=a.rfl
PROBE2_BOX=-0.5 0 -1 2 2 1
PROBE2_CENTER=0.75 1 0
PROBE2_BLEND=0 1 0 0 0 0
PROBE2_ENV=b.rfl"

test_expect_success 'setup: two uniform rooms and a row across the doorway' '
	uniform_chain a.rfl 1 &&
	uniform_chain b.rfl 3 &&
	{
		echo "#?REFLECT1" && echo "$probe_keys" &&
		echo "NCOLS=8" && echo "NROWS=1" && echo "NCOMP=17" &&
		echo "CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness mask R.X R.Y R.Z D.X D.Y D.Z" &&
		echo "FORMAT=ascii" && echo &&
		for x in -1 -0.5 -0.25 0 0.25 0.5 1 3
		do
			echo "$x 1 0 0 1 0 0 1 0 0 1 0 1 0 0 1 0" || return 1
		done
	} >row.txt
'

test_expect_success 'the weights and the blend as derived' '
	reflect-shade -fa -m none row.txt >out.txt &&
	column out.txt weight.probe1 weight.probe2 weight.fallback spec.R >got &&
	cat >expect <<-\EOF &&
	1 0 0 1
	1 0 0 1
	0.84375 0.15625 0 1.3125
	0.5 0.5 0 2
	0.15625 0.84375 0 2.6875
	0 1 0 3
	0 1 0 3
	0 0 1 1
	EOF
	test_cmp_numbers expect got 1e-6
'

test_expect_success '--fallback=none, --max-probes=1, --blend=off' '
	reflect-shade -fa -m none --fallback=none row.txt >none.txt &&
	column none.txt spec.R weight.fallback >got &&
	sed -n 8p got >last &&
	echo "0 0" >expect &&
	test_cmp_numbers expect last 0 &&
	# one probe a pixel: A alone where it covers, the rest to the fallback
	reflect-shade -fa -m none --max-probes=1 row.txt >one.txt &&
	column one.txt weight.probe1 weight.probe2 weight.fallback spec.R >got &&
	sed -n 4p got >mid &&
	echo "0.5 0 0.5 1" >expect &&
	test_cmp_numbers expect mid 1e-6 &&
	reflect-shade -fa -m none --blend=off row.txt >off.txt &&
	column off.txt spec.R | sort -u >got &&
	echo 1 >expect &&
	test_cmp_numbers expect got 0 &&
	! test_grep weight off.txt
'

test_expect_success '--fallback=sky:FILE: what no probe covers comes from the sky' '
	uniform_chain sky.rfl 7 &&
	reflect-shade -fa -m none --fallback=sky:sky.rfl row.txt >sky.txt &&
	column sky.txt spec.R >got &&
	printf "1\n1\n1.3125\n2\n2.6875\n3\n3\n7\n" >expect &&
	test_cmp_numbers expect got 1e-6 &&
	test_expect_code 1 reflect-shade -m none --fallback=sky:nothere.rfl row.txt \
		>/dev/null 2>err &&
	test_grep "nothere.rfl" err
'

# A sky that cannot be read is refused before any frame, also when every
# frame has one probe and no pixel would read it: never a silent pass.
test_expect_success '--fallback=sky:FILE: a missing sky is refused with one probe too' '
	reflect-gbuffer -x 4 -y 2 </dev/null | reflect-project >one.rfl &&
	reflect-info one.rfl >info &&
	! test_grep PROBE2_ info &&
	test_expect_code 1 reflect-shade -m none --fallback=sky:nothere.rfl one.rfl \
		>out 2>err &&
	test ! -s out &&
	test_grep "cannot open .nothere.rfl." err &&
	printf "not a stream" >bad.rfl &&
	test_expect_code 1 reflect-shade -m none --fallback=sky:bad.rfl one.rfl \
		>out 2>err &&
	test ! -s out &&
	test_grep "bad.rfl" err
'

# The raytraced mode traces each probe's rays through that probe's box
# and environment, a stage a probe: in these uniform rooms every ray
# reads its probe's radiance, so spec is the same blend, to the noise of
# 256 rays (spec divides by the lobe's albedo: about 1 %); the fallback's
# share goes to the first probe.
test_expect_success 'the raytraced mode blends the probes too' '
	awk "/^CHANNELS=/ { print; next } body { \$10 = 0.5 } /^$/ { body = 1 } { print }" \
		row.txt >rough.txt &&
	reflect-shade -fa -m raytraced:samples=256 rough.txt >rt.txt &&
	column rt.txt spec.R weight.probe1 weight.probe2 >got &&
	printf "1\n1\n1.3125\n2\n2.6875\n3\n3\n1\n" >expect &&
	cut -d " " -f 1 got >spec &&
	paste expect spec | awk "{ d = (\$2 - \$1) / \$1; if (d < 0) d = -d; if (d > 0.03) bad = 1 }
		END { exit bad }" &&
	reflect-shade -h -j 1 -m raytraced:samples=8 rough.txt >one &&
	reflect-shade -h -j 2 -m raytraced:samples=8 rough.txt >two &&
	cmp one two
'

# B's own box: from P = (1.9, 1, 0.3) the reflection R = +Z leaves B's
# box at z = 1, at (1.9, 1, 1); from B's capture point (0.75, 1, 0) that
# is (1.15, 0, 1), on the +X face at a = 1/1.15 = 0.87, texel 15 of 16
# (value 1 in a chain whose face f holds f + 1), where R itself would
# read +Z (5).
test_expect_success 'each probe is read with its own box' '
	level_chain faces.rfl 16 4 unity 1 &&
	sed "s/^PROBE2_ENV=b.rfl$/PROBE2_ENV=faces.rfl/" row.txt |
		awk "/^$/ && !body { body = 1; print; print \"1.9 1 0.3 0 1 0 0 1 0 0 1 0 0 1 0 0 1\"; next } !body" |
		sed "s/^NCOLS=8$/NCOLS=1/" >one-pixel.txt &&
	reflect-shade -fa -m none one-pixel.txt >p.txt &&
	column p.txt weight.probe2 spec.R >got &&
	echo "1 1" >expect &&
	test_cmp_numbers expect got 1e-6
'

# The same pixel facing +Z (N = V = +Z, so R = +Z) through reflect-project:
# the box projection reads 1 as above; a projection without parallax
# (-m infinite) turns it off in every probe, so that B reads R: +Z, 5.
test_expect_success 'after -m infinite every probe keeps R, not the first only' '
	sed "s/^1.9 1 0.3 .*/1.9 1 0.3 0 0 1 0 0 1 0 1 0 0 1 0 0 1/" one-pixel.txt >facing.txt &&
	reflect-project facing.txt >box.rfl &&
	reflect-project -m infinite facing.txt >inf.rfl &&
	reflect-info inf.rfl >info &&
	test_grep "[[:space:]]PROBE_BOX_PROJECTION=0$" info &&
	test_grep "[[:space:]]PROBE2_BOX_PROJECTION=0$" info &&
	reflect-shade -fa -m none box.rfl | column - weight.probe2 spec.R >got &&
	echo "1 1" >expect &&
	test_cmp_numbers expect got 1e-6 &&
	reflect-shade -fa -m none inf.rfl | column - weight.probe2 spec.R >got &&
	echo "1 5" >expect &&
	test_cmp_numbers expect got 1e-6
'

# Across the metre of the doorway in steps of 2 cm, spec moves by at most
# 2 x 1.5 x 0.02 (smoothstep's steepest slope is 1.5) = 0.06 a step; a
# switch to one probe jumps by 2.
test_expect_success 'smooth across the boundary, and a seam without blending' '
	{
		echo "#?REFLECT1" && echo "$probe_keys" &&
		echo "NCOLS=101" && echo "NROWS=1" && echo "NCOMP=17" &&
		echo "CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness mask R.X R.Y R.Z D.X D.Y D.Z" &&
		echo "FORMAT=ascii" && echo &&
		awk "BEGIN { for (i = 0; i <= 100; i++) print -1 + i * 0.02, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1, 0 }"
	} >line.txt &&
	reflect-shade -fa -m none line.txt | column - spec.R >s &&
	awk "NR > 1 { d = \$1 - prev; if (d < 0) d = -d; if (d > worst) worst = d } { prev = \$1 }
	     END { printf \"worst step %g\n\", worst; exit !(worst <= 0.0601) }" s &&
	reflect-shade -fa -m none --max-probes=1 --fallback=none line.txt | column - spec.R >n &&
	awk "NR > 1 { d = \$1 - prev; if (d < 0) d = -d; if (d > worst) worst = d } { prev = \$1 }
	     END { exit !(worst >= 1.9) }" n
'

test_expect_success 'the same bytes at 1 and 2 threads, blending the two-room example' '
	reflect-gbuffer -x 64 -y 36 "$srcdir/doc/examples/two-rooms.scene" | reflect-project >two.rfl &&
	reflect-capture -p 1 -n 32 "$srcdir/doc/examples/two-rooms.scene" >c1.rfl &&
	reflect-capture -p 2 -n 32 "$srcdir/doc/examples/two-rooms.scene" >c2.rfl &&
	sed "s|^PROBE_ENV=.*|PROBE_ENV=c1.rfl|; s|^PROBE2_ENV=.*|PROBE2_ENV=c2.rfl|" two.rfl >t.rfl &&
	reflect-shade -h -j 1 -m hdrp --final t.rfl >one 2>/dev/null &&
	reflect-shade -h -j 2 -m hdrp --final t.rfl >two 2>/dev/null &&
	cmp one two &&
	reflect-shade -m hdrp t.rfl 2>/dev/null | reflect-info -s >stats &&
	awk "\$1 == \"weight.probe1\" { a = \$4 } \$1 == \"weight.probe2\" { b = \$4 }
	     END { exit !(a > 0.2 && b > 0.05) }" stats
'

test_expect_success 'bad blending options and keys are refused' '
	test_expect_code 1 reflect-shade --blend=maybe row.txt >/dev/null 2>err &&
	test_grep "blend: .maybe. is not on or off" err &&
	test_expect_code 1 reflect-shade --max-probes=0 row.txt >/dev/null 2>err &&
	test_grep "max-probes" err &&
	test_expect_code 1 reflect-shade --fallback=sky row.txt >/dev/null 2>err &&
	test_grep "fallback: .sky. is not infinite, none or sky:FILE" err &&
	sed "s/^PROBE2_BLEND=.*/PROBE2_BLEND=1 2/" row.txt >bad.txt &&
	test_expect_code 1 reflect-shade -m none bad.txt >/dev/null 2>err &&
	test_grep "PROBE2_BLEND" err
'

test_done
