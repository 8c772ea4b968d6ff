#!/bin/sh
test_description='reflect-shade: the environment it picks, threads, listing'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"
SQ="'"

test_expect_success 'setup: a small scene, projected, and a small prefiltered room' '
	reflect-gbuffer -x 40 -y 24 -n 2 | reflect-project >scene.rfl &&
	reflect-prefilter --size=32 -s 8 -o room.rfl 2>/dev/null &&
	level_chain chain.rfl 8 4 unity
'

for m in none approx approx:clamp=0 hdrp godot
do
	test_expect_success "$m: the bytes do not depend on the thread count" '
		reflect-shade -h -j1 -m $m --final --env=room.rfl scene.rfl >j1 &&
		reflect-shade -h -j2 -m $m --final --env=room.rfl scene.rfl >j2 &&
		reflect-shade -h -j7 -m $m --final --env=room.rfl scene.rfl >j7 &&
		test $(wc -c <j1) -eq $((2 * 40 * 24 * (23 + 8 + 4 + 3 + 3) * 4)) &&
		cmp j1 j2 &&
		cmp j1 j7 &&
		REFLECT_THREADS=3 reflect-shade -h -m $m --final --env=room.rfl scene.rfl >j3 &&
		cmp j1 j3
	'
done

# On x86-64 with AVX2 the pass makes its reads eight at a time; the plain
# loop (REFLECT_SIMD=off) rounds differently, by far less than 1e-3 of
# the room's radiance, and both see walls (mask 0) and mirrors alike.
test_expect_success 'vector and plain reads of the environment agree' '
	reflect-gbuffer -x 61 -y 37 | reflect-project >odd.rfl &&
	reflect-shade -h -f a -m approx --final --env=room.rfl odd.rfl >vector &&
	REFLECT_SIMD=off reflect-shade -h -f a -m approx --final --env=room.rfl odd.rfl >plain &&
	test $(wc -l <plain) -eq $((61 * 37)) &&
	test_cmp_numbers plain vector 2e-3
'

# Rows of 1500 pixels of 38 channels: a block of 4 MB holds 18 of them,
# so a frame of 50 rows is three blocks, read ahead into two buffers in
# turn.
test_expect_success 'several blocks and frames: any thread count, every frame alike' '
	reflect-gbuffer -x 1500 -y 50 -n 2 | reflect-project >wide.rfl &&
	reflect-shade -h -j1 -m approx --final --env=room.rfl wide.rfl >w1 &&
	reflect-shade -h -j2 -m approx --final --env=room.rfl wide.rfl >w2 &&
	frame=$((1500 * 50 * 41 * 4)) &&
	test $(wc -c <w1) -eq $((2 * frame)) &&
	cmp w1 w2 &&
	# The two frames have the same camera: the same bytes (nothing of a
	# frame or of its read-ahead blocks carries over to the next).
	head -c $frame w1 >f1 &&
	tail -c $frame w1 >f2 &&
	cmp f1 f2
'

test_expect_success 'the output has no NaN or Inf on the default scene' '
	reflect-shade -m godot --final --env=room.rfl scene.rfl | reflect-info -s >stats &&
	awk "\$1 ~ /^(spec\.[RGB]|R|G|B|roughness\.eff)\$/ { n++; if (\$5 != 0 || \$6 != 0) bad = 1 }
		END { exit bad || n != 2 * 7 }" stats
'

test_expect_success 'no --env: the embedded room, prefiltered once for all frames' '
	reflect-shade -fa -m none --samples=4 scene.rfl >out 2>err &&
	test_line_count 1 err &&
	test_grep "^reflect-shade: prefiltering the environment (256x256 per face, 7 levels)$" err &&
	test $(grep -c "^ENV_STEPS=6$" out) -eq 2 &&
	test $(grep -c "^ENV_MAPPING=unity$" out) -eq 2
'

test_expect_success '--size and a raw environment: the message says so' '
	reflect-shade -m none --samples=4 --size=64 scene.rfl >/dev/null 2>err &&
	test_grep "(64x64 per face, 7 levels)" err &&
	reflect-shade -m none --samples=4 --size=16 scene.rfl >/dev/null 2>err &&
	test_grep "(16x16 per face, 5 levels)" err
'

test_expect_success 'a prefiltered chain is used as it is: no prefiltering, its steps' '
	reflect-shade -fa -m none --env=chain.rfl scene.rfl >out 2>err &&
	! test -s err &&
	test_grep "^ENV_STEPS=3$" out
'

# A DDS or KTX cube without mips is an environment, as a cube image is:
# it is prefiltered, so that a rough surface reads it blurred.  Taken as a
# chain of one level, every roughness read the sharp level 0.  Face f of
# the files holds (f, 1, 2) everywhere, as does the EXR cube made here.
test_expect_success 'a DDS or KTX cube of one level is prefiltered as an EXR cube is' '
	"$builddir/tests/mkdds" one.dds 16 1 &&
	"$builddir/tests/mkktx" one.ktx2 ktx2-rgba32f 16 1 &&
	awk "BEGIN {
		printf \"#?REFLECT1\nNCOLS=16\nNROWS=96\nNCOMP=3\nCHANNELS=R G B\nFORMAT=ascii\n\n\"
		for (i = 0; i < 16 * 96; i++) printf \"%d\t1\t2\n\", int(i / 256)
	}" >one.txt &&
	reflect-export -c all -o one.exr one.txt &&
	reflect-shade -h -m hdrp --final --env=one.exr scene.rfl >exr.raw 2>err &&
	test_grep "prefiltering the environment ${SQ}one.exr${SQ} (16x16 per face, 5 levels)" err &&
	for f in one.dds one.ktx2
	do
		reflect-shade -h -m hdrp --final --no-cache --env=$f scene.rfl >got.raw 2>err &&
		test_grep "prefiltering the environment ${SQ}$f${SQ}" err &&
		cmp exr.raw got.raw &&
		# as a scene names it (PROBE_ENV), and as reflect-prefilter reads it
		sed "s/^PROBE_ENV=default$/PROBE_ENV=$f/" scene.rfl >named.rfl &&
		reflect-shade -h -m hdrp --final named.rfl >got.raw 2>/dev/null &&
		cmp exr.raw got.raw &&
		reflect-prefilter -fa -s 4 $f >chain.txt 2>err &&
		! test_grep already err &&
		test "$(grep "^LEVELS=" chain.txt | sort -u)" = "LEVELS=5" &&
		test "$(grep "^PREFILTER=" chain.txt | sort -u)" = "PREFILTER=ggx" || return 1
	done
