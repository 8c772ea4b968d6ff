#!/bin/sh
test_description='reflect-filter -m atrous: the variance-guided luminance stop'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

# floor FILE SE: a 16x12 floor of one object (N up, P on the plane y = 0,
# roughness 0.5), spec.R 1 +- 0.5 by a fixed draw of signs; with SE, the
# channels spec.R.se spec.G.se spec.B.se all SE.  On it every G-buffer
# weight is 1, so a tap weighs the B3 spline's h(dx) h(dy) times the
# luminance stop alone.
floor () {
	awk -v se="$2" 'BEGIN {
		srand(7)
		for (y = 0; y < 12; y++) for (x = 0; x < 16; x++) {
			line = "0 1 0 " x * 0.1 " 0 " y * 0.1 " 0.5 1 " (rand() < 0.5 ? 0.5 : 1.5)
			print se == "" ? line : line " " se " " se " " se
		}
	}' | stream "$1" 16 12 "N.X N.Y N.Z P.X P.Y P.Z roughness objid spec.R${2:+ spec.R.se spec.G.se spec.B.se}"
}

# brute IN HOW L: one pass of atrous over a floor's spec.R, from its
# formula (reflect-mode-atrous(7)): w = h(dx) h(dy) exp(-|l_p - l_q| / (L
# sd + 1e-10)), sd 0.5 from the standard errors (how = se; their 3x3
# blur of a constant is that constant), the spread of the 25 taps'
# spec.R under h h (how = spatial), or no stop (how = off).
brute () {
	column "$1" spec.R | awk -v how="$2" -v L="$3" '
	{ v[NR - 1] = $1 }
	END {
		h[-2] = 1 / 16; h[-1] = 1 / 4; h[0] = 3 / 8; h[1] = 1 / 4; h[2] = 1 / 16
		for (y = 0; y < 12; y++) for (x = 0; x < 16; x++) {
			p = v[y * 16 + x]; gs = m = s2 = 0
			for (dy = -2; dy <= 2; dy++) for (dx = -2; dx <= 2; dx++) {
				if (x + dx < 0 || x + dx >= 16 || y + dy < 0 || y + dy >= 12) continue
				g = h[dx] * h[dy]; gs += g; m += g * v[(y + dy) * 16 + x + dx]
			}
			m /= gs
			for (dy = -2; dy <= 2; dy++) for (dx = -2; dx <= 2; dx++) {
				if (x + dx < 0 || x + dx >= 16 || y + dy < 0 || y + dy >= 12) continue
				s2 += h[dx] * h[dy] * (v[(y + dy) * 16 + x + dx] - m) ^ 2
			}
			sd = how == "se" ? 0.5 : sqrt(s2 / gs)
			ws = vs = 0
			for (dy = -2; dy <= 2; dy++) for (dx = -2; dx <= 2; dx++) {
				if (x + dx < 0 || x + dx >= 16 || y + dy < 0 || y + dy >= 12) continue
				q = v[(y + dy) * 16 + x + dx]; d = q - p; d = d < 0 ? -d : d
				w = h[dx] * h[dy] * (how == "off" ? 1 : exp(-d / (L * sd + 1e-10)))
				ws += w; vs += w * (q - p)
			}
			printf "%.6f\n", p + vs / ws
		}
	}'
}

# sd FILE: the standard deviation of a column of numbers, pixels 2..13 x
# 2..9 of the floor (those with all 25 taps).
sd () {
	awk '{ x = (NR - 1) % 16; y = int((NR - 1) / 16)
		if (x < 2 || x > 13 || y < 2 || y > 9) next
		n++; s += $1; s2 += $1 * $1 }
		END { printf "%.6f\n", sqrt(s2 / n - (s / n) ^ 2) }' "$1"
}

