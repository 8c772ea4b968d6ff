#!/bin/sh
test_description='probe shapes in the scene: rotate, matrix, sphere and proxy'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"

test_expect_success 'the shapes become the stream keys' '
	cat >s.scene <<-\EOF &&
	probe center 0 1.5 0 box -3 0 -2 3 3 2 proxy sphere 3
	probe center 1.5 1 0 box 0.5 0 -1 2.5 2 1 rotate 0 30 0 blend 0.3
	probe center -1.5 1 0 sphere 0.9 blend 0.2 proxy infinite
	probe center 0 1 1 box -1 0 0 1 2 2 proxy box -2 0 -1 2 3 3 proxy_matrix 0 -1 0 1 0 0 0 0 1
	camera position 0 1.6 2 target 0 1 0 fov 60
	sphere center 0 1 0 radius 0.5 roughness 0.2
	EOF
	reflect-gbuffer -x 16 -y 12 s.scene >g.rfl &&
	reflect-info g.rfl >info &&
	# the proxy sphere of radius 3 around (0, 1.5, 0), its bounding cube
	test_grep "PROBE_PROXY=sphere$" info &&
	test_grep "PROBE_PROXY_BOX=-3 -1.5 -3 3 4.5 3$" info &&
	# y 30: cos 30 = 0.866025388 as a float, sin 30 = 0.5
	test_grep "PROBE2_ROTATION=0.866025388 0 0.5 0 1 0 -0.5 0 0.866025388$" info &&
	test_grep "PROBE3_SHAPE=sphere$" info &&
	test_grep "PROBE3_BOX=-2.4 0.1 -0.9 -0.6 1.9 0.9$" info &&
	test_grep "PROBE3_PROXY=infinite$" info &&
	test_grep "PROBE4_PROXY_ROTATION=0 -1 0 1 0 0 0 0 1$" info &&
	! grep "PROBE_ROTATION\|PROBE_SHAPE\|PROBE2_SHAPE\|PROBE2_PROXY" info
'

test_expect_success 'turned by nothing: the stream of the unturned scene, byte for byte' '
	cat >a.scene <<-\EOF &&
	probe center 0 1.5 0 box -3 0 -2 3 3 2
	probe center 1.5 1 0 box 0.5 0 -1 2.5 2 1 blend 0.3
	camera position 0 1.6 2 target 0 1 0 fov 60
	sphere center 0 1 0 radius 0.5 roughness 0.2
	EOF
	sed "2s/blend/rotate 0 0 0 blend/" a.scene >b.scene &&
	sed "2s/blend/matrix 1 0 0 0 1 0 0 0 1 blend/" a.scene >c.scene &&
	reflect-gbuffer -x 32 -y 24 a.scene | reflect-project | reflect-shade -m hdrp -h >a.bin &&
	reflect-gbuffer -x 32 -y 24 b.scene | reflect-project | reflect-shade -m hdrp -h >b.bin &&
	reflect-gbuffer -x 32 -y 24 c.scene | reflect-project | reflect-shade -m hdrp -h >c.bin &&
	cmp a.bin b.bin && cmp a.bin c.bin
'

# channel FILE NAME: the channel's value of each pixel of an ascii stream
channel () {
	awk -v name="$2" '
	/^CHANNELS=/ { n = split(substr($0, 10), c, " "); for (i = 1; i <= n; i++) if (c[i] == name) k = i; next }
	/^NCOMP=/ { ncomp = substr($0, 7); next }
	!body && /^$/ { body = 1; next }
	body { for (i = k; i <= NF; i += ncomp) print $i }' "$1"
}

