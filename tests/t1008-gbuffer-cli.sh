#!/bin/sh
test_description='reflect-gbuffer: header keys, channels, default scene and conventions'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"

test_expect_success 'the default scene: header keys for the stages downstream' '
	reflect-gbuffer -x 8 -y 4 -fa >out.txt &&
	test_grep "^reflect-gbuffer -x 8 -y 4 -fa$" out.txt &&
	test_grep "^SCENE=default$" out.txt &&
	test_grep "^PROBE_BOX=-3 0 -2 3 3 2$" out.txt &&
	test_grep "^PROBE_CENTER=0 1.5 0$" out.txt &&
	test_grep "^PROBE_BOX_PROJECTION=1$" out.txt &&
	test_grep "^PROBE_ENV=default$" out.txt &&
	test_grep "^PROBE_BLEND=1$" out.txt &&
	test_grep "^CAMERA=-2.6 1.6 1.8 0.9 0.45 -1 0 1 0 55$" out.txt &&
	test_grep "^FRAME=0$" out.txt &&
	test_grep "^CHANNELS=P.X P.Y P.Z N.X N.Y N.Z Ng.X Ng.Y Ng.Z V.X V.Y V.Z roughness metallic albedo.R albedo.G albedo.B mask objid depth emission.R emission.G emission.B$" out.txt
'

test_expect_success 'the default scene has no NaN and sees no nothing' '
	reflect-gbuffer -x 320 -y 180 | reflect-info -s >stats &&
	awk "/^\tP.X/,0 { if (\$5 != 0 || \$6 != 0) bad = 1 } END { exit bad }" stats &&
	awk "/^\tobjid/ { exit !(\$2 == -6 && \$3 == 9) }" stats
'

test_expect_success '--print-default-scene prints a scene that renders the same' '
	reflect-gbuffer --print-default-scene >default.scene &&
	test_grep "^probe center 0 1.5 0 box -3 0 -2 3 3 2" default.scene &&
	reflect-gbuffer -x 64 -y 36 -h >embedded.rf &&
	reflect-gbuffer -x 64 -y 36 -h default.scene >printed.rf &&
	cmp embedded.rf printed.rf &&
	reflect-gbuffer -x 4 -y 4 -fa default.scene >out.txt &&
	test_grep "^SCENE=default$" out.txt
'

test_expect_success 'several probes: PROBE2_* keys, env paths next to the scene' '
	mkdir -p dir &&
	cat >dir/two.scene <<-\EOF &&
	probe center 0 1.5 0 box -3 0 -2 3 3 2 env room.exr blend 0.5
	probe center 4 1 0 box 3 0 -1 5 2 1 projection off
	EOF
	reflect-gbuffer -x 2 -y 2 -fa dir/two.scene >out.txt &&
	test_grep "^SCENE=two$" out.txt &&
	test_grep "^PROBE_ENV=dir/room.exr$" out.txt &&
	test_grep "^PROBE_BLEND=0.5$" out.txt &&
	test_grep "^PROBE2_BOX=3 0 -1 5 2 1$" out.txt &&
	test_grep "^PROBE2_CENTER=4 1 0$" out.txt &&
	test_grep "^PROBE2_BOX_PROJECTION=0$" out.txt &&
	test_grep "^PROBE2_ENV=default$" out.txt &&
	test_grep "^PROBE2_BLEND=1$" out.txt &&
	test_grep "^CAMERA=0 1.5 0 0 1.5 -1 0 1 0 60$" out.txt
'

test_expect_success 'the example of reflect-scene(5) is a valid scene' '
	sed -n "/^\.SH EXAMPLE/,/^\.SH/p" "$srcdir/doc/reflect-scene.5" |
	sed -e "/^\./d" -e "s/\\\\-/-/g" -e "s/\\\\e/\\\\/g" >example.scene &&
	test_grep "^name corridor$" example.scene &&
	reflect-gbuffer -x 8 -y 8 -fa example.scene >out.txt &&
	test_grep "^PROBE_ENV=corridor.exr$" out.txt
'

test_expect_success '-c selects channels; layers stand for their components' '
	reflect-gbuffer -x 2 -y 2 -c V,roughness,objid -fa >out.txt &&
	test_grep "^CHANNELS=V.X V.Y V.Z roughness objid$" out.txt &&
	test_expect_code 1 reflect-gbuffer -c P,spec 2>err &&
	test_one_line_message reflect-gbuffer err &&
	test_grep "unknown G-buffer channel .spec." err
'

test_expect_success 'the stream goes on through reflect-project' '
	reflect-gbuffer -x 16 -y 9 | reflect-project -fa >out.txt &&
	test_grep "^PROJECTION=box$" out.txt &&
	test_grep "^CHANNELS=.* R.X R.Y R.Z D.X D.Y D.Z hit.dist probe.dist$" out.txt
'

test_expect_success 'raw output with -h is the frame alone' '
	reflect-gbuffer -x 5 -y 3 -h >raw &&
	test "$(wc -c <raw)" -eq $((5 * 3 * 23 * 4))
'

test_expect_success '--help on stdout, -V, usage errors' '
	reflect-gbuffer --help >out 2>err &&
	test_grep "^usage: reflect-gbuffer" out &&
	test ! -s err &&
	reflect-gbuffer -V >out &&
	test_grep "^reflect-gbuffer (reflect) " out &&
	test_expect_code 1 reflect-gbuffer -Q 2>err &&
	test_grep "^usage: reflect-gbuffer" err &&
	test_expect_code 1 reflect-gbuffer a.scene b.scene 2>err &&
	test_grep "^usage: reflect-gbuffer" err &&
	test_expect_code 1 reflect-gbuffer -x 0 2>err &&
	test_one_line_message reflect-gbuffer err
'

test_expect_success 'a closed pipe ends it quietly' '
	{ reflect-gbuffer -x 2000 -y 2000 -n 50 2>err; echo $? >status; } | head -c 100 >/dev/null &&
	test ! -s err &&
	test "$(cat status)" -ne 0
'

test_done
