#!/bin/sh
test_description='reflect-shade --final=split-sum|unity|hdrp: the engines final colours by hand'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

# A sky of one radiance in every level: spec = 1, so R G B is the BRDF
# term alone.  Rows: N = (0,1,0); V at n.v = 1 or 0.5; roughness 0.5 or
# 1; metallic 1, albedo 1 (a white metal, F0 = 1) or metallic 0, albedo
# 0.5 (a dielectric, F0 = 0.04).
test_expect_success 'setup: a uniform sky and a few pixels' '
	awk "BEGIN { n = 8; for (k = 0; k < 4; k++) {
		printf \"#?REFLECT1\\nENVMAP=CUBE\\nLEVEL=%d\\nLEVELS=4\\nPREFILTER=ggx\\n\", k
		printf \"MAPPING=unity\\nSTEPS=3\\nNCOLS=%d\\nNROWS=%d\\n\", n, 6 * n
		printf \"NCOMP=3\\nCHANNELS=R G B\\nFORMAT=ascii\\n\\n\"
		for (j = 0; j < 6 * n * n; j++) print 1, 1, 1
		n = n / 2 } }" >sky.rfl &&
	stream px.txt 5 1 "N.X N.Y N.Z V.X V.Y V.Z D.X D.Y D.Z roughness metallic albedo.R albedo.G albedo.B" <<-\EOF
	0 1 0 0 1 0 0 1 0 0.5 1 1 1 1
	0 1 0 0 1 0 0 1 0 1 1 1 1 1
	0 1 0 0 1 0 0 1 0 0.5 0 0.5 0.5 0.5
	0 1 0 0.866025 0.5 0 0 1 0 0.5 1 1 1 1
	0 1 0 0.866025 0.5 0 0 1 0 0.5 0 0.5 0.5 0.5
	EOF
'

test_expect_success 'unity: surface reduction 1 / (alpha^2 + 1) times lerp(F0, grazing, (1 - n.v)^5)' '
	# metal: grazing = sat(1 - r + 1) = 1, F0 = 1: 1 / (r^4 + 1) = 0.941176
	# at r = 0.5 and 0.5 at r = 1.  Dielectric at n.v = 1: 0.04 / 1.0625
	# = 0.0376471; at n.v = 0.5: grazing = 0.5 + 0.04 = 0.54, (0.5)^5 =
	# 0.03125, lerp = 0.04 + 0.5 x 0.03125 = 0.055625, / 1.0625 = 0.0523529
	reflect-shade -fa -m none --final=unity --diffuse=off --env=sky.rfl px.txt >u.txt &&
	column u.txt R G B >got &&
	cat >expect <<-\EOF &&
	0.941176 0.941176 0.941176
	0.5 0.5 0.5
	0.0376471 0.0376471 0.0376471
	0.941176 0.941176 0.941176
	0.0523529 0.0523529 0.0523529
	EOF
	cmp_numbers expect got 2e-6
'

test_expect_success 'split-sum is the default --final, spec x (F0 A + B)' '
	reflect-shade -fa -m none --final --diffuse=off --env=sky.rfl px.txt >s.txt &&
	reflect-shade -fa -m none --final=split-sum --diffuse=off --env=sky.rfl px.txt >s2.txt &&
	column s.txt R G B >a && column s2.txt R G B >b && cmp a b &&
	# a white metal loses energy to single scattering, the more the
	# rougher: E = A + B, 0.916 at roughness 0.5, 0.307 at 1
	awk "NR == 1 { e1 = \$1 } NR == 2 { e2 = \$1 }
		END { exit !(e1 > 0.9 && e1 < 0.93 && e2 > 0.29 && e2 < 0.32) }" a
'