'

# --prefiltered takes the file's levels as they are: its one level is
# read at every roughness, as asked.
test_expect_success '--prefiltered takes a cube of one level as it is' '
	reflect-shade -h -m hdrp --final --prefiltered --env=one.dds scene.rfl >got.raw 2>err &&
	! test_grep prefiltering err &&
	! cmp -s exr.raw got.raw &&
	reflect-shade -h -m hdrp --final --prefiltered --env=one.exr scene.rfl >exr1.raw &&
	cmp exr1.raw got.raw
'

test_expect_success 'PROBE_ENV names the environment when --env is absent' '
	test_grep "^PROBE_ENV=default$" scene.rfl &&
	sed "s/^PROBE_ENV=default$/PROBE_ENV=chain.rfl/" scene.rfl >named.rfl &&
	reflect-shade -fa -m none named.rfl >out 2>err &&
	! test -s err &&
	test_grep "^ENV_STEPS=3$" out &&
	reflect-shade -fa -m none --env=chain.rfl scene.rfl >want &&
	column out spec.R spec.G spec.B >a &&
	column want spec.R spec.G spec.B >b &&
	cmp a b
'

test_expect_success '--env wins over PROBE_ENV and replaces it' '
	reflect-shade -fa -m none --env=room.rfl named.rfl >out 2>err &&
	! test -s err &&
	test_grep "^PROBE_ENV=room.rfl$" out &&
	test_grep "^ENV_STEPS=5$" out
'

test_expect_success '-v says which plugin and which environment' '
	reflect-shade -v -m hdrp --env=chain.rfl scene.rfl >/dev/null 2>err &&
	test_grep "^reflect-shade: mode .hdrp. from .*/shade-hdrp\.so.$" err &&
	test_grep "^reflect-shade: environment .chain.rfl.: 8 texels, 4 levels, mapping unity, steps 3$" err
'

test_expect_success '-l lists the four modes and their parameters' '
	reflect-shade -l >list &&
	for m in none approx hdrp godot
	do
		test_grep "^$m	" list || return 1
	done &&
	test_grep "^    clamp=1	" list &&
	test_grep "^    power=4	" list &&
	test_grep "^    distance=6	" list &&
	test_grep "writes: roughness.eff$" list
'

test_expect_success '--help and -V' '
	reflect-shade --help >help &&
	test_grep "^usage: reflect-shade" help &&
	reflect-shade -V >version &&
	test -s version
'

# sample() and sample_many() read through the pass's own kernels (plugin
# ABI 1.1), every read through the same one (a batch's tail padded to
# eight): a one-tap mode at the pass's D and lod gets none's bytes
# (rf_cubemap_sample, before, differed by 4.5e-5).
test_expect_success 'a mode that samples through the host services equals none' '
	radiance="$REFLECT_TEST_PLUGINS/shade_radiance.so" &&
	reflect-shade -fa -m none --env=room.rfl scene.rfl >none.txt &&
	reflect-shade -fa -m "$radiance" --env=room.rfl scene.rfl >radiance.txt &&
	test_grep "^CHANNELS=.* spec.R spec.G spec.B$" radiance.txt &&
	! grep "roughness.eff" radiance.txt &&
	column none.txt spec.R spec.G spec.B >a &&
	column radiance.txt spec.R spec.G spec.B >b &&
	test_line_count $((2 * 40 * 24)) b &&
	cmp a b &&
	reflect-shade -fa -m "$REFLECT_TEST_PLUGINS/shade_radiance_many.so" --env=room.rfl \
		scene.rfl >many.txt &&
	column many.txt spec.R spec.G spec.B >m &&
	cmp a m
'

test_expect_success 'a mode of plugin ABI 1.0 that samples itself still does' '
	reflect-shade -fa -m "$REFLECT_TEST_PLUGINS/shade_radiance_1_0.so" \
		--env=room.rfl scene.rfl >legacy.txt &&
	test_grep "^CHANNELS=.* spec.R spec.G spec.B$" legacy.txt &&
	! grep "roughness.eff" legacy.txt &&
	column legacy.txt spec.R spec.G spec.B >c &&
	test_line_count $((2 * 40 * 24)) c &&
	cmp b c
'

test_expect_success 'a mode that writes neither roughness.eff nor spec is refused' '
	test_expect_code 1 reflect-shade \
		-m "$REFLECT_TEST_PLUGINS/shade_no_roughness.so" scene.rfl 2>err &&
	test_one_line_message reflect-shade err &&
	test_grep "a shade mode must output roughness.eff (or, with RF_PLUGIN_RADIANCE, spec.R spec.G spec.B); add it and rebuild the plugin" err
'

test_expect_success 'a closed pipe downstream ends the tool quietly' '
	reflect-shade -m none --env=chain.rfl scene.rfl 2>err | head -c 10 >/dev/null &&
	! test -s err
'

test_done