for case in "se 2" "se 0.5" "spatial 2" "spatial 8" "off 2"
do
	how=${case% *} L=${case#* }
	test_expect_success "atrous:passes=1, $how variance, luminance=$L: the formula's values" '
		se= mode=atrous:passes=1:luminance=$L &&
		if test $how = se; then se=0.5; fi &&
		if test $how = off; then mode=$mode:variance=off; fi &&
		floor in.txt $se &&
		reflect-filter -fa -m $mode in.txt | column - spec.R >got &&
		brute in.txt $how $L >want &&
		test_cmp_numbers want got 1e-3 &&
		column in.txt spec.R >before &&
		ratio=$(awk -v a=$(sd got) -v b=$(sd before) "BEGIN { print a / b }") &&
		want_ratio=$(awk -v a=$(sd want) -v b=$(sd before) "BEGIN { print a / b }") &&
		echo "noise sd through the pass: x $ratio (formula x $want_ratio)" &&
		awk -v r=$ratio -v w=$want_ratio "BEGIN { exit !(r < 1 && r - w < 2e-3 && w - r < 2e-3) }"
	'
done

# The noise's steps are 2 sd (1 against sd 0.5): luminance=2 weighs a
# step exp(-1), luminance=0.5 exp(-4), off 1: the tighter the stop, the
# less the pass smooths, and every one smooths some.
test_expect_success 'a tighter stop smooths less: off < luminance=2 < luminance=0.5 < 1' '
	floor in.txt 0.5 &&
	column in.txt spec.R >before &&
	for m in variance=off luminance=2 luminance=0.5
	do
		reflect-filter -fa -m atrous:passes=1:$m in.txt | column - spec.R >out &&
		sd out >"sd.${m#*=}" || return 1
	done &&
	awk -v a=$(cat sd.off) -v b=$(cat sd.2) -v c=$(cat sd.0.5) \
		-v d=$(sd before) "BEGIN { exit !(a < b && b < c && c < d) }"
'

# +inf: not known yet (one frame accumulated): the spread over the taps
# stands in, as without the channels, byte for byte.
test_expect_success 'standard errors of +inf weigh as no standard errors at all' '
	floor none.txt &&
	floor inf.txt inf &&
	reflect-filter -fa -m atrous:passes=3 none.txt | column - spec.R >a.txt &&
	reflect-filter -fa -m atrous:passes=3 inf.txt | column - spec.R >b.txt &&
	test -s a.txt &&
	cmp a.txt b.txt
'

test_expect_success 'a constant image with standard errors comes out unchanged' '
	awk "BEGIN { for (i = 0; i < 192; i++) print 0, 1, 0, (i % 16) * 0.1, 0, int(i / 16) * 0.1,
		0.5, 1, 0.75, 0.1, 0.1, 0.1 }" |
	stream flat.txt 16 12 "N.X N.Y N.Z P.X P.Y P.Z roughness objid spec.R spec.R.se spec.G.se spec.B.se" &&
	reflect-filter -fa flat.txt | column - spec.R | sort -u >got &&
	echo 0.75 >expect &&
	diff -u expect got
'

