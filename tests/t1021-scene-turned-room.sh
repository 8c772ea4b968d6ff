#!/bin/sh
test_description='a turned room: the G-buffer, the trace and the capture turn with it'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"

imgdump="$builddir/tests/imgdump"

# turn_scene ANGLE AX AY AZ <IN >OUT: the scene turned by ANGLE degrees
# about the axis (AX AY AZ) through the room's centre (0 1.5 0): points
# after center, position and target, directions after up, normal and
# tangent; the room's box keeps its numbers and gains the rotation, its
# frame's own.  The rotation, row after row, into q.txt.
turn_scene () {
	awk -v ang="$1" -v ax="$2" -v ay="$3" -v az="$4" '
	function turn(x, y, z, centre,   d1, d2, d3) {
		d1 = x - centre * c[1]; d2 = y - centre * c[2]; d3 = z - centre * c[3]
		return sprintf("%.15g %.15g %.15g",
			q[1,1] * d1 + q[1,2] * d2 + q[1,3] * d3 + centre * c[1],
			q[2,1] * d1 + q[2,2] * d2 + q[2,3] * d3 + centre * c[2],
			q[3,1] * d1 + q[3,2] * d2 + q[3,3] * d3 + centre * c[3])
	}
	BEGIN {
		c[1] = 0; c[2] = 1.5; c[3] = 0
		l = sqrt(ax^2 + ay^2 + az^2); x = ax / l; y = ay / l; z = az / l
		a = ang * 3.14159265358979324 / 180; co = cos(a); si = sin(a); t = 1 - co
		q[1,1] = t*x*x + co;   q[1,2] = t*x*y - si*z; q[1,3] = t*x*z + si*y
		q[2,1] = t*x*y + si*z; q[2,2] = t*y*y + co;   q[2,3] = t*y*z - si*x
		q[3,1] = t*x*z - si*y; q[3,2] = t*y*z + si*x; q[3,3] = t*z*z + co
		for (i = 1; i <= 3; i++)
			printf "%.15g %.15g %.15g\n", q[i,1], q[i,2], q[i,3] >"q.txt"
		m = ""
		for (i = 1; i <= 3; i++) for (j = 1; j <= 3; j++) m = m " " sprintf("%.15g", q[i,j])
	}
	{
		out = $1
		for (i = 2; i <= NF; i++) {
			w = $i
			if (w == "center" || w == "position" || w == "target") {
				out = out " " w " " turn($(i+1), $(i+2), $(i+3), 1); i += 3
			} else if (w == "up" || w == "normal" || w == "tangent") {
				out = out " " w " " turn($(i+1), $(i+2), $(i+3), 0); i += 3
			} else if (w == "box" && $1 == "probe") {
				out = out " box " $(i+1) " " $(i+2) " " $(i+3) " " $(i+4) " " $(i+5) " " $(i+6) " matrix" m
				i += 6
			} else
				out = out " " w
		}
		print out
	}'
}

# body FILE: an ascii stream's pixels, one a line
body () {
	sed -n "/^\$/,\$p" "$1" | sed 1d
}

# gbuffer_turned A B: G-buffer B (P N Ng V T roughness metallic albedo
# mask objid depth emission) is A turned by q.txt about the room's
# centre, pixel by pixel: P within 8e-5, the unit vectors within 2e-5,
# the rest within 2e-5 relative.  A sphere has no frame to turn its
# tangent with (east on it is about +Y), so its T is not compared.
# Prints the pixels and those whose objects differ.
gbuffer_turned () {
	body "$2" >b.body &&
	body "$1" | awk -v tol=2e-5 '
	function bad(msg) { if (nbad++ < 5) print "pixel " np ": " msg >"/dev/stderr"; err = 1 }
	function far(a, b, scale) { return (a - b < 0 ? b - a : a - b) > tol * scale }
	BEGIN {
		for (i = 1; i <= 3; i++) { getline l <"q.txt"; split(l, r); for (j = 1; j <= 3; j++) q[i, j] = r[j] }
		c[1] = 0; c[2] = 1.5; c[3] = 0
	}
	{
		if ((getline l <"b.body") <= 0) { bad("missing"); exit 1 }
		np++
		split(l, b)
		if ($22 != b[22]) { other++; next }
		for (v = 0; v < 5; v++) {
			if (v == 4 && ($22 == 2 || $22 == 3)) continue
			o = 3 * v; p = v ? 0 : 1
			for (i = 1; i <= 3; i++) {
				w = q[i,1] * ($(o+1) - p * c[1]) + q[i,2] * ($(o+2) - p * c[2])
				w += q[i,3] * ($(o+3) - p * c[3]) + p * c[i]
				if (far(w, b[o+i], p ? 4 : 1))
					bad("vector " v + 1 " axis " i ": " w " turned, " b[o+i] " found")
			}
		}
		for (k = 16; k <= 26; k++)
			if (k != 22 && far($k, b[k], ($k < 0 ? -$k : $k) + 1))
				bad("channel " k ": " $k " and " b[k])
	}
	END { print np, other + 0; exit err }'
}