test_expect_success 'hdrp: (F0 A + B)(1 + F0 (1/E - 1)): a white metal keeps all its energy' '
	reflect-shade -fa -m none --final=hdrp --diffuse=off --env=sky.rfl px.txt >h.txt &&
	column h.txt R >h &&
	column s.txt R >e &&
	# rows 1, 2, 4: F0 = 1, so E (1 + 1/E - 1) = 1; rows 3 and 5 from the
	# split sum of the same pixel and the white metal beside it (E)
	paste -d" " h e | awk "
		NR == 1 || NR == 2 || NR == 4 { if (\$1 < 0.999999 || \$1 > 1.000001) bad++ }
		NR == 1 { e1 = \$2 } NR == 4 { e4 = \$2 }
		NR == 3 { w = \$2 * (1 + 0.04 * (1 / e1 - 1)); if (\$1 - w > 1e-6 || w - \$1 > 1e-6) bad++ }
		NR == 5 { w = \$2 * (1 + 0.04 * (1 / e4 - 1)); if (\$1 - w > 1e-6 || w - \$1 > 1e-6) bad++ }
		END { exit bad > 0 }"
'

test_expect_success 'an unknown --final is refused' '
	test_expect_code 1 reflect-shade --final=unreal --env=sky.rfl px.txt >/dev/null 2>err &&
	test_grep "final: .unreal. is not split-sum, unity or hdrp" err
'

# Diffuse light: E = pi under a sky of radiance 1, so albedo (1 -
# metallic) E / pi = 0.5 for the dielectric rows (3 and 5), 0 for metal.
test_expect_success '--diffuse=on: albedo (1 - metallic) E(N) / pi, added to R G B' '
	reflect-shade -fa -m none --final --diffuse=on --env=sky.rfl px.txt >d.txt &&
	test_grep "^CHANNELS=.* R G B diffuse.R diffuse.G diffuse.B$" d.txt &&
	column d.txt diffuse.R diffuse.G diffuse.B >got &&
	printf "0 0 0\n0 0 0\n0.5 0.5 0.5\n0 0 0\n0.5 0.5 0.5\n" >expect &&
	cmp_numbers expect got 1e-4 &&
	column d.txt R >with && column s.txt R >without &&
	paste -d" " with without got | awk "{ d = \$1 - \$2 - \$3; if (d > 1e-5 || d < -1e-5) bad++ }
		END { exit bad > 0 }" &&
	! grep "^CHANNELS=.*diffuse" s.txt &&
	# on by default with --final
	reflect-shade -fa -m none --final --env=sky.rfl px.txt >default.txt &&
	column default.txt diffuse.R >dflt && column d.txt diffuse.R >on && cmp dflt on
'

# Box-projected diffuse light: from the capture point itself it is E at N;
# from elsewhere it reads another direction.  Level 0 of this chain holds
# 10 + f on face f, so E changes with the direction.
test_expect_success '--diffuse-projection=box: E along N projected from P' '
	level_chain faces.rfl 16 5 unity 10 &&
	stream b.txt 2 1 "P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z D.X D.Y D.Z roughness metallic" \
		PROBE_BOX="-3 0 -2 3 3 2" PROBE_CENTER="0 1.5 0" <<-\EOF &&
	0 1.5 0 0.6 0.8 0 0 1 0 0 1 0 0.5 0
	2.5 0.2 1.5 0.6 0.8 0 0 1 0 0 1 0 0.5 0
	EOF
	reflect-shade -fa -m none --final --diffuse=on --env=faces.rfl b.txt >off.txt &&
	reflect-shade -fa -m none --final --diffuse=on --diffuse-projection=box \
		--env=faces.rfl b.txt >box.txt &&
	column off.txt diffuse.R >a && column box.txt diffuse.R >b &&
	sed -n 1p a >a1 && sed -n 1p b >b1 && cmp_numbers a1 b1 1e-6 &&
	sed -n 2p a >a2 && sed -n 2p b >b2 && ! cmp_numbers a2 b2 1e-3 2>/dev/null
'