# objects: the default scene's G-buffer, object k's spec.R in
# [10 k, 10 k + 1] (noise), its standard errors 0.3: whatever the weights,
# a value out of its object's range came from another object.
test_expect_success 'setup: objects with noise in ranges apart, and their standard errors' '
	reflect-gbuffer -fa -x 64 -y 48 | reflect-project -fa | awk "
	/^CHANNELS=/ {
		n = split(substr(\$0, 10), ch, \" \")
		for (i = 1; i <= n; i++) if (ch[i] == \"objid\") oc = i
		print \$0 \" spec.R spec.R.se spec.G.se spec.B.se\"; next
	}
	/^NCOMP=/ { print \"NCOMP=\" substr(\$0, 7) + 4; next }
	!body && /^\$/ { body = 1; srand(3); print; next }
	body { print \$0, 10 * \$oc + rand(), 0.3, 0.3, 0.3; next }
	{ print }" >objects.txt
'

for m in atrous atrous:luminance=1000:lobe=0:plane=10:normal=0 atrous:variance=off:lobe=0:plane=10:normal=0
do
	test_expect_success "$m: no value crosses from one object to another" '
		reflect-filter -fa -m $m objects.txt | column - objid spec.R >got &&
		column objects.txt spec.R >before &&
		awk "{ if (\$2 < 10 * \$1 || \$2 > 10 * \$1 + 1) { print; bad = 1 } }
			END { exit bad }" got &&
		test $(cut -d" " -f1 got | sort -u | wc -l) -gt 3 &&
		! cut -d" " -f2 got | cmp -s - before
	'
done

test_expect_success 'the bytes do not depend on the thread count or the lanes' '
	reflect-filter -h -j1 objects.txt >j1 &&
	reflect-filter -h -j2 objects.txt >j2 &&
	REFLECT_SIMD=off reflect-filter -h -j3 objects.txt >j3 &&
	test -s j1 &&
	cmp j1 j2 &&
	cmp j1 j3
'

test_expect_success 'a standard error below 0, or NaN where the stream has it: refused' '
	floor se.txt 0.5 &&
	sed "\$s/0.5 0.5 0.5\$/0.5 -1 0.5/" se.txt >neg.txt &&
	test_expect_code 1 reflect-filter neg.txt >/dev/null 2>err &&
	test_one_line_message reflect-filter err &&
	test_grep "row 12, pixel 16: channel .spec.G.se. is -1, not a standard error (0 or more, inf when not known)" err &&
	sed "\$s/0.5 0.5 0.5\$/nan 0.5 0.5/" se.txt >nan.txt &&
	test_expect_code 1 reflect-filter nan.txt >/dev/null 2>err &&
	test_one_line_message reflect-filter err &&
	test_grep "row 12, pixel 16: channel .spec.R.se. is nan, not a standard error" err &&
	reflect-filter -m atrous:variance=off nan.txt >/dev/null
'

# After the filter a value's standard error is the error of the value as
# it was, not as it is: a second filter would take it for the noise still
# there.  So the filter drops the .se of each value it filters, and keeps
# every other channel as it came.
test_expect_success 'the standard errors of the values filtered are dropped' '
	floor se.txt 0.5 &&
	reflect-filter -fa se.txt >out.txt &&
	test_grep "^CHANNELS=N.X N.Y N.Z P.X P.Y P.Z roughness objid spec.R spec.G.se spec.B.se$" out.txt &&
	test_grep "^NCOMP=11$" out.txt &&
	for c in N.X N.Y N.Z P.X P.Y P.Z roughness objid spec.G.se spec.B.se
	do
		column se.txt $c >before &&
		column out.txt $c >after &&
		test -s after &&
		test_cmp_numbers before after 1e-7 || return 1
	done &&
	column se.txt spec.R >before &&
	column out.txt spec.R >after &&
	! cmp -s before after
'

test_expect_success 'a standard error filtered itself, or of a value not filtered, stays' '
	reflect-filter -fa --channels=spec.R,spec.R.se se.txt >both.txt &&
	test_grep "^CHANNELS=N.X N.Y N.Z P.X P.Y P.Z roughness objid spec.R spec.R.se spec.G.se spec.B.se$" both.txt &&
	column both.txt spec.R.se | sort -u >got &&
	echo 0.5 >want &&
	diff -u want got &&
	reflect-filter -fa --channels=P.X se.txt >other.txt &&
	test_grep "^NCOMP=12$" other.txt &&
	column se.txt spec.R spec.R.se >before &&
	column other.txt spec.R spec.R.se >after &&
	cmp before after
'

test_expect_success 'a tile of a frame with standard errors: the tile of the filtered frame' '
	reflect-filter -fa -m quad se.txt >whole.txt &&
	reflect-filter -fa -m quad --region=3,2,11,9 se.txt >tile.txt &&
	test_grep "^NCOMP=11$" tile.txt &&
	column whole.txt P.X P.Z spec.R spec.G.se |
		awk "{ x = int(NR - 1) % 16; y = int((NR - 1) / 16) }
			x >= 3 && x < 11 && y >= 2 && y < 9" >want &&
	column tile.txt P.X P.Z spec.R spec.G.se >got &&
	test $(wc -l <got) -eq 56 &&
	cmp want got
'

test_done
