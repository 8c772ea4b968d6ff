#!/bin/sh
test_description='reflect-shade refuses bad input with one clear line'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

test_expect_success 'setup' '
	level_chain chain.rfl 8 4 unity &&
	printf "0.5 2 3 0 1 0 0 1 0 0 0 1\n" |
	stream full.txt 1 1 "roughness hit.dist probe.dist N.X N.Y N.Z V.X V.Y V.Z D.X D.Y D.Z"
'

test_expect_success 'a channel the mode reads is missing: the message names it and the mode' '
	printf "0.5 0 0 1\n" | stream nohit.txt 1 1 "roughness D.X D.Y D.Z" &&
	test_expect_code 1 reflect-shade -m approx nohit.txt >out 2>err &&
	test_one_line_message reflect-shade err &&
	test_grep "input has no channel '"'"'hit.dist'"'"' (mode '"'"'approx'"'"' reads roughness hit.dist)" err &&
	! test -s out
'

test_expect_success 'each mode names what it misses' '
	printf "0.5 2 0 0 1\n" | stream few.txt 1 1 "roughness hit.dist D.X D.Y D.Z" &&
	test_expect_code 1 reflect-shade -m hdrp few.txt 2>err &&
	test_grep "'"'"'probe.dist'"'"' (mode '"'"'hdrp'"'"'" err &&
	test_expect_code 1 reflect-shade -m godot few.txt 2>err &&
	test_grep "'"'"'N.X'"'"' (mode '"'"'godot'"'"'" err &&
	printf "0 0 1\n" | stream norough.txt 1 1 "D.X D.Y D.Z" &&
	test_expect_code 1 reflect-shade -m none norough.txt 2>err &&
	test_grep "'"'"'roughness'"'"' (mode '"'"'none'"'"'" err
'

test_expect_success 'no lookup direction: the message names D.X and reflect-project' '
	printf "0.5 2\n" | stream nod.txt 1 1 "roughness hit.dist" &&
	test_expect_code 1 reflect-shade -m approx nod.txt 2>err &&
	test_one_line_message reflect-shade err &&
	test_grep "input has no channel '"'"'D.X'"'"'.*reflect-project" err
'

test_expect_success 'a missing channel fails at once, before any prefiltering' '
	test_expect_code 1 reflect-shade -m approx nod.txt 2>err &&
	! grep prefiltering err
'

test_expect_success '--final without N names it' '
	printf "0.5 0 0 1\n" | stream non.txt 1 1 "roughness D.X D.Y D.Z" &&
	test_expect_code 1 reflect-shade -m none --final --env=chain.rfl non.txt 2>err &&
	test_one_line_message reflect-shade err &&
	test_grep "'"'"'N.X'"'"'" err
'

test_expect_success 'unknown mode' '
	test_expect_code 1 reflect-shade -m nosuchmode full.txt >out 2>err &&
	test_one_line_message reflect-shade err &&
	test_grep "nosuchmode" err &&
	! test -s out
'

test_expect_success 'a projection mode is not a shade mode' '
	test_expect_code 1 reflect-shade -m box full.txt 2>err &&
	test_one_line_message reflect-shade err
'

for p in approx:clamp=2 approx:clamp=0.5 approx:distance=0 approx:distance=-1 \
	approx:nosuch=1 godot:power=-1 godot:power=65 godot:power=x godot:distance=0 \
	none:clamp=1 hdrp:power=4
do
	test_expect_success "bad parameter $p" '
		test_expect_code 1 reflect-shade -m $p --env=chain.rfl full.txt >out 2>err &&
		test_one_line_message reflect-shade err &&
		! test -s out
	'
done

for o in --mapping=foo --steps=0 --steps=x --samples=0 --samples=1.5 --seed=-1 \
	--layout=round --srgb=maybe --box=1,2,3 --center=1,2 --box-projection=maybe
do
	test_expect_success "bad option $o" '
		test_expect_code 1 reflect-shade $o --env=chain.rfl full.txt >out 2>err &&
		test_one_line_message reflect-shade err &&
		! test -s out
	'
done

test_expect_success 'an environment that does not exist' '
	test_expect_code 1 reflect-shade --env=no-such.exr full.txt >out 2>err &&
	test_one_line_message reflect-shade err &&
	test_grep "no-such.exr" err
'

test_expect_success 'PROBE_ENV naming a missing file' '
	printf "0.5 2 3 0 1 0 0 1 0 0 0 1\n" |
	stream env.txt 1 1 "roughness hit.dist probe.dist N.X N.Y N.Z V.X V.Y V.Z D.X D.Y D.Z" \
		"PROBE_ENV=gone.rfl" &&
	test_expect_code 1 reflect-shade env.txt 2>err &&
	test_one_line_message reflect-shade err &&
	test_grep "gone.rfl" err
'

test_expect_success 'a chain prefiltered with another mapping is refused, unless --prefiltered' '
	test_expect_code 1 reflect-shade --mapping=linear --env=chain.rfl full.txt 2>err &&
	test_one_line_message reflect-shade err &&
	test_grep "mapping unity" err &&
	test_expect_code 1 reflect-shade --steps=6 --env=chain.rfl full.txt 2>err &&
	test_one_line_message reflect-shade err &&
	reflect-shade -fa --mapping=unity --steps=3 --env=chain.rfl full.txt >/dev/null &&
	reflect-shade -fa --prefiltered --mapping=linear --env=chain.rfl full.txt >out.txt &&
	test_grep "^ENV_MAPPING=linear$" out.txt
'

test_expect_success 'a truncated stream' '
	head -c $(($(wc -c <full.txt) - 8)) full.txt >cut.txt &&
	test_expect_code 1 reflect-shade --env=chain.rfl cut.txt >/dev/null 2>err &&
	test_one_line_message reflect-shade err
'

test_expect_success 'two files' '
	test_expect_code 1 reflect-shade full.txt full.txt 2>err &&
	test_grep "^usage: " err
'

test_done
