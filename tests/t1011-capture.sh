#!/bin/sh
test_description='reflect-capture: a probe baked from the scene, by hand, against the embedded room and against Cycles'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"

imgdump="$builddir/tests/imgdump"
truth="${REFLECT_TRUTH:-$srcdir/../shared/truth}"
examples="$srcdir/doc/examples"

test_expect_success 'a uniform room: every texel is its radiance' '
	cat >uniform.scene <<-\EOF &&
	probe box -1 -2 -3 4 5 6 center 0 0 0
	room emission 2 0.5 0.25
	EOF
	reflect-capture -n 8 -o u.exr uniform.scene &&
	"$imgdump" u.exr >dump &&
	head -n 1 dump >size &&
	echo "8 48 3" >expect &&
	cmp expect size &&
	sed 1,2d dump | sort -u >got &&
	echo "2 0.5 0.25" >expect &&
	test_cmp_numbers expect got 0
'

# A cube room [-1, 1]^3 seen from its centre: face +X looks at the wall
# x = 1, where the texel at (a, b) in [-1, 1]^2 meets (z, y) = (a, -b)
# (the OpenEXR orientation).  At 2 texels a face, texel (0, 0) of +X is
# z in [-1, 0], y in [0, 1]: a window over exactly that is the texel's
# radiance; one over z in [-1, -0.5] covers half of it, which the 16 x 16
# samples of an edge texel see as 8 columns of 16: half the radiance.
# The texel beside it, (1, 0), sees none of it.
test_expect_success 'a window over a whole texel, over half of one' '
	cat >win.scene <<-\EOF &&
	probe box -1 -1 -1 1 1 1
	window +x min -1 0 max 0 1 radiance 8 4 2
	EOF
	reflect-capture -n 2 -o w.exr win.scene &&
	"$imgdump" w.exr | sed 1,2d >got &&
	printf "8 4 2\n0 0 0\n" >expect &&
	head -n 2 got >first &&
	test_cmp_numbers expect first 0 &&
	sed 1,2d got | sort -u >rest &&
	echo "0 0 0" >expect &&
	test_cmp_numbers expect rest 0 &&
	sed "s/max 0 1/max -0.5 1/" win.scene >half.scene &&
	reflect-capture -n 2 -o h.exr half.scene &&
	"$imgdump" h.exr | sed -n 3p >got &&
	echo "4 2 1" >expect &&
	test_cmp_numbers expect got 0
'

# The embedded environment is the default scene's room seen from its
# probe, each texel the mean of 4 x 4 samples at the centres of a grid;
# the default scene writes that room as emission.  With the same 4 x 4
# samples on the edges, the capture is the embedded room to float
# rounding, texel for texel: pattern, windows, mullions and samples.
test_expect_success 'the default scene without its objects is the embedded room' '
	reflect-capture -n 64 --edge-samples=4 --hide-reflective >cap.rfl &&
	reflect-prefilter --size=64 --levels=2 -o room.rfl 2>/dev/null &&
	reflect-export -c R,G,B -o cap.exr cap.rfl &&
	reflect-export -c R,G,B -o "room%d.exr" room.rfl &&
	"$imgdump" cap.exr | sed 1,2d >ea &&
	"$imgdump" room0.exr | sed 1,2d >eb &&
	test_line_count 24576 ea &&
	paste -d " " ea eb | awk "{
		r = 0
		for (c = 1; c <= 3; c++) { d = \$c - \$(c + 3); r += (d < 0 ? -d : d) / \$(c + 3) }
		r /= 3; s += r; if (r > worst) worst = r
	} END {
		printf \"mean %g worst %g\n\", s / NR, worst
		exit !(s / NR < 1e-6 && worst < 1e-5)
	}"
'

# Objects: a white metal mirror sphere in a room of radiance 1.  Bounce
# 0 sees it black; one bounce lights it with the room, prefiltered, so a
# mirror (F0 = 1, A + B = 1 at roughness 0 within the DFG table's 1 %)
# shows 1; hidden, it is not there.
test_expect_success 'objects black at bounce 0, lit by the room at bounce 1, hidden' '
	cat >ball.scene <<-\EOF &&
	probe box -2 -2 -2 2 2 2 center 0 0 0
	room emission 1 1 1
	sphere center 1.5 0 0 radius 0.3 roughness 0
	EOF
	# the +X face centre looks straight at the ball
	for b in 0 1
	do
		reflect-capture -n 16 --bounces=$b -o b$b.exr ball.scene &&
		"$imgdump" b$b.exr | sed -n "$((3 + 7 * 16 + 7))p" >c$b || return 1
	done &&
	echo "0 0 0" >expect &&
	test_cmp_numbers expect c0 0 &&
	awk "{ for (k = 1; k <= 3; k++) if (\$k < 0.98 || \$k > 1.02) exit 1 }" c1 &&
	reflect-capture -n 16 --hide-reflective -o hid.exr ball.scene &&
	"$imgdump" hid.exr | sed 1,2d | sort -u >got &&
	echo "1 1 1" >expect &&
	test_cmp_numbers expect got 0
