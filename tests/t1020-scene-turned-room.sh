#!/bin/sh
test_description='a turned room: the G-buffer, the trace and the capture turn with it'
. "$srcdir/tests/lib.sh"

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
	cat >img.txt <<-\EOF &&
	#?REFLECT1
	NCOLS=2
	NROWS=2
	NCOMP=3
	CHANNELS=R G B
	FORMAT=ascii

	1 2 3
	4 5 6
	7 8 9
	10 11 12
	EOF
	reflect-export -o wall.exr img.txt &&
	cat >a.scene <<-\EOF &&
	probe center 0.4 1.4 -0.3 box -3 0 -2 3 3 2 blend 0.5
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

# A cube room turned by 90 degrees about y: its +x wall is the world s
# -z wall, local (1, y, z) at world (z, y, -1).  The window over z in
# [-1, 0], y in [0, 1] lies at world x in [-1, 0] on it: texel (0, 0) of
# face -Z at 2 texels a face (a = x, b = -y there), the 21st of 24.
test_expect_success 'capture of a room turned by 90 degrees, by hand' '
	cat >win.scene <<-\EOF &&
	probe box -1 -1 -1 1 1 1 rotate 0 90 0
	window +x min -1 0 max 0 1 radiance 8 4 2
	EOF
	reflect-capture -n 2 -o w.exr win.scene &&
	"$imgdump" w.exr | sed 1,2d >got &&
	awk "{ print (NR == 21 ? \"8 4 2\" : \"0 0 0\") }" got >expect &&
	test_cmp_numbers expect got 0
'

# Walls of one colour each in the oblique turn: a texel whose corners
# and centre all leave the room by one wall (in its frame) is that wall s
# colour exactly; awk finds those texels.
test_expect_success 'capture of the obliquely turned room: each texel its wall' '
	{
		sed -n 1p b.scene | sed "s/center [^b]*box/box/" &&
		cat <<-\EOF
		wall +x emission 1 0 0
		wall -x emission 0 1 0
		wall +y emission 0 0 1
		wall -y emission 1 1 0
		wall +z emission 0 1 1
		wall -z emission 1 0 1
		EOF
	} >walls.scene &&
	reflect-capture -n 8 -o walls.exr walls.scene &&
	"$imgdump" walls.exr | sed 1,2d >got &&
	awk "
	function wall(f, a, b,   d, l, i, t, best, w, o) {
		if (f == 0) { d[1] = 1; d[2] = -b; d[3] = a }
		if (f == 1) { d[1] = -1; d[2] = -b; d[3] = -a }
		if (f == 2) { d[1] = a; d[2] = 1; d[3] = -b }
		if (f == 3) { d[1] = a; d[2] = -1; d[3] = b }
		if (f == 4) { d[1] = -a; d[2] = -b; d[3] = 1 }
		if (f == 5) { d[1] = a; d[2] = -b; d[3] = -1 }
		# into the room s frame: q transposed; from its centre (0 1.5 0)
		for (i = 1; i <= 3; i++) l[i] = q[1,i] * d[1] + q[2,i] * d[2] + q[3,i] * d[3]
		lo[1] = -3; lo[2] = -1.5; lo[3] = -2; hi[1] = 3; hi[2] = 1.5; hi[3] = 2
		best = 1e30
		for (i = 1; i <= 3; i++) {
			if (l[i] == 0) continue
			t = (l[i] > 0 ? hi[i] : lo[i]) / l[i]
			if (t < best) { best = t; w = 2 * (i - 1) + (l[i] < 0) }
		}
		return w
	}
	BEGIN {
		for (i = 1; i <= 3; i++) { getline r <\"q.txt\"; split(r, e); for (j = 1; j <= 3; j++) q[i, j] = e[j] }
		split(\"1 0 0|0 1 0|0 0 1|1 1 0|0 1 1|1 0 1\", col, \"|\")
	}
	{
		k = NR - 1; f = int(k / 64); j = int((k % 64) / 8); i = k % 8
		a0 = i / 4 - 1; b0 = j / 4 - 1
		w = wall(f, a0 + 0.125, b0 + 0.125)
		if (wall(f, a0, b0) != w || wall(f, a0 + 0.25, b0) != w ||
		    wall(f, a0, b0 + 0.25) != w || wall(f, a0 + 0.25, b0 + 0.25) != w)
			next
		n++
		if (\$0 != col[w + 1]) { print \"texel \" k \": \" \$0 \", expected \" col[w + 1]; bad = 1 }
	}
	END { print n >\"whole\"; exit bad }" got &&
	# three texels in four lie within one wall (292 of 384)
	test $(cat whole) -gt 250
'

test_done
