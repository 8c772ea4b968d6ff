#!/bin/sh
test_description='probe shapes: oriented boxes, spheres and proxies in reflect-project'
. "$srcdir/tests/lib.sh"

# gbuf FILE KEYS ROW...: an ascii G-buffer (P N V) of one row; KEYS are
# header lines (one per line) after the box and centre
gbuf () {
	out=$1
	keys=$2
	shift 2
	{
		printf '#?REFLECT1\nNCOLS=%d\nNROWS=1\nNCOMP=9\n' $#
		printf 'CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z\n'
		printf '%s\n' "$keys"
		printf 'FORMAT=ascii\n\n'
		for row
		do
			echo "$row"
		done
	} >"$out"
}

# the projection's outputs of each pixel: R D hit.dist probe.dist
outputs () {
	sed -n '/^$/,$p' "$1" | sed 1d | awk '{ print $10, $11, $12, $13, $14, $15, $16, $17 }'
}

box='PROBE_BOX=-3 0 -2 3 3 2
PROBE_CENTER=0 1.5 0'

test_expect_success 'setup: a scene and its G-buffer' '
	cat >room.scene <<-\EOF &&
	probe center 0.4 1.2 -0.3 box -3 0 -2 3 3 2
	camera position 0.5 1.6 1.8 target 0 0.8 0 fov 60
	sphere center 0 1 0 radius 0.5 roughness 0.1
	EOF
	reflect-gbuffer -x 48 -y 32 -fa room.scene >g.txt &&
	# the same stream with a rotation of nothing, as angles and as a matrix
	sed "/^PROBE_BOX=/a PROBE_ROTATION=0 0 0" g.txt >g0.txt &&
	sed "/^PROBE_BOX=/a PROBE_ROTATION=1 0 0 0 1 0 0 0 1" g.txt >gi.txt &&
	test_grep "^PROBE_ROTATION=0 0 0$" g0.txt
'

test_expect_success 'a box turned by nothing is the box, byte for byte, in box and bevel' '
	for m in box bevel:radius=0.4 bevel:radius=0.3:offset=1:roughen=0.5
	do
		reflect-project -m $m -h g.txt >a.bin &&
		reflect-project -m $m -h g0.txt >b.bin &&
		reflect-project -m $m -h gi.txt >c.bin &&
		cmp a.bin b.bin && cmp a.bin c.bin || return 1
	done &&
	# and the rotation key is not written for it
	reflect-project -fa g0.txt >o.txt &&
	! grep "^PROBE_ROTATION" o.txt
'