test_expect_success 'a turned second probe weighs inside its turned box only' '
	# probe 2 is the box x [0.5, 2.5] z [-1, 1] turned 45 degrees about y
	# around (1.5, 1, 0): (1.5, 1, 1.2) is inside it (local z 0.85), and
	# outside the unturned box; (2.4, 1, 0.9) the other way round
	printf "%s\n" "#?REFLECT1" "NCOLS=2" "NROWS=1" "NCOMP=10" \
		"CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness" \
		"PROBE_BOX=-3 0 -2 3 3 2" "PROBE_BLEND=0" \
		"PROBE2_BOX=0.5 0 -1 2.5 2 1" "PROBE2_CENTER=1.5 1 0" "PROBE2_BLEND=0" \
		"PROBE2_ROTATION=0 45 0" "FORMAT=ascii" "" \
		"1.5 1 1.2 0 1 0 0 1 0 0.5 2.4 1 0.9 0 1 0 0 1 0 0.5" >w.txt &&
	reflect-project -fa w.txt | reflect-shade -fa -m hdrp >o.txt &&
	channel o.txt weight.probe2 >got &&
	printf "1\n0\n" >expect &&
	test_cmp_numbers expect got 0 &&
	sed "/PROBE2_ROTATION/d" w.txt | reflect-project -fa | reflect-shade -fa -m hdrp >o0.txt &&
	channel o0.txt weight.probe2 >got &&
	printf "0\n1\n" >expect &&
	test_cmp_numbers expect got 0
'

# Without a room drawn, the first probe's shape is a probe's like any
# other: a sphere too, wherever 'room off' stands.
test_expect_success 'a sphere first probe where no room is drawn' '
	for order in before after
	do
		{
			test $order = after || echo "room off" &&
			echo "probe center 0 1.5 0 sphere 1.5 proxy infinite" &&
			echo "camera position 0 1.5 1 target 0 1 0 fov 60" &&
			echo "sphere center 0 1 0 radius 0.3 roughness 0.2" &&
			{ test $order = before || echo "room off"; }
		} >r.scene &&
		reflect-gbuffer -x 8 -y 6 r.scene >g.rfl &&
		reflect-info g.rfl >info &&
		test_grep "PROBE_SHAPE=sphere$" info &&
		test_grep "PROBE_BOX=-1.5 0 -1.5 1.5 3 1.5$" info &&
		test_grep "PROBE_PROXY=infinite$" info || return 1
	done
'

test_expect_success 'bad shapes: refused at their place' '
	bad_scene "1:22: the first probe.s box is the scene.s room, whose walls cannot be a sphere: give the first probe a box" <<-\EOF &&
	probe center 0 1.5 0 sphere 1.5
	EOF
	bad_scene "1:22: the first probe.s box is the scene.s room, whose walls cannot be a sphere: .* or draw no room (.room off.)$" <<-\EOF &&
	probe center 0 1.5 0 sphere 1.5
	room on
	EOF
	bad_scene "2:25: expected a rotation, and this matrix is not orthonormal$" <<-\EOF &&
	probe box -3 0 -2 3 3 2
	probe box -1 0 -1 1 2 1 matrix 1 0 0 0 1 0 0 0 0
	EOF
	bad_scene "2:25: expected a rotation, and this matrix is a reflection" <<-\EOF &&
	probe box -3 0 -2 3 3 2
	probe box -1 0 -1 1 2 1 matrix -1 0 0 0 1 0 0 0 1
	EOF
	bad_scene "2:45: expected a radius greater than 0 for .sphere., found -1$" <<-\EOF &&
	probe box -3 0 -2 3 3 2
	probe center 0 1 0 box -1 0 -1 1 2 1 sphere -1
	EOF
	bad_scene "2:20: a probe is a box or a sphere, not both" <<-\EOF &&
	probe box -3 0 -2 3 3 2
	probe center 0 1 0 box -1 0 -1 1 2 1 sphere 1
	EOF
	bad_scene "2:1: expected .center X Y Z. (the sphere.s centre)" <<-\EOF &&
	probe box -3 0 -2 3 3 2
	probe sphere 1
	EOF
	bad_scene "2:7: expected the probe.s centre inside its turned box, and (1.2 1 0.5) is outside it on the box.s own Z axis$" <<-\EOF &&
	probe box -3 0 -2 3 3 2
	probe center 1.2 1 0.5 box -2 0 -0.5 2 2 1.5 rotate 0 90 0
	EOF
	bad_scene "2:31: expected a proxy: box, sphere or infinite, found .cone.$" <<-\EOF &&
	probe box -3 0 -2 3 3 2
	probe box -1 0 -1 1 2 1 proxy cone 2
	EOF
	bad_scene "2:40: only a proxy box turns" <<-\EOF
	probe box -3 0 -2 3 3 2
	probe box -1 0 -1 1 2 1 proxy sphere 2 proxy_rotate 0 10 0
	EOF
'

test_done
