#!/bin/sh
test_description='room-floor with its floor a glTF quad: the G-buffer and the truth of the analytic scene'
. "$srcdir/tests/lib.sh"

ex=$srcdir/doc/examples
quad=$srcdir/tests/meshes/room-floor-quad.gltf

# Every channel of the G-buffer, one by one.
CHANNELS=P.X,P.Y,P.Z,N.X,N.Y,N.Z,Ng.X,Ng.Y,Ng.Z,V.X,V.Y,V.Z,roughness,metallic
CHANNELS=$CHANNELS,albedo.R,albedo.G,albedo.B,mask,objid,depth
CHANNELS=$CHANNELS,emission.R,emission.G,emission.B

test_expect_success 'the scene with the quad in place of the rect' '
	cp "$quad" . &&
	sed "s|^rect plane y 0.005 .*|mesh room-floor-quad.gltf|" \
		"$ex/room-floor.scene" >quad.scene &&
	grep -q "^mesh room-floor-quad.gltf$" quad.scene &&
	! grep -q "^rect" quad.scene
'

# The quad's positions are floats (0.005 is 0.004999999888 there) and
# its hits are found again in double on the triangle: the same values to
# a float's rounding (2.4e-7 at most, on 2 % of the pixels).
test_expect_success 'the same G-buffer, channel by channel' '
	reflect-gbuffer -x 96 -y 54 "$ex/room-floor.scene" >rect.rfl &&
	reflect-gbuffer -x 96 -y 54 quad.scene >quad.rfl &&
	reflect-compare -c "$CHANNELS" --fail=1e-6 quad.rfl rect.rfl >out &&
	grep PASS out &&
	reflect-compare -c mask,objid --fail=0 quad.rfl rect.rfl
'

test_expect_success 'a changed quad is seen: roughness 0.4 instead of 0.5' '
	sed "s|^mesh room-floor-quad.gltf|& roughness 0.4|" quad.scene >rough.scene &&
	reflect-gbuffer -x 96 -y 54 rough.scene >rough.rfl &&
	test_expect_code 3 reflect-compare -c roughness --fail=2e-5 rough.rfl rect.rfl
'

# The quad is reflective: reflected rays pass it as they pass the rect,
# and the walls they meet are the same to the bit (the headers differ:
# they name the scene).
test_expect_success 'the same truth, byte for byte' '
	reflect-trace -x 48 -y 27 --samples=16 --seed=3 "$ex/room-floor.scene" >rect.tr &&
	reflect-trace -x 48 -y 27 --samples=16 --seed=3 quad.scene >quad.tr &&
	reflect-compare -c R,G,B,mask,objid --fail=0 quad.tr rect.tr
'

test_done