# turned FILE: the G-buffer of pixels drawn at random inside the box,
# and TURNED the whole of it (points, normals, views, capture point)
# turned by 30 degrees about an oblique axis through the box centre,
# the box with it; Q the rotation
make_pair () {
	awk -v n=200 -v qfile=q.txt -v afile=a.txt -v bfile=b.txt -v bevel="$1" '
	function unit(v,   l) { l = sqrt(v[1]^2 + v[2]^2 + v[3]^2); v[1] /= l; v[2] /= l; v[3] /= l }
	function turn(v, w, centre,   i, d) {
		for (i = 1; i <= 3; i++) d[i] = v[i] - (centre ? c[i] : 0)
		for (i = 1; i <= 3; i++)
			w[i] = q[i, 1] * d[1] + q[i, 2] * d[2] + q[i, 3] * d[3] + (centre ? c[i] : 0)
	}
	BEGIN {
		srand(7)
		ax[1] = 1; ax[2] = 2; ax[3] = -2; unit(ax)
		a = 30 * 3.14159265358979 / 180; co = cos(a); si = sin(a); t = 1 - co
		x = ax[1]; y = ax[2]; z = ax[3]
		q[1,1] = t*x*x + co;   q[1,2] = t*x*y - si*z; q[1,3] = t*x*z + si*y
		q[2,1] = t*x*y + si*z; q[2,2] = t*y*y + co;   q[2,3] = t*y*z - si*x
		q[3,1] = t*x*z - si*y; q[3,2] = t*y*z + si*x; q[3,3] = t*z*z + co
		c[1] = 0; c[2] = 1.5; c[3] = 0
		cap[1] = 0.5; cap[2] = 1.2; cap[3] = -0.4
		turn(cap, cap2, 1)
		hdr = "#?REFLECT1\nNCOLS=" n "\nNROWS=1\nNCOMP=9\nCHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z\nPROBE_BOX=-3 0 -2 3 3 2\n"
		if (bevel != "") hdr = hdr "PROBE_BEVEL=" bevel "\n"
		printf "%sPROBE_CENTER=%.9g %.9g %.9g\nFORMAT=ascii\n\n", hdr, cap[1], cap[2], cap[3] > afile
		printf "%sPROBE_CENTER=%.9g %.9g %.9g\nPROBE_ROTATION=%.12g %.12g %.12g %.12g %.12g %.12g %.12g %.12g %.12g\nFORMAT=ascii\n\n",
			hdr, cap2[1], cap2[2], cap2[3], q[1,1], q[1,2], q[1,3], q[2,1], q[2,2], q[2,3],
			q[3,1], q[3,2], q[3,3] > bfile
		for (i = 1; i <= 3; i++) printf "%.12g %.12g %.12g\n", q[i,1], q[i,2], q[i,3] > qfile
		for (k = 0; k < n; k++) {
			p[1] = -2.9 + 5.8 * rand(); p[2] = 0.1 + 2.8 * rand(); p[3] = -1.9 + 3.8 * rand()
			do { nn[1] = rand() - 0.5; nn[2] = rand() - 0.5; nn[3] = rand() - 0.5 } while (nn[1]^2 + nn[2]^2 + nn[3]^2 < 0.01)
			unit(nn)
			do { v[1] = rand() - 0.5; v[2] = rand() - 0.5; v[3] = rand() - 0.5 } while (v[1]^2 + v[2]^2 + v[3]^2 < 0.01 || v[1]*nn[1] + v[2]*nn[2] + v[3]*nn[3] < 0.1)
			unit(v)
			turn(p, p2, 1); turn(nn, n2, 0); turn(v, v2, 0)
			printf "%.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g\n", p[1], p[2], p[3], nn[1], nn[2], nn[3], v[1], v[2], v[3] > afile
			printf "%.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g\n", p2[1], p2[2], p2[3], n2[1], n2[2], n2[3], v2[1], v2[2], v2[3] > bfile
		}
	}'
}

# turn_outputs Q OUT: OUT's R and D turned by Q, the distances kept
turn_outputs () {
	awk -v qf="$1" 'BEGIN { for (i = 1; i <= 3; i++) { getline l < qf; split(l, r); for (j = 1; j <= 3; j++) q[i, j] = r[j] } }
	{
		for (i = 1; i <= 3; i++) {
			R[i] = q[i,1] * $1 + q[i,2] * $2 + q[i,3] * $3
			D[i] = q[i,1] * $4 + q[i,2] * $5 + q[i,3] * $6
		}
		printf "%.7f %.7f %.7f %.7f %.7f %.7f %.6f %.6f\n", R[1], R[2], R[3], D[1], D[2], D[3], $7 / 10, $8 / 10
	}' "$2"
}

# tenths OUT: OUT with its distances in tenths, so that one tolerance
# holds for directions and distances of up to about ten
tenths () {
	awk '{ printf "%.7f %.7f %.7f %.7f %.7f %.7f %.6f %.6f\n", $1, $2, $3, $4, $5, $6, $7 / 10, $8 / 10 }' "$1"
}

test_expect_success 'the whole stream turned with the box: the same lookups, turned' '
	make_pair "" &&
	test_line_count 3 q.txt &&
	reflect-project -fa a.txt >oa.txt &&
	reflect-project -fa b.txt >ob.txt &&
	outputs oa.txt >ra && outputs ob.txt >rb &&
	turn_outputs q.txt ra >expect &&
	tenths rb >got &&
	test_cmp_numbers expect got 2e-5 &&
	# and it is a turn that matters: unturned, the box differs
	sed /^PROBE_ROTATION/d b.txt >b0.txt &&
	reflect-project -fa b0.txt >o0.txt &&
	outputs o0.txt >r0 && tenths r0 >got0 &&
	! test_cmp_numbers expect got0 2e-5 2>/dev/null
'