test_expect_success 'bad --diffuse values are refused' '
	test_expect_code 1 reflect-shade --final --diffuse=maybe --env=sky.rfl px.txt 2>err >/dev/null &&
	test_grep "diffuse: .maybe. is not on or off" err &&
	test_expect_code 1 reflect-shade --final --diffuse-projection=sphere --env=sky.rfl px.txt \
		2>err >/dev/null &&
	test_grep "diffuse-projection: .sphere. is not off or box" err
'

test_expect_success 'reflect-prefilter keeps the coefficients with the chain, and shade uses them' '
	reflect-prefilter --size=16 -o room.rfl 2>/dev/null &&
	reflect-info room.rfl | grep "^	IRRADIANCE_SH9=" >key &&
	test_line_count 1 key &&
	test "$(sed "s/.*=//" key | wc -w)" = 27 &&
	# the same numbers as projecting level 0 on load: the key removed
	sed "/^IRRADIANCE_SH9=/d" room.rfl >bare.rfl &&
	reflect-shade -h -m none --final --diffuse=on --env=room.rfl px.txt >a.raw &&
	reflect-shade -h -m none --final --diffuse=on --env=bare.rfl px.txt >b.raw &&
	cmp a.raw b.raw &&
	# and they are read: zero coefficients give no diffuse light
	zeros=$(printf "0 %.0s" $(seq 27)) &&
	sed "s/^IRRADIANCE_SH9=.*/IRRADIANCE_SH9=$zeros/" room.rfl >zero.rfl &&
	reflect-shade -fa -m none --final --diffuse=on --env=zero.rfl px.txt >z.txt &&
	column z.txt diffuse.R | sort -u >got && echo 0 >expect && diff expect got &&
	sed "s/^IRRADIANCE_SH9=.*/IRRADIANCE_SH9=1 2 x/" room.rfl >bad.rfl &&
	test_expect_code 1 reflect-shade -m none --final --diffuse=on --env=bad.rfl px.txt >/dev/null 2>err &&
	test_grep "IRRADIANCE_SH9.*needs 27 finite float numbers" err
'

# 1e39 is a finite double and an infinite float: the diffuse light was
# inf with exit 0.
test_expect_success 'IRRADIANCE_SH9 past the float range is refused' '
	big=$(printf "1e39 %.0s" $(seq 27)) &&
	sed "s/^IRRADIANCE_SH9=.*/IRRADIANCE_SH9=$big/" room.rfl >big.rfl &&
	test_expect_code 1 reflect-shade -m none --final --diffuse=on --env=big.rfl px.txt \
		>out.rfl 2>err &&
	test_one_line_message reflect-shade err &&
	test_grep "IRRADIANCE_SH9.*needs 27 finite float numbers" err
'

test_expect_success 'the diffuse light is the same bytes at 1 and 2 threads' '
	reflect-gbuffer -x 48 -y 27 | reflect-project >scene.rfl &&
	for f in split-sum unity hdrp
	do
		for p in off box
		do
			reflect-shade -h -j 1 -m hdrp --final=$f --diffuse-projection=$p \
				--env=room.rfl scene.rfl >one.raw &&
			reflect-shade -h -j 2 -m hdrp --final=$f --diffuse-projection=$p \
				--env=room.rfl scene.rfl >two.raw &&
			cmp one.raw two.raw || return 1
		done || return 1
	done
'

# An EXR chain stores its texels as halves; its coefficients come from
# the float level 0 as the stream's do, so the diffuse light is the same
# to the last bit, where projecting the half texels would not be.
test_expect_success 'an EXR chain keeps the same coefficients as an attribute' '
	reflect-prefilter --size=16 -o room.exr 2>/dev/null &&
	tr -c "[:print:]" "\n" <room.exr | grep "reflect:irradianceSH9" >attr &&
	test_line_count 1 attr &&
	reflect-shade -fa -m none --final --diffuse=on --env=room.exr px.txt >x.txt &&
	reflect-shade -fa -m none --final --diffuse=on --env=room.rfl px.txt >r.txt &&
	column x.txt diffuse.R >xd && column r.txt diffuse.R >rd &&
	cmp xd rd
'

test_done