test_expect_success 'setup: a room and the room turned by 30 degrees about an oblique axis' '
	write_wall_image wall.exr &&
	cat >a.scene <<-\EOF &&
	probe center 0.4123 1.3871 -0.2937 box -3 0 -2 3 3 2 blend 0.5
	pattern cell 0.5 line-width 0.05 base 0.42 checker 0.18 line 3 line-white 1
	wall +x pattern 0.8 0.25 0.2
	wall -x pattern 0.2 0.65 0.25
	wall +y pattern 0.85 0.85 0.8
	wall -y pattern 0.45 0.35 0.28
	wall +z pattern 0.2 0.3 0.85
	wall -z image wall.exr size 0.7 0.5 origin 0.2 0.1 gain 0.5
	window +x min -1.2 1 max 0.2 2.3 radiance 18 15.5 12 mullions 0.06 1 1 1
	camera position -2.4 1.6 1.6 target 0.9 0.5 -1 up 0 1 0 fov 60
	rect center 0 0.02 0 normal 0 1 0 tangent 1 0 0 size 5 3.5 roughness 0.2
	sphere center -1 0.5 -0.5 radius 0.4 roughness 0.1
	sphere center 1 0.6 0.3 radius 0.45 roughness 0.5 metallic 0 albedo 0.7 0.5 0.3
	EOF
	turn_scene 30 1 2 -2 <a.scene >b.scene &&
	test_line_count 3 q.txt &&
	test_grep "^probe center .* box -3 0 -2 3 3 2 matrix 0.88091147" b.scene
'

test_expect_success 'the G-buffer of the turned room is the G-buffer turned' '
	c=P,N,Ng,V,T,roughness,metallic,albedo,mask,objid,depth,emission &&
	reflect-gbuffer -x 40 -y 30 -fa -c $c a.scene >ga.txt &&
	reflect-gbuffer -x 40 -y 30 -fa -c $c b.scene >gb.txt &&
	gbuffer_turned ga.txt gb.txt >counts &&
	# every pixel on the same object: no ray crosses an edge by rounding
	echo "1200 0" >expect &&
	cmp expect counts &&
	# the image on -z, the floor, the ceiling, the window on +x, the
	# mirror and the spheres are seen
	body ga.txt | awk "{ print \$22 }" | sort -n | uniq >ids &&
	printf "%s\n" -6 -4 -3 -1 1 2 3 >expect &&
	cmp expect ids &&
	# and it can fail: the room left unturned is another room
	sed "1s/ matrix.*blend/ blend/" b.scene >c.scene &&
	reflect-gbuffer -x 40 -y 30 -fa -c $c c.scene >gc.txt &&
	! gbuffer_turned ga.txt gc.txt 2>/dev/null
'