'

test_expect_success 'an emissive object is seen at bounce 0' '
	cat >lamp.scene <<-\EOF &&
	probe box -2 -2 -2 2 2 2 center 0 0 0
	sphere center 0 0 -1.5 radius 0.3 emission 5 6 7 reflective off
	EOF
	reflect-capture -n 16 --bounces=0 -o l.exr lamp.scene &&
	# face -Z (the sixth) centre: texel (7, 7)
	"$imgdump" l.exr | sed -n "$((3 + 5 * 256 + 7 * 16 + 7))p" >got &&
	echo "5 6 7" >expect &&
	test_cmp_numbers expect got 1e-6
'

test_expect_success 'the same bytes at 1 and 2 threads, streams and files alike' '
	reflect-capture -n 32 -j 1 >one.rfl &&
	reflect-capture -n 32 -j 2 >two.rfl &&
	sed "1,/^$/d" one.rfl >one.body &&
	sed "1,/^$/d" two.rfl >two.body &&
	cmp one.body two.body &&
	reflect-info one.rfl >info &&
	test_grep "^	ENVMAP=CUBE$" info &&
	test_grep "^	NCOLS=32$" info &&
	test_grep "^	NROWS=192$" info &&
	test_grep "^	CAPTURE_PROBE=1$" info &&
	# a capture is an environment like any other
	reflect-gbuffer -x 16 -y 9 | reflect-project | reflect-shade --env=one.rfl >/dev/null
'

test_expect_success 'env capture: reflect-shade bakes the probe itself' '
	cat >baked.scene <<-\EOF &&
	probe box -2 -1 -2 2 2 2 center 0 0.5 0 env capture
	pattern cell 0.5
	wall -z pattern 0.2 0.4 0.9
	room emission 0.3 0.3 0.3
	sphere center 0 0 -1 radius 0.4 roughness 0.2
	EOF
	reflect-gbuffer -x 32 -y 18 baked.scene | reflect-project >g.rfl &&
	reflect-info g.rfl >info &&
	test_grep "^	PROBE_ENV=capture:baked.scene#1$" info &&
	reflect-shade -h -m hdrp --final g.rfl >onthefly 2>err &&
	test_grep "prefiltering the environment .capture:baked.scene#1." err &&
	reflect-capture baked.scene >baked.rfl &&
	reflect-shade -h -m hdrp --final --env=baked.rfl g.rfl >given 2>/dev/null &&
	cmp onthefly given &&
	test_expect_code 1 reflect-shade --env="capture:nothere.scene#1" g.rfl >/dev/null 2>err &&
	test_grep "cannot open .nothere.scene." err &&
	test_expect_code 1 reflect-shade --env="capture:baked.scene#2" g.rfl >/dev/null 2>err &&
	test_grep "capture:baked.scene#2.: the scene has 1 probe, not 2" err &&
	test_expect_code 1 reflect-shade --env="capture:baked.scene#x" g.rfl >/dev/null 2>err &&
	test_grep "is not a probe number" err
'

# A stream names the scene of its capture; a message about that file
# tells where the parser stopped, never what it read there, or a stream
# could have reflect-shade print any file the user can read.
test_expect_success 'a scene named by a header: its words never shown' '
	printf "root:x:0:0:SECRET-WORD:/root:/bin/sh\nline two\n" >secret.txt &&
	sed "s|^PROBE_ENV=capture:baked.scene#1$|PROBE_ENV=capture:secret.txt#1|" g.rfl >evil.rfl &&
	reflect-info evil.rfl >info &&
	test_grep "PROBE_ENV=capture:secret.txt#1$" info &&
	test_expect_code 1 reflect-shade evil.rfl >out 2>err &&
	test ! -s out &&
	! test_grep SECRET err &&
	! test_grep root err &&
	test_grep "secret.txt:1:1" err &&
	test_grep "named by the stream.s header" err &&
	# named by the user, the parser says all it has to say
	test_expect_code 1 reflect-shade --env=capture:secret.txt g.rfl >out 2>err &&
	test_grep "unknown keyword .root:x:0:0:SECRET-WORD" err
