#!/bin/sh
test_description='-m MODE --help tells one mode; --help names the modes found; did you mean'
. "$srcdir/tests/lib.sh"

B=$builddir/plugins/.libs
P=$REFLECT_TEST_PLUGINS
tab=$(printf '\t')

# -m MODE --help in every tool that takes -m: the usage with the mode,
# its summary, file, channels (optional ones apart), parameters with
# default and range, and its man page; exit 0, nothing on stderr.
test_expect_success 'reflect-shade -m footprint --help: reads, optional reads, parameters' '
	reflect-shade -m footprint --help >out 2>err &&
	test_line_count 0 err &&
	test_grep "^usage: reflect-shade -m footprint\[:KEY=VALUE\.\.\.\] \[options\] \[file\]$" out &&
	test_grep "^footprint${tab}the GGX lobe.s footprint on the box as the probe sees it, read in up to four taps$" out &&
	test_grep "^  file: $B/shade-footprint\.so (version 1\.2, plugin ABI 1\.3, reflect developers, MIT)$" out &&
	test_grep "^  found in: REFLECT_PLUGIN_PATH$" out &&
	test_grep "^  reads: P\.X P\.Y P\.Z N\.X N\.Y N\.Z V\.X V\.Y V\.Z roughness$" out &&
	test_grep "^  reads when present: Ng\.X Ng\.Y Ng\.Z$" out &&
	test_grep "^  writes: spec\.R spec\.G spec\.B$" out &&
	test_grep "^    taps=4${tab}cubemap reads a pixel at most, along the footprint.s long axis (integer \[1, 4\])$" out &&
	test_grep "^    lobe=measured${tab}.* (measured|round)$" out &&
	test_grep "^  man page: none beside the file (reflect-plugin(7) says where one goes)$" out &&
	! grep -e "--env=FILE" out
'

test_expect_success '--help before -m, parameters given, every tool with -m' '
	reflect-shade --help -m approx:distance=3 >out 2>err &&
	test_line_count 0 err &&
	test_grep "^usage: reflect-shade -m approx\[" out &&
	test_grep "^    distance=6${tab}hit distance in world units at which the material.s roughness is reached (\[1e-06, 1e+06\])$" out &&
	for t in project:box occlude:box accumulate:ema filter:atrous
	do
		tool=reflect-${t%%:*} mode=${t#*:} &&
		$tool -m $mode --help >out 2>err || return 1
		test_line_count 0 err &&
		test_grep "^usage: $tool -m $mode\[:KEY=VALUE\.\.\.\] \[options\] \[file\]$" out &&
		test_grep "^$mode${tab}" out &&
		test_grep "^  found in: REFLECT_PLUGIN_PATH$" out || return 1
	done &&
	reflect-accumulate -m ema --help >out &&
	test_grep "^  state of each value: value variance" out &&
	reflect-filter -m atrous --help >out &&
	test_grep "^  guided by: " out
'

test_expect_success '-m MODE --help of a mode that is not there: did you mean, exit 1' '
	test_expect_code 1 reflect-shade -m aprox --help >out 2>err &&
	test_line_count 0 out &&
	test_one_line_message reflect-shade err &&
	test_grep "^reflect-shade: unknown shade mode .aprox.: no shade-aprox\.so or aprox\.so in .$B.; did you mean .approx.? (-l lists the modes)$" err
'

# The list of modes in --help is what the search path holds: a mode
# added there is named, one of another kind is not.
test_expect_success '--help names the modes of the search path, the default apart' '
	reflect-shade --help >out 2>err &&
	test_line_count 0 err &&
	test_grep "^  -m MODE\[:K=V\.\.\.\]  the shade mode, default approx; -m MODE --help tells$" out &&
	test_grep "^      one, -l lists them all\. Modes: approx, footprint, godot, hdrp, none,$" out &&
	test_grep "^      raytraced$" out &&
	! grep "none, approx (default), hdrp, godot" out &&
	reflect-project --help >out &&
	test_grep "Modes: bevel, box, infinite$" out &&
	REFLECT_PLUGIN_PATH="$B:$P" reflect-project --help >out &&
	test_grep "Modes: bad_out, bail_at_row, bevel,$" out &&
	test_grep "^      bevel_original, box, crash, echo_params, infinite, print_stdout,$" out &&
	! grep -e "approx" out &&
	! grep "print_stdout: loaded" out &&
	REFLECT_PLUGIN_PATH= reflect-occlude --help >out &&
	test_grep "Modes: none found (-l says where they are looked for)$" out
'

test_expect_success 'a misspelt mode: did you mean, only when one is close' '
	for t in "shade aprox approx" "shade hdpr hdrp" "project boxx box" \
		"occlude horizn horizon" "filter atros atrous" "accumulate men mean"
	do
		set -- $t &&
		test_expect_code 1 reflect-$1 -m $2 </dev/null >out 2>err || return 1
		test_one_line_message reflect-$1 err &&
		test_grep "; did you mean .$3.? (-l lists the modes)$" err || return 1
	done &&
	test_expect_code 1 reflect-shade -m wobbly </dev/null 2>err &&
	test_grep "^reflect-shade: unknown shade mode .wobbly.: no shade-wobbly\.so or wobbly\.so in .$B. (-l lists the modes)$" err &&
	test_expect_code 1 reflect-project -m approx </dev/null 2>err &&
	! grep "did you mean" err
'

test_expect_success 'a misspelt parameter: did you mean, with the list' '
	test_expect_code 1 reflect-shade -m approx:distanse=3 </dev/null >out 2>err &&
	test_one_line_message reflect-shade err &&
	test_grep "^reflect-shade: mode .approx. has no parameter .distanse.; did you mean .distance.? (it has: clamp, distance)$" err &&
	test_expect_code 1 reflect-shade -m approx:zzz=3 </dev/null 2>err &&
	test_grep "^reflect-shade: mode .approx. has no parameter .zzz. (it has: clamp, distance)$" err
'

# A mode's man page lies beside its file (reflect-plugin(7)):
# reflect-mode-KIND-NAME.7 first, else reflect-mode-NAME.7.
test_expect_success '-m MODE --help and -l name the man page beside the file' '
	mkdir mine &&
	cp "$P/echo_params.so" mine/ &&
	REFLECT_PLUGIN_PATH="$PWD/mine" reflect-project -m echo_params --help >out &&
	test_grep "^  man page: none beside the file" out &&
	echo ".TH X 7" >mine/reflect-mode-echo_params.7 &&
	REFLECT_PLUGIN_PATH="$PWD/mine" reflect-project -m echo_params --help >out &&
	test_grep "^  man page: $PWD/mine/reflect-mode-echo_params\.7$" out &&
	REFLECT_PLUGIN_PATH="$PWD/mine" reflect-project -l >out &&
	test_grep "^  man page: $PWD/mine/reflect-mode-echo_params\.7$" out &&
	echo ".TH X 7" >mine/reflect-mode-projection-echo_params.7 &&
	REFLECT_PLUGIN_PATH="$PWD/mine" reflect-project -m echo_params --help >out &&
	test_grep "^  man page: $PWD/mine/reflect-mode-projection-echo_params\.7$" out &&
	reflect-project -m "$PWD/mine/echo_params.so" --help >out &&
	test_grep "^  found in: a path given to -m$" out
'

test_done