# traced_same A B: traces A and B (R G B mask objid) agree pixel by pixel
# within 2e-6 relative (plus 1e-6): float rounding, not noise
traced_same () {
	body "$2" >b.body &&
	body "$1" | awk "
	{
		getline l <\"b.body\"; split(l, b)
		for (k = 1; k <= 5; k++) {
			d = \$k - b[k]; if (d < 0) d = -d
			if (d > 2e-6 * (\$k < 0 ? -\$k : \$k) + 1e-6) { print NR \": \" \$k \" and \" b[k]; bad = 1 }
		}
	}
	END { exit bad }"
}

test_expect_success 'reflect-trace of the turned room: the same image' '
	reflect-trace -x 40 -y 30 --samples=16 -fa a.scene >ta.txt &&
	reflect-trace -x 40 -y 30 --samples=16 -fa b.scene >tb.txt &&
	traced_same ta.txt tb.txt &&
	reflect-trace -x 40 -y 30 --samples=16 -fa c.scene >tc.txt &&
	! traced_same ta.txt tc.txt >/dev/null
'

# same_channels A B NAMES...: the channels NAMES of ascii streams A and
# B agree pixel by pixel within $tol relative (2e-5 unset; plus 2e-7);
# prints how many values it compared
same_channels () {
	a=$1 b=$2
	shift 2
	body "$b" >b.body &&
	awk -v names="$*" -v tol="${tol:-2e-5}" "
	/^CHANNELS=/ {
		sub(/^CHANNELS=/, \"\"); n = split(\$0, ch, \" \")
		for (i = 1; i <= n; i++) at[ch[i]] = i
		m = split(names, want, \" \")
		for (w = 1; w <= m; w++) if (!at[want[w]]) { print \"no channel \" want[w] >\"/dev/stderr\"; exit 1 }
		next
	}
	!body { if (\$0 == \"\") body = 1; next }
	{
		getline l <\"b.body\"; split(l, v)
		for (w = 1; w <= m; w++) {
			i = at[want[w]]; d = \$i - v[i]; if (d < 0) d = -d
			if (d > tol * (\$i < 0 ? -\$i : \$i) + 2e-7) { print NR \": \" want[w] \" \" \$i \" and \" v[i]; bad = 1 }
			count++
		}
	}
	END { print count; exit bad }" "$a"
}

# The probe's capture turns with its box (its cube is in the box's
# frame), so every mode reads the same texels in the turned scene.  The
# capture takes the same number of samples on walls and objects (2):
# the turned mirror's bounding box covers other texels, and with other
# counts those texels would average other samples.
test_expect_success 'every mode: the turned scene gives the same image' '
	for s in a b
	do
		reflect-capture -n 32 --edge-samples=2 --object-samples=2 -o c$s.exr $s.scene &&
		reflect-gbuffer -x 40 -y 30 $s.scene >g$s.rfl || return 1
	done &&
	"$imgdump" ca.exr | sed 1,2d >cube-a &&
	"$imgdump" cb.exr | sed 1,2d >cube-b &&
	test_cmp_numbers cube-a cube-b 2e-5 &&
	for p in box bevel:radius=0.4 infinite
	do
		for m in none approx hdrp godot footprint
		do
			for s in a b
			do
				reflect-project -m $p g$s.rfl >p$s.rfl &&
				reflect-shade -q -m $m --env=c$s.exr --final p$s.rfl >h$s.rfl &&
				reflect-filter -fa h$s.rfl >h$s.txt || return 1
			done &&
			# footprint takes its width rays and their log map in
			# float lanes, which round differently in the turned
			# frame, and the rounding of a width moves the level of
			# a tap: 1.03e-4 at worst here (4e-6 when they were
			# double), twice that allowed
			case $m in footprint) mode_tol=2e-4 ;; *) mode_tol=2e-5 ;; esac &&
			tol=$mode_tol same_channels ha.txt hb.txt spec.R spec.G spec.B R G B \
				diffuse.R diffuse.G diffuse.B >count &&
			echo 10800 >expect &&
			cmp expect count || return 1
		done || return 1
	done &&
	for s in a b
	do
		reflect-project g$s.rfl | reflect-shade -q -m hdrp --env=c$s.exr >h$s.rfl &&
		reflect-occlude -m box h$s.rfl >o1$s.rfl &&
		reflect-occlude -m horizon h$s.rfl >o2$s.rfl &&
		reflect-filter -m atrous h$s.rfl >f1$s.rfl &&
		reflect-filter -m quad h$s.rfl >f2$s.rfl &&
		cat h$s.rfl f2$s.rfl | reflect-accumulate -m ema >e1$s.rfl &&
		cat h$s.rfl f2$s.rfl | reflect-accumulate -m mean >e2$s.rfl || return 1
	done &&
	for k in o1 o2 f1 f2 e1 e2
	do
		reflect-filter -fa ${k}a.rfl >${k}a.txt &&
		reflect-filter -fa ${k}b.rfl >${k}b.txt &&
		same_channels ${k}a.txt ${k}b.txt spec.R spec.G spec.B >/dev/null || return 1
	done &&
	# and the unturned room is not the same
	sed "1s/ matrix.*blend/ blend/" b.scene >d.scene &&
	reflect-gbuffer -x 40 -y 30 d.scene | reflect-project |
		reflect-shade -q -m none --env=cb.exr -fa >hd.txt &&
	reflect-project ga.rfl | reflect-shade -q -m none --env=ca.exr -fa >h0.txt &&
	! same_channels h0.txt hd.txt spec.R >/dev/null 2>&1
'

# raytraced lays its rays in a frame about N: with basis=view, whose x
# axis leans toward V, the turned scene draws the same rays turned, for
# every pattern and sampler, and the images agree to float rounding
# (the largest difference measured is 3.7e-5 relative).  Its default,
# HDRP's frame, is fixed to the world's axes (the write-up's rays): the
# noise is another draw, and the two images agree as estimates, here
# their sums over 1200 pixels at 1024 rays within 0.1 % (measured
# 1.4e-4).
test_expect_success 'raytraced: the same image with basis=view, the same estimate without' '
	for v in white:sampler=vndf blue:sampler=mis deterministic:sampler=mis
	do
		for s in a b
		do
			reflect-project g$s.rfl |
			reflect-shade -q -m raytraced:samples=16:basis=view:pattern=$v \
				--env=c$s.exr --final -fa >r$s.txt || return 1
		done &&
		tol=1e-4 same_channels ra.txt rb.txt spec.R spec.G spec.B R G B >count &&
		echo 7200 >expect &&
		cmp expect count || return 1
	done &&
	for s in a b
	do
		reflect-project g$s.rfl |
		reflect-shade -q -m raytraced:samples=1024 --env=c$s.exr -fa >r$s.txt || return 1
	done &&
	! same_channels ra.txt rb.txt spec.R >/dev/null 2>&1 &&
	for s in a b
	do
		awk "/^CHANNELS=/ { sub(/^CHANNELS=/, \"\"); n = split(\$0, ch, \" \"); for (i = 1; i <= n; i++) if (ch[i] == \"spec.R\") k = i; next }
		!body { if (\$0 == \"\") body = 1; next }
		{ sum += \$k + \$(k + 1) + \$(k + 2) }
		END { printf \"%.9g\\n\", sum }" r$s.txt >sum$s || return 1
	done &&
	awk -v b="$(cat sumb)" "{ d = (\$1 - b) / \$1; if (d < 0) d = -d; exit !(\$1 > 1000 && d < 1e-3) }" suma
'

# A second probe about the room's centre turns with the scene: the
# blend reads its environment in its own frame too.
test_expect_success 'a blend of two turned probes: the same image and weights' '
	sed "1a probe center 0.1 1.1 0.2 box -1.2 0.3 -0.9 1.2 2.7 0.9 blend 0.4" a.scene >a2.scene &&
	turn_scene 30 1 2 -2 <a2.scene >b2.scene &&
	for s in a b
	do
		reflect-capture -p all -n 32 --edge-samples=2 --object-samples=2 \
			-o c2$s%d.exr ${s}2.scene &&
		sed "1s/blend/env c2${s}1.exr blend/; 2s/blend/env c2${s}2.exr blend/" \
			${s}2.scene >${s}3.scene &&
		reflect-gbuffer -x 40 -y 30 ${s}3.scene | reflect-project |
		reflect-shade -q -m hdrp -fa >bl$s.txt || return 1
	done &&
	same_channels bla.txt blb.txt spec.R spec.G spec.B weight.probe1 weight.probe2 \
		weight.fallback >count &&
	echo 7200 >expect &&
	cmp expect count &&
	# the second probe lights some of the pixels
	awk "/^CHANNELS=/ { n = split(substr(\$0, 10), ch, \" \"); for (i = 1; i <= n; i++) if (ch[i] == \"weight.probe2\") k = i; next }
	!body { if (\$0 == \"\") body = 1; next }
	\$k > 0.01 { c++ }
	END { exit !(c > 40) }" bla.txt
'

# A probe's cube is in its box's frame: a cube room turned by 90
# degrees about y, its window on its own +x wall over z in [-1, 0], y in
# [0, 1], is seen where the unturned room shows it, texel (0, 0) of face
# +X at 2 texels a face (t1011), the first of 24, though in the world
# that wall is the -z wall.
test_expect_success 'capture of a room turned by 90 degrees: in its own frame, by hand' '
	cat >win.scene <<-\EOF &&
	probe box -1 -1 -1 1 1 1 rotate 0 90 0
	window +x min -1 0 max 0 1 radiance 8 4 2
	EOF
	reflect-capture -n 2 -o w.exr win.scene &&
	"$imgdump" w.exr | sed 1,2d >got &&
	awk "{ print (NR == 1 ? \"8 4 2\" : \"0 0 0\") }" got >expect &&
	test_cmp_numbers expect got 0 &&
	# the G-buffer sees that window on the world s -z wall: a camera at
	# the centre looking down -z through (-0.5, 0.5, -1) meets it
	cat >>win.scene <<-\EOF &&
	camera position 0 0 0 target -0.5 0.5 -1 fov 10
	EOF
	reflect-gbuffer -x 1 -y 1 -fa -c P,objid,emission win.scene >g.txt &&
	body g.txt >got &&
	echo "-0.5 0.5 -1 -1 8 4 2" >expect &&
	test_cmp_numbers expect got 1e-6
'

test_done