test_expect_success 'bevel on a turned box: the same, turned' '
	make_pair "0.5" &&
	reflect-project -fa -m bevel:radius=0.5 a.txt >oa.txt &&
	reflect-project -fa -m bevel:radius=0.5 b.txt >ob.txt &&
	outputs oa.txt >ra && outputs ob.txt >rb &&
	turn_outputs q.txt ra >expect &&
	tenths rb >got &&
	test_cmp_numbers expect got 5e-5
'

sphere='PROBE_BOX=-2 -2 -2 2 2 2
PROBE_SHAPE=sphere
PROBE_CENTER=0 0 0'

test_expect_success 'a sphere: exits by hand' '
	# from the centre every exit is the radius; from (1, 0, 0) along +y
	# the exit is (1, sqrt 3, 0) at sqrt 3, seen from the centre at
	# (0.5, sqrt 3 / 2, 0), 2 away
	gbuf s.txt "$sphere" "0 0 0 0 0 1 0 0 1" "1 0 0 0 1 0 0 1 0" \
		"0 -1.5 0 0 1 0 0.6 0.8 0" &&
	reflect-project -fa s.txt >o.txt &&
	outputs o.txt >got &&
	# last: N = (0,1,0), V = (0.6,0.8,0): R = (-0.6, 0.8, 0); from
	# (0,-1.5,0): t^2 - 2.4 t + 2.25 - 4 = 0, t = 1.2 + sqrt(3.19)
	awk "BEGIN { t = 1.2 + sqrt(3.19); x = -0.6 * t; y = -1.5 + 0.8 * t;
		printf \"0 0 1 0 0 1 2 2\n0 1 0 0.5 0.866025404 0 1.73205081 2\n\";
		printf \"-0.6 0.8 0 %.9f %.9f 0 %.9f 2\n\", x / 2, y / 2, t }" >expect &&
	test_cmp_numbers expect got 2e-6 &&
	test_grep "^PROBE_SHAPE=sphere$" o.txt
'

test_expect_success 'a proxy of its own: the lookups follow it, the keys pass through' '
	gbuf p.txt "$box
PROBE_PROXY=sphere
PROBE_PROXY_BOX=-2 -0.5 -2 2 3.5 2" "0 1.5 0 0 0 1 0 0 1" &&
	reflect-project -fa p.txt >o.txt &&
	outputs o.txt >got &&
	echo "0 0 1 0 0 1 2 2" >expect &&
	test_cmp_numbers expect got 1e-6 &&
	test_grep "^PROBE_PROXY=sphere$" o.txt &&
	test_grep "^PROBE_PROXY_BOX=-2 -0.5 -2 2 3.5 2$" o.txt &&
	gbuf i.txt "$box
PROBE_PROXY=infinite" "1 1 0.5 0.6 0.8 0 0 0.6 0.8" &&
	reflect-project -fa i.txt >o.txt &&
	outputs o.txt >got &&
	echo "0.576 0.168 -0.8 0.576 0.168 -0.8 inf inf" >expect &&
	test_cmp_numbers expect got 1e-6
'

test_expect_success 'bad shape keys: refused, the key and the fix named' '
	gbuf bad.txt "$box
PROBE_ROTATION=1 0 0 0 1 0 0 0 0" "0 1.5 0 0 0 1 0 0 1" &&
	test_expect_code 1 reflect-project -fa bad.txt >/dev/null 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "reflect-project: .*PROBE_ROTATION: .1 0 0 0 1 0 0 0 0. is not a rotation" err &&
	gbuf bad.txt "$box
PROBE_SHAPE=sphere" "0 1.5 0 0 0 1 0 0 1" &&
	test_expect_code 1 reflect-project -fa bad.txt >/dev/null 2>err &&
	test_grep "bounding cube" err &&
	gbuf bad.txt "$sphere" "0 0 0 0 0 1 0 0 1" &&
	test_expect_code 1 reflect-project -fa -m bevel:radius=0.5 bad.txt >/dev/null 2>err &&
	test_grep "the probe.s proxy is a sphere, and bevel rounds a box: use mode box" err &&
	gbuf bad.txt "$box
PROBE_PROXY=infinite" "0 0 0 0 0 1 0 0 1" &&
	reflect-project -fa bad.txt >o.txt &&
	test_expect_code 1 reflect-occlude -m box:scale=box o.txt >/dev/null 2>err &&
	test_grep "scale=box needs a size, and the probe.s proxy is infinite: give scale=world" err
'

test_done