'

test_expect_success 'bad options and probes are refused with the fix' '
	test_expect_code 1 reflect-capture -p 2 >/dev/null 2>err &&
	test_grep "p 2: the default scene has 1 probe" err &&
	test_expect_code 1 reflect-capture -n 0 >/dev/null 2>err &&
	test_grep "option -n: 0 is out of range" err &&
	test_expect_code 1 reflect-capture --bounces=17 >/dev/null 2>err &&
	test_grep "bounces" err &&
	test_expect_code 1 reflect-capture -o x.png >/dev/null 2>err &&
	test_grep "cannot write .x.png.: a capture is a stream" err
'

# Cycles captures of the references (../shared/truth): texels inside the
# pattern's cells must agree to 1e-3 (the median texel of every face);
# the references spread each edge over about two texels where a box
# filter over the texel does not, so the mean is held to what that
# leaves, 5 %, and printed.
#
# Why not 0.5 %: the references are not box-filtered over each texel as
# their README says; they look resampled from a lat-long, every edge of
# the pattern blurred over about two texels either side.  5.8 % of the
# texels of the +-Y faces straddle an edge, 14.7 to 15.2 % of the others,
# and on those the references differ from a box filter by 2.8 % (+-Y)
# and 11.6 to 12.1 % on average; the blur leaves the texels beside an
# edge off by 7 to 11 %, the next ones by 0.2 to 0.3 %.  That alone
# makes the face means 1.0 % (+-Y) and 3.8 to 4.0 %, which no capture
# that box-filters its texels can bring under 0.5 %.  What can be held
# tight is below: the texels far from every edge, and the light.
#
# Flat texels: those whose whole 7 x 7 neighbourhood lies inside the face
# and is, in our capture, its centre on every channel to a relative 1e-6
# (a 7 x 7 minimum and maximum, along the rows then down the columns).
# No edge texel is within 3 of them, beyond the references' blur, so
# they must be the references to float rounding: measured at most
# 3.34e-6 (relative, the worst channel) on every face of both scenes,
# held to 1e-5, which a colour off by 1 %, a flipped face or a face put
# in another's place is far beyond (a shift of a texel or less may leave
# them flat in the references too: the blocks below catch it).  They are
# 41.6 to 42.2 % of the +-X and +-Z faces and 66.0 % of the +-Y faces,
# held to over 30 % so that the check cannot pass on next to nothing.
#
# Light conserved: the blur moves light by two texels at most, so the
# sums over 8 x 8 blocks of texels agree, per channel, to a mean over
# the face of 0.05 % (+-Y) to 0.84 % (measured), held to 2 %.  A block
# along whose side a bright line or a window edge runs loses or gains
# what the blur carries across it (up to 84 %, beside the -Z window):
# those are 0 % (+-Y) to 4.04 % of the blocks beyond 2 %, held to under
# 10 %; a capture shifted by half a texel (the probe 2 cm off) puts 25
# to 32 % of the blocks of a face beyond 2 %, one shifted by a texel 39
# to 53 %.  The face totals agree per channel to 1.3e-4 to 6.5e-4
# (measured), held to 1e-3: a colour off by 1 % is 1e-2.  Both scenes
# see the same room from the same point, hence the same figures.
for scene in room-floor room-spheres
do
	if ! test -f "$truth/$scene.probe.cube.exr"
	then
		test_skip "$scene: captured beside Cycles" "no references in $truth"
		test_skip "$scene: the capture against Cycles" "no references in $truth"
		test_skip "$scene: flat texels against Cycles" "no references in $truth"
		test_skip "$scene: light conserved against Cycles" "no references in $truth"
		continue
	fi
	# one capture and its dump for the three checks, by scene
	test_expect_success "$scene: captured beside Cycles" '
		reflect-capture --hide-reflective -o cap.exr "$examples/$scene.scene" &&
		"$imgdump" cap.exr | sed 1,2d >$scene.a &&
		"$imgdump" "$truth/$scene.probe.cube.exr" | sed 1,2d >$scene.b &&
		test_line_count 393216 $scene.a &&
		test_line_count 393216 $scene.b
	'
	test_expect_success "$scene: the capture against Cycles, face by face" '
		paste -d " " $scene.a $scene.b | awk "{
			r = 0
			for (c = 1; c <= 3; c++) { d = \$c - \$(c + 3); r += (d < 0 ? -d : d) / \$(c + 3) }
			print int((NR - 1) / 65536), r / 3
		}" | sort -k1,1n -k2,2g >rel &&
		awk "{ v[\$1, n[\$1]++] = \$2; s[\$1] += \$2 }
		END {
			for (f = 0; f < 6; f++) {
				m = v[f, int(n[f] / 2)]; mean = s[f] / n[f]
				printf \"face %d: median %.3g mean %.4f\n\", f, m, mean
				if (!(m < 1e-3 && mean < 0.05)) bad = 1
			}
			exit bad
		}" rel
	'
	test_expect_success "$scene: flat texels against Cycles, to 1e-5" '
		paste -d " " $scene.a $scene.b | awk "
		function face(f,   c, x, y, p, k, lo, hi, n, r, d, worst) {
			for (p = 0; p < 65536; p++) flat[p] = 0
			for (y = 3; y < 253; y++) for (x = 3; x < 253; x++) flat[y * 256 + x] = 1
			for (c = 1; c <= 3; c++) {
				for (p = 0; p < 65536; p++) v[p] = c == 1 ? a1[p] : c == 2 ? a2[p] : a3[p]
				for (y = 0; y < 256; y++) for (x = 3; x < 253; x++) {
					p = y * 256 + x; lo = hi = v[p - 3]
					for (k = p - 2; k <= p + 3; k++) { if (v[k] < lo) lo = v[k]; if (v[k] > hi) hi = v[k] }
					rlo[p] = lo; rhi[p] = hi
				}
				for (p = 768; p < 64768; p++) if (flat[p]) {
					lo = rlo[p - 768]; hi = rhi[p - 768]
					for (k = p - 512; k <= p + 768; k += 256) { if (rlo[k] < lo) lo = rlo[k]; if (rhi[k] > hi) hi = rhi[k] }
					if (hi > v[p] * (1 + 1e-6) || lo < v[p] * (1 - 1e-6)) flat[p] = 0
				}
			}
			n = 0; worst = 0
			for (p = 0; p < 65536; p++) if (flat[p]) {
				n++
				d = a1[p] / b1[p] - 1; r = d < 0 ? -d : d
				d = a2[p] / b2[p] - 1; d = d < 0 ? -d : d; if (d > r) r = d
				d = a3[p] / b3[p] - 1; d = d < 0 ? -d : d; if (d > r) r = d
				if (r > worst) worst = r
			}
			printf \"face %d: %.1f %% flat, worst %.3g\n\", f, 100 * n / 65536, worst
			if (!(n > 0.3 * 65536 && worst < 1e-5)) bad = 1
		}
		{
			p = (NR - 1) % 65536
			a1[p] = \$1; a2[p] = \$2; a3[p] = \$3; b1[p] = \$4; b2[p] = \$5; b3[p] = \$6
			if (p == 65535) face(int((NR - 1) / 65536))
		}
		END { exit bad }"
	'
	test_expect_success "$scene: light conserved against Cycles, 8 x 8 blocks and faces" '
		paste -d " " $scene.a $scene.b | awk "{
			k = NR - 1; f = int(k / 65536); p = k % 65536
			q = f * 1024 + int(p / 2048) * 32 + int(p % 256 / 8)
			for (c = 1; c <= 3; c++) { sa[q, c] += \$c; sb[q, c] += \$(c + 3); ta[f, c] += \$c; tb[f, c] += \$(c + 3) }
		}
		END {
			for (f = 0; f < 6; f++) {
				s = 0; out = 0; tot = 0
				for (q = f * 1024; q < f * 1024 + 1024; q++) for (c = 1; c <= 3; c++) {
					d = sa[q, c] / sb[q, c] - 1; d = d < 0 ? -d : d
					s += d; if (d > 0.02) out++
				}
				for (c = 1; c <= 3; c++) { d = ta[f, c] / tb[f, c] - 1; d = d < 0 ? -d : d; if (d > tot) tot = d }
				printf \"face %d: blocks %.4f on average, %.2f %% beyond 2 %%; total %.2e\n\", f, s / 3072, 100 * out / 3072, tot
				if (!(s / 3072 < 0.02 && out / 3072 < 0.1 && tot < 1e-3)) bad = 1
			}
			exit bad
		}"
	'
done

test_done
